// Jogging the fictive axes X1/Y1 of G31 (REPOS manual 5.2): in manual mode under an active face
// transformation the keys of X1 and Y1 move the tool on straight lines of the face plane, as
// jog mode does on the real control, and X and C follow transformed. The same zone rule as for
// the machine axes holds while a REPOS function is called (3.2): between the target and where
// the fictive axis stood when the function was called, never past the target.
//
// Continuous, incremental (parametric, 0.001 .. 1 mm) and handwheel (JogMode::kHandwheel: the
// counts of X1 or Y1 move the point along that fictive axis, handwheel_per_count each) modes.
// The speed is X's jogging speed (the handwheel's: X's jogging rapid, as the real axes'
// handwheel's), limited so that C keeps its jogging rapid rate (tangential speed <= C's rate
// times the radius); the point never comes closer to the centre than kFictiveJogCentre (C is
// undefined there). PathGuard checks the way to where the jog could stop (a handwheel's: its
// target, as for the real axes) in chords of the face line, each within kChordTolerance of
// it, as the G31 block moves are checked.
//
// The handwheel's target of a fictive axis lasts until the point gets there: the next counts
// start from where it stands then, so moves of X or C in between are not undone. While it
// runs, the real axes' handwheel targets of X and C follow it (they would pull X and C back).
#include <cmath>
#include <numbers>

#include "control/channel/channel.hpp"
#include "control/channel/fictive_jog.hpp"
#include "control/channel/jog_follow.hpp"

