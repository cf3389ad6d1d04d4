// PathGuard in the channel (interface: control/path_guard.hpp): jog moves are checked ahead
// while they run, far enough to brake before a contact; an increment is checked whole before it
// starts. A contact stops the move before it happens with an NC error naming the parts and the
// position (GuardReaction::kStop), or is only recorded (kWarn). The approach moves of
// repositioning (G77 and the closing move, REPOS manual 4.2) and every move the REPOS subroutine
// programs are checked whole before they start, arcs as chords. Every check ends up in a
// GuardRecord.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "control/channel/channel.hpp"
#include "control/channel/jog_follow.hpp"

namespace vmt::control::channel {

std::vector<double> Channel::GuardFrom() const {
  std::vector<double> from = drive_positions_;
  for (size_t a = 0; a < config_.axes.size(); ++a)
    if (static_cast<size_t>(config_.axes[a].drive) < from.size())
      from[config_.axes[a].drive] = out_.commanded[a];
  return from;
}

bool Channel::GuardStops(const std::string& move, const std::vector<double>& from,
                         const std::vector<double>& to, const PathCheck& check) {
  return StopAhead(guard_.Contact(move, from, to, check), move, from, to, check);
}

bool Channel::StopAhead(bool stop, const std::string& move, const std::vector<double>& from,
                        const std::vector<double>& to, const PathCheck& check) {
  if (!stop) return false;
  std::string where;
  for (const ChannelAxis& axis : config_.axes) {
    if (static_cast<size_t>(axis.drive) >= check.position.size()) continue;
    char text[48];
    std::snprintf(text, sizeof text, "%s%s%.3f", where.empty() ? "" : " ", axis.name.c_str(),
                  check.position[axis.drive]);
    where += text;
  }
  // A turret index, or an axis move against the turret indexing: where the turret stands then.
  const size_t t = static_cast<size_t>(config_.tool_storage_drive);
  if (ToolStorageNc() && t < check.position.size() && t < from.size() &&
      (from[t] != to[t] || check.position[t] != drive_positions_[t])) {
    char text[48];
    std::snprintf(text, sizeof text, " %s%.3f", config_.tool_storage.name.c_str(),
                  check.position[t]);
    where += text;
  }
  char point[96];
  std::snprintf(point, sizeof point, " (contact at x %.3f y %.3f z %.3f mm)", check.point[0],
                check.point[1], check.point[2]);
  const std::string text = "collision ahead (" + move + "): " + check.part_a + " would touch " +
                           check.part_b + " at " + where + point;
  if (state_ != ChannelState::kError) Fail(text, kMsgCollision);
  return true;
}

bool Channel::GuardIncrement(size_t axis, double to_position) {
  if (!guard_.active()) return true;
  const std::vector<double> from = GuardFrom();
  std::vector<double> to = from;
  to[config_.axes[axis].drive] = to_position;
  const PathCheck c = GuardCheck(from, to);
  if (c.clear) {
    guard_.Clear("jog", from, to, c);
    return true;
  }
  return !GuardStops("jog", from, to, c);
}

bool Channel::GuardBlockMove(const std::string& move, const std::vector<double>* end,
                             bool measuring_path) {
  if (!guard_.active()) return true;
  if (!end && (work_.motion.face_axes[0] >= 0 || work_.motion.arc_axes[0] >= 0))
    return GuardCurvedMove(move);
  const std::vector<double> from = GuardFrom();
  std::vector<double> to = from;
  for (size_t a = 0; a < config_.axes.size(); ++a)
    if (static_cast<size_t>(config_.axes[a].drive) < to.size())
      to[config_.axes[a].drive] = end ? (*end)[a] : work_.motion.end[a];
  const PathCheck c = GuardCheck(from, to, measuring_path);
  if (c.clear) {
    guard_.Clear(move, from, to, c);
    return true;
  }
  return !GuardStops(move, from, to, c);
}

bool Channel::GuardCurvedMove(const std::string& move) {
  // The curve is checked as chords, straight in the drives' positions, short enough that each
  // stays within kChordTolerance of it; one record sums them up. An arc's chord of angle t lies
  // r (1 - cos(t/2)) inside it. G31's line (or arc) of the face plane is a curve of X and C:
  // nc::FaceChordStep proves its bound.
  double chords = 1;
  if (work_.motion.face_axes[0] >= 0) {
    const nc::FaceLine line = work_.motion.FaceBounds();
    chords = std::ceil(line.length / std::max(nc::FaceChordStep(line, kChordTolerance), 1e-9));
  } else if (work_.motion.arc_radius > kChordTolerance) {
    const double angle = 2 * std::acos(1 - kChordTolerance / work_.motion.arc_radius);
    chords = std::ceil(std::abs(work_.motion.arc_sweep) / angle);
  }
  const int n = static_cast<int>(std::clamp(chords, 1.0, static_cast<double>(kMaxChords)));
  const std::vector<double> from = GuardFrom();
  std::vector<double> to = from, a = from, b = from, point;
  for (size_t k = 0; k < config_.axes.size(); ++k)
    if (static_cast<size_t>(config_.axes[k].drive) < to.size())
      to[config_.axes[k].drive] = work_.motion.end[k];
  GuardRecord record{move, from, to, PathCheck{}, 0, false};
  for (int i = 1; i <= n; ++i) {
    work_.motion.PointAt(static_cast<double>(i) / n, point);
    for (size_t k = 0; k < config_.axes.size(); ++k)
      if (static_cast<size_t>(config_.axes[k].drive) < b.size())
        b[config_.axes[k].drive] = point[k];
    const PathCheck c = GuardCheck(a, b);
    if (!c.clear) return !GuardStops(move, from, to, c);
    if (record.checks == 0 || c.min_clearance < record.check.min_clearance) record.check = c;
    ++record.checks;
    a = b;
  }
  guard_.Add(record);
  return true;
}

void Channel::GuardJog(double dt) {
  if (!guard_.active()) return;
  // A stopped key stays stopped until it is released (or the other way is pressed).
  for (JogAxis& j : jog_.axes)
    if (j.blocked != 0 && j.key != j.blocked) j.blocked = 0;
  // Where each moving axis would stand if it braked at the next check: it runs at most one
  // check interval (and this cycle) on, accelerating, then brakes.
  const std::vector<double> from = GuardFrom();
  std::vector<double> to = from;
  const double interval = config_.path_guard_every * dt + dt;
  bool moving = false;
  for (size_t a = 0; a < jog_.axes.size(); ++a) {
    if (headstock_.RotaryAxisOff() && static_cast<int>(a) == config_.rotary_axis) continue;
    const JogAxis& j = jog_.axes[a];
    const ChannelAxis& axis = config_.axes[a];
    double stop = out_.commanded[a];
    if (jog_.mode == JogMode::kHandwheel) {
      stop = j.handwheel ? j.handwheel_target : out_.commanded[a];
    } else if (!j.stepping) {
      // In incremental mode a key starts an increment, which GuardIncrement checks whole: no
      // continuous run to predict (its braking distance could stop a short increment).
      if (jog_rules().Increment(axis) > 0 && j.velocity == 0) continue;
      const int key = enable_.process && j.key != j.blocked ? j.key : 0;
      const int dir = key != 0 ? key : j.velocity > 0 ? 1 : j.velocity < 0 ? -1 : 0;
      if (dir == 0) continue;
      const double rapid = JogRapid(axis);
      // Braking (key released or stopped) it ends where the brake takes it; driven, it may
      // run on and speed up for the interval first.
      const double v = key == 0 ? std::abs(j.velocity)
                                : std::min(std::abs(j.velocity) + axis.acceleration * interval,
                                           std::max(rapid * override_, std::abs(j.velocity)));
      stop += dir * (v * v / (2 * axis.acceleration) + v * (key == 0 ? dt : interval));
      if (axis.travel_max > axis.travel_min)
        stop = std::clamp(stop, axis.travel_min, axis.travel_max);
    }
    if (std::abs(stop - out_.commanded[a]) < 1e-9) continue;
    to[axis.drive] = stop;
    moving = true;
  }
  if (!guard_.Due(ContinuousMove::kJog, moving)) return;  // at the start, then every n cycles
  // Once the jog's first check is made, a check ahead that the last one proves clear needs no
  // query of its own.
  PathCheck c;
  if (guard_.Open(ContinuousMove::kJog) && !IndexingBeside(from, to) &&
      guard_.guard().Proves(from, to, c)) {
    guard_.Proven(ContinuousMove::kJog, to);
    return;
  }
  c = GuardCheck(from, to);
  if (!StopAhead(guard_.Ahead(ContinuousMove::kJog, "jog", from, to, c), "jog", from, to, c))
    return;
  // Brake every moving axis: its key is held off, a handwheel's target becomes where the axis
  // can stop.
  for (size_t a = 0; a < jog_.axes.size(); ++a) {
    JogAxis& j = jog_.axes[a];
    if (to[config_.axes[a].drive] == from[config_.axes[a].drive]) continue;
    if (jog_.mode == JogMode::kHandwheel) {
      j.handwheel_target = out_.commanded[a] +
                           j.velocity * std::abs(j.velocity) / (2 * config_.axes[a].acceleration);
    } else {
      j.blocked = j.key != 0 ? j.key : (j.velocity > 0 ? 1 : -1);
    }
  }
}

}  // namespace vmt::control::channel
