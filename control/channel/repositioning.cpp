#include "control/channel/repositioning.hpp"

#include <algorithm>
#include <cmath>

#include "control/channel/channel_config.hpp"
#include "control/channel/further_spindle_control.hpp"
#include "control/channel/program_frames.hpp"
#include "control/nc/modal_g_codes.hpp"

namespace vmt::control::channel {
namespace {

bool Endless(const axes::AxisParameters& axis) {
  return axis.rotary && !(axis.travel_max > axis.travel_min);
}

}  // namespace

const char* ToString(ReposFunction f) {
  switch (f) {
    case ReposFunction::kNone:
      return "none";
    case ReposFunction::kRepositioning:
      return "repositioning";
    case ReposFunction::kRestart:
      return "restart";
  }
  return "?";
}

double ReposDistanceToGo(const axes::AxisParameters& axis, double target, double actual) {
  const double d = target - actual;
  if (!Endless(axis)) return d;
  return d - 360 * std::round(d / 360);  // the short way round, -180..180
}

bool WithinReposWindow(const axes::AxisParameters& axis, double target, double actual) {
  return std::abs(ReposDistanceToGo(axis, target, actual)) <= axis.repos_window + 1e-9;
}

bool WithinFictiveWindow(const axes::AxisParameters& x_axis, nc::FictivePoint target,
                         nc::FictivePoint actual) {
  return std::hypot(target.x1 - actual.x1, target.y1 - actual.y1) <= x_axis.repos_window + 1e-9;
}

ReposZone FictiveZoneOf(double target, double start) {
  if (std::isnan(target)) return {};
  return {true, std::min(target, start), std::max(target, start)};
}

ReposZone ZoneOf(const axes::AxisParameters& axis, double target, double start) {
  if (Endless(axis) || std::isnan(target)) return {};
  return {true, std::min(target, start), std::max(target, start)};
}

bool KeyRestoresSpindle(int spindle_m_before, int key) {
  switch (spindle_m_before) {
    case 3:
    case 4:
      return key == 3 || key == 4;
    case 5:
      return key == 5;
    case 19:
      return key == 19;
  }
  return false;
}

int SpindleMOf(const DriveSetpoint& command) {
  if (command.mode == DriveMode::kPosition) return 19;
  return command.value > 0 ? 3 : command.value < 0 ? 4 : 5;
}

bool OutOfItsMode(const axes::HeadstockChangeover* headstock, int rotary_axis, size_t axis) {
  return headstock && static_cast<int>(axis) == rotary_axis &&
         headstock->mode() != axes::HeadstockMode::kRotary;
}

void Repositioning::Interrupt(Interruption interruption, const std::vector<double>& commanded) {
  data_.interruption = std::move(interruption);
  data_.start = commanded;
}

void Repositioning::MoveInterruptionPoint(const std::vector<double>& point) {
  if (data_.interruption) data_.interruption->point = point;
}

void Repositioning::Request(bool repositioning, bool restart) {
  data_.request = repositioning && !restart   ? ReposFunction::kRepositioning
                  : restart && !repositioning ? ReposFunction::kRestart
                                              : ReposFunction::kNone;
}

void Repositioning::StartRun(bool subroutine) {
  data_.rerun = false;
  data_.run = true;
  data_.closing = false;
  data_.finish = !subroutine;
}

void Repositioning::Clear() {
  data_.interruption.reset();
  data_.function = ReposFunction::kNone;
  data_.crest = false;
  data_.run = data_.closing = data_.finish = data_.rerun = false;
}

bool Repositioning::Fictive(const ReposView& v, int& x, int& c) const {
  x = c = -1;
  if (!data_.interruption || data_.interruption->modal.transformation != nc::Transformation::kFace)
    return false;
  for (size_t a = 0; a < v.config.axes.size(); ++a) {
    if (v.config.axes[a].name == "X") x = static_cast<int>(a);
    if (v.config.axes[a].name == "C") c = static_cast<int>(a);
  }
  return x >= 0 && c >= 0 && !std::isnan(data_.interruption->point[x]) &&
         !std::isnan(data_.interruption->point[c]);
}

namespace {

// The interrupted block's translation with the tables as they are now (2.5: an edit during the
// interruption moves the contour).
std::vector<double> TranslationNow(const ReposView& v, const Interruption& i) {
  std::vector<double> t;
  TranslationOf(v.config, v.zero_offsets, v.shift, i.modal, ActiveEdge(v.tools, i.modal), t);
  return t;
}

}  // namespace

nc::FictivePoint Repositioning::FictiveOf(const ReposView& v, const std::vector<double>& position,
                                          int x, int c) const {
  // Program coordinates of the interrupted block's frame, as its X1/Y1 were programmed.
  const std::vector<double> t = TranslationNow(v, *data_.interruption);
  return nc::MachineToFace(position[x] - t[x], position[c] - t[c]);
}

std::vector<double> Repositioning::Target(const ReposView& v) const {
  std::vector<double> target(v.config.axes.size(), std::nan(""));
  if (!data_.interruption) return target;
  const Interruption& i = *data_.interruption;
  const std::vector<double>& base =
      data_.function == ReposFunction::kRestart ? i.block_start : i.point;
  // 2.5: zero offset and tool edits during the interruption move the interruption point and
  // the block start with the contour.
  const std::vector<double> now = TranslationNow(v, i);
  for (size_t a = 0; a < target.size(); ++a) target[a] = base[a] + (now[a] - i.translation[a]);
  return target;
}

bool Repositioning::ToolStorageRestored(const ReposView& v) const {
  // 6.2 / 7.3: only with Bxx.045 'Reposition Tool Storage Axis' = yes.
  if (!v.config.process.reposition_tool_storage || !v.tool_storage || !data_.interruption)
    return true;
  // 3.4: an endless one compares the short way round, however often it has turned.
  return std::abs(ReposDistanceToGo(v.config.tool_storage, data_.interruption->tool_storage,
                                    *v.tool_storage)) <= kToolStorageWindow;
}

bool Repositioning::SpindleRelevant(const ReposView& v) const {
  // 7.3: all spindles; a spindle with rotary axis capability if it was in spindle mode.
  if (v.config.spindle_drive < 0 || !data_.interruption) return false;
  return !v.headstock || data_.interruption->headstock_mode != axes::HeadstockMode::kRotary;
}

bool Repositioning::SpindleRestored(const ReposView& v, const AmplifierTelegram& at) const {
  const DriveSetpoint& before = data_.interruption->spindle;
  const DriveSetpoint& command = v.spindle.command;
  if (v.headstock && v.headstock->mode() != axes::HeadstockMode::kSpindle) return false;
  if (command.mode != before.mode || std::abs(command.value - before.value) > 1e-9) return false;
  const size_t drive = static_cast<size_t>(v.config.spindle_drive);
  const uint32_t status = drive < at.feedback.size() ? at.feedback[drive].status : 0;
  if (before.mode == DriveMode::kPosition) return status & drive_status::kInPosition;
  // The status bit of the last tick may still answer the command before this cycle's.
  const double actual = at.feedback[drive].velocity;
  const double commanded = before.value * v.spindle.override;
  if (std::abs(actual - commanded) > std::max(6.0, 0.02 * std::abs(commanded))) return false;
  return before.value == 0 || (status & drive_status::kAtSpeed);
}

void Repositioning::Cycle(const ReposView& v, const AmplifierTelegram& at, bool interrupted,
                          bool motion) {
  if (!data_.interruption) {
    data_.function = ReposFunction::kNone;
    data_.crest = false;
    return;
  }
  Interruption& i = *data_.interruption;
  for (size_t a = 0; a < v.commanded.size() && !i.left_contour; ++a)
    if (!std::isnan(i.point[a]) && std::abs(v.commanded[a] - i.point[a]) > 1e-6)
      i.left_contour = true;
  // 7.1: the signals count only in the situation of 2.1 (interrupted, left by jogging, no
  // Control-Reset), and only if the program may be continued other than by the reverse
  // program (Bxx.032, 6.1).
  const bool evaluated =
      interrupted && i.left_contour && !v.config.process.reverse_program_required;
  const ReposFunction function = evaluated ? data_.request : ReposFunction::kNone;
  // 7.3: updated only while a function is called; the relevant axes within their windows, the
  // spindle in its former state. Withdrawing the function drops it at once.
  data_.crest = false;
  // 7.1 instruction: withdrawn in manual mode, repositioning ends once the motion under way has
  // ended: a jog still moving, or its key still held, keeps its zone and stops at the target;
  // the next press is a plain jog.
  if (evaluated && function == ReposFunction::kNone && data_.function != ReposFunction::kNone &&
      motion)
    return;
  if (function != data_.function && function != ReposFunction::kNone) data_.start = v.commanded;
  data_.function = function;
  if (data_.function == ReposFunction::kNone) return;
  const std::vector<double> target = Target(v);
  const int rotary = v.config.rotary_axis;
  bool restored = true;
  // 6.1 instruction: under G31 X and C count as the fictive point, with X's window.
  int fx = -1, fc = -1;
  const bool fictive = Fictive(v, fx, fc);
  for (size_t a = 0; a < target.size() && restored; ++a) {
    const ChannelAxis& axis = v.config.axes[a];
    if (fictive && (static_cast<int>(a) == fx || static_cast<int>(a) == fc)) continue;
    if (std::isnan(target[a]) || axis.repos_window <= 0) continue;
    restored =
        WithinReposWindow(axis, target[a], v.commanded[a]) && !OutOfItsMode(v.headstock, rotary, a);
  }
  if (fictive && restored && v.config.axes[fx].repos_window > 0)
    restored = WithinFictiveWindow(v.config.axes[fx], FictiveOf(v, target, fx, fc),
                                   FictiveOf(v, v.commanded, fx, fc)) &&
               !OutOfItsMode(v.headstock, rotary, fc);
  if (restored && SpindleRelevant(v)) restored = SpindleRestored(v, at);
  if (restored) restored = v.further.AllRestored(i.further_spindles, at);
  data_.crest = restored && ToolStorageRestored(v);
}

ReposStatus Repositioning::Status(const ReposView& v, const AmplifierTelegram* at,
                                  bool whole) const {
  ReposStatus s;
  s.function = data_.function;
  s.conditions_restored = data_.crest;
  s.subroutine_running = data_.run;
  if (!data_.interruption) return s;
  const Interruption& i = *data_.interruption;
  const int rotary = v.config.rotary_axis;
  s.left_contour = i.left_contour;
  const std::vector<double> target = Target(v);
  for (size_t a = 0; a < v.config.axes.size(); ++a) {
    const ChannelAxis& axis = v.config.axes[a];
    ReposAxisStatus x;
    x.name = axis.name;
    x.command_value = v.commanded[a];
    x.relevant = !std::isnan(target[a]) && axis.repos_window > 0;
    if (!std::isnan(target[a])) {
      x.final_value = target[a];
      x.distance_to_go = ReposDistanceToGo(axis, target[a], v.commanded[a]);
      x.adjust = x.relevant && (!WithinReposWindow(axis, target[a], v.commanded[a]) ||
                                OutOfItsMode(v.headstock, rotary, a));
    }
    s.axes.push_back(x);
  }
  // 5.2: under G31 the screen shows the fictive axes X1, Y1 as well, and X and C are adjusted
  // as the fictive point is, with X's window (6.1).
  int fx = -1, fc = -1;
  if (Fictive(v, fx, fc)) {
    const nc::FictivePoint to = FictiveOf(v, target, fx, fc);
    const nc::FictivePoint now = FictiveOf(v, v.commanded, fx, fc);
    const bool relevant = v.config.axes[fx].repos_window > 0;
    const bool adjust = relevant && (!WithinFictiveWindow(v.config.axes[fx], to, now) ||
                                     OutOfItsMode(v.headstock, rotary, fc));
    s.axes[fx].relevant = s.axes[fc].relevant = relevant;
    s.axes[fx].adjust = s.axes[fc].adjust = adjust;
    static const std::string kNames[2] = {"X1", "Y1"};
    for (int k = 0; k < 2; ++k) {
      ReposAxisStatus f;
      f.name = kNames[k];
      f.final_value = k == 0 ? to.x1 : to.y1;
      f.command_value = k == 0 ? now.x1 : now.y1;
      f.distance_to_go = f.final_value - f.command_value;
      f.relevant = relevant;
      f.adjust = adjust;
      s.axes.push_back(f);
    }
  }
  const MainSpindleState& spindle = v.spindle;
  const size_t drive = static_cast<size_t>(v.config.spindle_drive);
  ReposSpindleStatus& sp = s.spindle;
  sp.relevant = SpindleRelevant(v);
  sp.override = spindle.override;
  sp.actual_m = SpindleMOf(spindle.command);
  sp.command_m = i.spindle_m;
  sp.command_rpm = i.spindle.mode == DriveMode::kVelocity ? i.spindle.value / 6 : 0;
  if (at && drive < at->feedback.size())
    sp.actual_rpm = at->feedback[drive].velocity / 6;
  else
    sp.actual_rpm = spindle.rpm;
  // Without the drives' feedback: the command restored, in spindle mode.
  sp.adjust = sp.relevant &&
              !(at ? SpindleRestored(v, *at)
                   : (!v.headstock || v.headstock->mode() == axes::HeadstockMode::kSpindle) &&
                         spindle.command.mode == i.spindle.mode &&
                         std::abs(spindle.command.value - i.spindle.value) < 1e-9);
  s.further_spindles = v.further.ReposStatus(i.further_spindles, at);
  s.tool_storage_relevant = v.config.process.reposition_tool_storage && v.tool_storage;
  s.tool_storage_adjust = !ToolStorageRestored(v);
  if (!whole) return s;
  s.programmed_feed = i.modal.feed;
  s.line = i.line;
  s.tool = i.modal.tool;
  s.correction = i.modal.correction;
  s.spindle_m = i.modal.spindle;
  s.coolant = i.modal.coolant;
  s.g_codes = nc::ActiveGCodes(i.modal);  // G31 / G32 too (5.2)
  return s;
}

}  // namespace vmt::control::channel