namespace vmt::control::channel {

bool Channel::FictiveJogAxes(int& x, int& c) const {
  x = c = -1;
  const nc::Transformation transformation =
      repos_.interruption() ? repos_.interruption()->modal.transformation : modal().transformation;
  if (transformation != nc::Transformation::kFace) return false;
  if (headstock_.RotaryAxisOff()) return false;
  for (size_t a = 0; a < config_.axes.size(); ++a) {
    if (config_.axes[a].name == "X") x = static_cast<int>(a);
    if (config_.axes[a].name == "C") c = static_cast<int>(a);
  }
  return x >= 0 && c >= 0;
}

bool Channel::JogFictive(int axis, int direction) {
  int x = -1, c = -1;
  if (mode_ != ChannelMode::kManual || axis < 0 || axis > 1 || !FictiveJogAxes(x, c)) return false;
  if (direction != 0 && config_.process.jogging_causes_reset && state_ == ChannelState::kHold)
    Reset();
  jog_.fictive[axis].key = direction > 0 ? 1 : direction < 0 ? -1 : 0;
  out_.take_over_pending = true;
  return true;
}

bool Channel::HandwheelFictive(int axis, int counts) {
  int x = -1, c = -1;
  if (mode_ != ChannelMode::kManual || jog_.mode != JogMode::kHandwheel || axis < 0 || axis > 1 ||
      !enable_.process || !FictiveJogAxes(x, c) || !axis_enabled(x) || !axis_enabled(c))
    return false;
  out_.take_over_pending = true;
  FictiveJog& j = jog_.fictive[axis];
  if (!j.handwheel) {
    const nc::FictivePoint p = nc::MachineToFace(out_.commanded[x] - frames_.translation[x],
                                                 out_.commanded[c] - frames_.translation[c]);
    j.handwheel = true;
    j.handwheel_target = axis == 0 ? p.x1 : p.y1;
  }
  j.handwheel_target += counts * config_.handwheel_per_count;
  return true;
}

void Channel::FictiveJogging(double dt) {
  int x = -1, c = -1;
  FictiveJog(&jogs)[2] = jog_.fictive;
  if (!FictiveJogAxes(x, c)) {
    for (int k = 0; k < 2; ++k) jogs[k] = FictiveJog{};
    return;
  }
  const ChannelAxis& ax = config_.axes[x];
  const ChannelAxis& ac = config_.axes[c];
  // A fictive axis moves X and C together: both need their axis enabling signal (C-axis 4.2).
  const bool enabled = enable_.process && axis_enabled(x) && axis_enabled(c);
  const nc::FictivePoint p = nc::MachineToFace(out_.commanded[x] - frames_.translation[x],
                                               out_.commanded[c] - frames_.translation[c]);
  const double radius = std::hypot(p.x1, p.y1);
  // The keys at X's jogging speed, the handwheel at X's jogging rapid (as the real axes'
  // handwheel), either slower where C would pass its own jogging rapid.
  const double c_limit =
      JogRapid(ac) * std::numbers::pi / 180 * std::max(radius, kFictiveJogCentre);
  FictiveJogContext context;
  context.enabled = enabled;
  context.speed = std::min(jog_rules().Speed(ax), c_limit);
  context.handwheel_speed = std::min(JogRapid(ax) * override_, c_limit);
  // 3.2: the zone of each fictive axis while a REPOS function is called.
  int rx = -1, rc = -1;
  if (const ReposView v = ReposViewNow(); repos_.called() && repos_.Fictive(v, rx, rc)) {
    const nc::FictivePoint target = repos_.FictiveOf(v, repos_.Target(v), rx, rc);
    const nc::FictivePoint start = repos_.FictiveOf(v, repos_.start(), rx, rc);
    const double now[2] = {p.x1, p.y1}, to[2] = {target.x1, target.y1},
                 from[2] = {start.x1, start.y1};
    for (int k = 0; k < 2; ++k) {
      const ReposZone zone = FictiveZoneOf(to[k], from[k]);
      context.low[k] = std::min(zone.low, now[k]);
      context.high[k] = std::max(zone.high, now[k]);
    }
  }
  context.mode = jog_.mode;
  context.increment = jog_rules().Increment(ax);
  context.acceleration = ax.acceleration;
  const std::optional<nc::FictivePoint> moved = FictiveJogCycle(jogs, p, context, dt);
  if (!moved) return;
  const nc::FictivePoint q = *moved;
  // Not through the centre: the jog stops short of it.
  if (std::hypot(q.x1, q.y1) < kFictiveJogCentre) {
    for (int k = 0; k < 2; ++k) jogs[k].velocity = 0, jogs[k].stepping = jogs[k].handwheel = false;
    return;
  }
  std::vector<double> to = out_.commanded;
  to[x] = std::hypot(q.x1, q.y1) + frames_.translation[x];
  to[c] = out_.commanded[c] + nc::SweepDeg(p, q);
  if (!GuardFictiveJog(x, c, q)) {
    for (int k = 0; k < 2; ++k) jogs[k] = FictiveJog{};
    return;
  }
  out_.commanded = to;
  jog_.axes[x].handwheel_target = out_.commanded[x];
  jog_.axes[c].handwheel_target = out_.commanded[c];
}

bool Channel::GuardFictiveJog(int x, int c, nc::FictivePoint next) {
  if (!guard_.active()) return true;
  if (!guard_.FictiveDue()) return true;
  // Where the jog could stop: the next point plus the braking distance and one check interval
  // at the present velocity, along the jog's direction.
  const double dt = config_.tick_s * config_.ticks_per_cycle;
  const double interval = config_.path_guard_every * dt + dt;
  const double a = config_.axes[x].acceleration;
  const nc::FictivePoint p = nc::MachineToFace(out_.commanded[x] - frames_.translation[x],
                                               out_.commanded[c] - frames_.translation[c]);
  const nc::FictivePoint s = FictiveJogStop(jog_.fictive, jog_.mode, next, a, interval);
  const std::string move = jog_.mode == JogMode::kHandwheel ? "handwheel X1/Y1" : "jog X1/Y1";
  // Chords of the line p-s, straight in the drives, within kChordTolerance of it (a
  // handwheel's target may be far; the line may bend much in X and C near the centre).
  const nc::FaceLine line = nc::FaceLineOf(p, s);
  const double chord = nc::FaceChordStep(line, kChordTolerance);
  const int chords =
      line.through_centre
          ? 1
          : static_cast<int>(std::clamp(std::ceil(line.length / std::max(chord, 1e-9)), 1.0,
                                        static_cast<double>(kMaxChords)));
  const std::vector<double> from = GuardFrom();
  std::vector<double> to = from, b = from, at = from;
  to[config_.axes[x].drive] = std::hypot(s.x1, s.y1) + frames_.translation[x];
  to[config_.axes[c].drive] = out_.commanded[c] + nc::SweepDeg(p, s);
  GuardRecord record{move, from, to, PathCheck{}, 0, false};
  for (int i = 1; i <= chords; ++i) {
    const double u = static_cast<double>(i) / chords;
    const nc::FictivePoint q{p.x1 + (s.x1 - p.x1) * u, p.y1 + (s.y1 - p.y1) * u};
    b[config_.axes[x].drive] = std::hypot(q.x1, q.y1) + frames_.translation[x];
    b[config_.axes[c].drive] = out_.commanded[c] + nc::SweepDeg(p, q);
    const PathCheck check = guard_.guard().CheckMove(at, b);
    if (!check.clear) return !GuardStops(move, from, to, check);
    if (record.checks == 0 || check.min_clearance < record.check.min_clearance)
      record.check = check;
    ++record.checks;
    at = b;
  }
  guard_.Add(record);
  return true;
}

}  // namespace vmt::control::channel
