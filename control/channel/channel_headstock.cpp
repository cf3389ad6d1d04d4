// The headstock's operating states in the channel (C-axis manual 2.3 and 3.3): the changeover
// as blocks and manual keys need it, immediate stop and the process enabling signal, the
// rotary axis' zero offsets, the references of spindle and rotary axis, and the position
// indication (S1 <-> C).
#include <cmath>

#include "control/channel/channel.hpp"
#include "control/channel/main_spindle_keys.hpp"

namespace vmt::control::channel {
void Channel::HeadstockCycle(const AmplifierTelegram& at, double dt) {
  HeadstockCycleInput in;
  in.hold = state_ == ChannelState::kHold;
  in.failed = state_ == ChannelState::kError;
  in.process_enabled = enable_.process;
  in.running = state_ == ChannelState::kRunning;
  if (const std::optional<std::string> error = headstock_.Cycle(in, at, dt))
    Fail(*error, kMsgChangeoverAck);
  const size_t r = static_cast<size_t>(config_.rotary_axis);
  frames_.translation[r] = headstock_.RotaryOffsetsActive() ? headstock_.rotary_translation() : 0;
  if (headstock_.RotaryFollowsFeedback()) {
    out_.commanded[r] = out_.previous[r] = at.feedback[config_.axes[r].drive].position;
    jog_.axes[r].handwheel_target = out_.commanded[r];
  }
}

void Channel::ManualChangeover(axes::HeadstockMode target) {
  headstock_.ManualChangeover(target,
                              state_ == ChannelState::kHold || state_ == ChannelState::kError);
}

void Channel::ManualSpindle(int m) {
  if (mode_ != ChannelMode::kManual || config_.spindle_drive < 0) return;
  if (m != 3 && m != 4 && m != 5 && m != 19) return;
  // Without the process enabling signal or the spindle's axis enabling signal (4.2) nothing
  // starts; a stop is always taken.
  if (m != 5 && (!enable_.process || !sp_.enable)) return;
  // 4.2: "The NC automatically switches over to main spindle mode if rotary axis mode is active
  // when one of these commands is started"; the command acts once spindle mode is there.
  if (headstock_) ManualChangeover(axes::HeadstockMode::kSpindle);
  // REPOS manual 3.3: during repositioning or NC-block restart the key of the table restores
  // the spindle's state before the interruption (M03 / M04 at the programmed speed, M05, M19).
  if (repos_.called() && repos_.SpindleRelevant(ReposViewNow()) &&
      KeyRestoresSpindle(repos_.interruption()->spindle_m, m)) {
    if (!GuardSpindleStart("spindle start", repos_.interruption()->spindle)) return;
    sp_.command = repos_.interruption()->spindle;
    sp_.referencing = m == 19;
    out_.take_over_pending = true;
    return;
  }
  const std::optional<SpindleKeyMove> move = SpindleMKey(m, config_.spindle);
  if (move && GuardSpindleStart("spindle start", move->command)) ApplySpindleKey(*move);
}

void Channel::ApplySpindleKey(const SpindleKeyMove& move) {
  sp_.command = move.command;
  sp_.jogging = move.jogging;
  sp_.referencing = move.referencing;
  out_.take_over_pending = true;
}

void Channel::HomeSpindle() {
  if (mode_ != ChannelMode::kManual || config_.spindle_drive < 0) return;
  if (!enable_.process || !sp_.enable) return;
  if (headstock_) ManualChangeover(axes::HeadstockMode::kSpindle);
  const SpindleKeyMove move = SpindleHomeKey(config_.spindle);
  if (GuardSpindleStart("spindle start", move.command)) ApplySpindleKey(move);
}

void Channel::JogSpindle(int direction) {
  if (mode_ != ChannelMode::kManual || config_.spindle_drive < 0) return;
  if (direction == 0) {
    // Released: a spindle the key turned brakes; an increment runs to its end.
    if (sp_.jogging) sp_.command = {DriveMode::kVelocity, 0, 0};
    sp_.jogging = false;
    out_.take_over_pending = true;
    return;
  }
  if (!enable_.process || !sp_.enable) return;
  // 4.4: jogging the main spindle initiates the changeover to spindle mode; 2.3 / 3.3 Jogging
  // Movements: its jog keys abort a changeover an immediate stop interrupted. The motion acts
  // once spindle mode is there.
  if (headstock_) ManualChangeover(axes::HeadstockMode::kSpindle);
  // 4.3: the jog mode's type of jogging, as for the feed axes (main_spindle_keys.hpp).
  const std::optional<SpindleKeyMove> move =
      SpindleJogKey(direction, jog_rules(), sp_.position, config_.spindle);
  if (move) ApplySpindleKey(*move);
}

void Channel::SetAxisEnable(size_t axis, bool on) {
  if (axis >= config_.axes.size()) return;
  if (enable_.axes.size() != config_.axes.size()) enable_.axes.assign(config_.axes.size(), true);
  enable_.axes[axis] = on;
}

void Channel::SetSpindleEnable(bool on) {
  sp_.enable = on;
  // 4.2: without the axis enabling signal the spindle cannot be moved in manual mode: a jog
  // key's turning stops. (A spindle turning by M3 from the program or AxxC.M3 keeps its
  // command: vmt's reading, as the signal gates motion the keys start.)
  if (!on && sp_.jogging) {
    sp_.command = {DriveMode::kVelocity, 0, 0};
    sp_.jogging = false;
    out_.take_over_pending = true;
  }
}

bool Channel::SpindleAtSpeedLimit() const {
  const double limit = config_.spindle.max_spindle_rpm;
  if (config_.spindle_drive < 0 || limit <= 0 || sp_.command.mode != DriveMode::kVelocity)
    return false;
  return std::abs(sp_.command.value / 6 * sp_.override) >= limit * (1 - 1e-9);
}

void Channel::SetProcessEnable(bool on) {
  enable_.process = on;
  // 2.3 Process Enabling Signal: removed, the NC initiates an immediate stop, stops program
  // execution (and so the changeover's internal sequence, HeadstockCycle) and brings the axes
  // to a standstill (Jogging brakes them). The manual describes it for a changeover; a real
  // control does the same without one.
  if (!on) Stop();
}

void Channel::TrackReferences(const AmplifierTelegram& at, double dt) {
  // 2.3 / 3.3 Homing: the reference is kept while the encoder's frequency,
  //   speed [1/s] * impulses or oscillations per revolution,
  // stays within the limit frequency of its interface; beyond it counts are lost.
  const int spindle = config_.spindle_drive;
  const int rotary = headstock_ ? config_.axes[config_.rotary_axis].drive : -1;
  drives_.encoder_last.resize(at.feedback.size(), std::nan(""));
  auto too_fast = [&](int drive, const axes::AxisParameters& p) {
    const double last = drives_.encoder_last[drive];
    const double position = at.feedback[drive].position;
    drives_.encoder_last[drive] = position;
    if (p.encoder_limit_hz <= 0 || p.encoder_periods_per_rev <= 0 || std::isnan(last)) return false;
    // The shorter way: a modulo encoder (0..360) wraps every turn. A cycle's step stays far
    // below half a turn (180 deg per 1 ms NC cycle is 30000 rpm).
    const double rev_per_s = std::abs(std::remainder(position - last, 360.0)) / 360 / dt;
    return rev_per_s * p.encoder_periods_per_rev > p.encoder_limit_hz;
  };
  if (rotary >= 0 && too_fast(rotary, config_.axes[config_.rotary_axis]))
    frames_.homed[config_.rotary_axis] = false;
  // Section 2: spindle and rotary axis are one drive with one encoder and one reference.
  if (spindle >= 0 && spindle != rotary && too_fast(spindle, config_.spindle)) sp_.homed = false;
  if (spindle < 0) return;
  sp_.position = at.feedback[spindle].position;
  sp_.rpm = at.feedback[spindle].velocity / 6;
  // M19 establishes the reference (2.3: "by crossing the related zero impulse", then it
  // moves to the command position): it is there when the spindle reports itself in position.
  // It needs spindle mode on a headstock: in rotary mode M19 waits for its changeover.
  const bool spindle_mode = !headstock_ || headstock_->mode() == axes::HeadstockMode::kSpindle;
  if (sp_.referencing && spindle_mode && sp_.command.mode == DriveMode::kPosition &&
      (at.feedback[spindle].status & drive_status::kInPosition)) {
    sp_.referencing = false;
    sp_.homed = true;
    if (spindle == rotary) frames_.homed[config_.rotary_axis] = true;
  }
  if (sp_.command.mode != DriveMode::kPosition) sp_.referencing = false;
}

bool Channel::spindle_homed() const {
  if (headstock_ && !headstock_->config().separate_servo())
    return frames_.homed[config_.rotary_axis];
  return sp_.homed;
}

std::string Channel::HeadstockAxisName() const {
  if (!headstock_) return "";
  if (headstock_.shown_mode() == axes::HeadstockMode::kRotary)
    return config_.axes[config_.rotary_axis].name;
  return config_.spindle.name.empty() ? "S1" : config_.spindle.name;
}

double Channel::HeadstockPosition() const {
  if (!headstock_) return 0;
  // 2.3 Position Indication: the representation usual for a rotary axis, 0..360 deg, though
  // the program's C runs on past a turn (C-270, the manual's 1.2).
  const size_t r = static_cast<size_t>(config_.rotary_axis);
  const double shown = headstock_.shown_mode() == axes::HeadstockMode::kRotary
                           ? out_.commanded[r] - frames_.translation[r]
                           : sp_.position;
  const double a = std::fmod(shown, 360.0);
  return a < 0 ? a + 360 : a;
}

SpindleStatus Channel::spindle_status() const {
  SpindleStatus st;
  st.spindle_override = sp_.override;
  st.feed_override = override_;
  // 2.3 / 3.3 Status Indication: lines instead of the speeds while the display shows the rotary
  // axis (the same switch as the position indication's designation).
  st.speeds_shown = config_.spindle_drive >= 0 &&
                    !(headstock_ && headstock_.shown_mode() == axes::HeadstockMode::kRotary);
  if (!st.speeds_shown) return st;
  // Programmed: what M3 / M4 and S (or the manual keys' jogging speed) command, before the
  // spindle override; a spindle that positions (M19) has no speed programmed. Not in spindle
  // mode yet (a changeover to it in progress): the command that waits for it.
  if (sp_.command.mode == DriveMode::kVelocity) st.programmed_rpm = sp_.command.value / 6;
  st.actual_rpm = sp_.rpm;
  st.max_rpm = config_.spindle.max_spindle_rpm;
  return st;
}

}  // namespace vmt::control::channel
