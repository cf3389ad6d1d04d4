// PathGuard of the NC-controlled turret and of a spindle start. A turret index (T word, MTP,
// MGPOS / MGNEG) swings every tool of the disc through space: its sweep, the turn of the tool
// storage drive alone with the axes where they stand, is checked whole before it starts (the
// guard's straight-move check is exact for a turn as for a slide). A spindle about to start
// sweeps its chuck, jaws and workpiece round: PathGuard checks that solid of revolution
// against the tools where they stand. And while the turret indexes asynchronously to the
// other axes (REPOS manual 4.2: the REPOS subroutine's G77 may run before an MRY), an axis
// move is checked against the turret as it turns on, not where it happens to stand.
#include <cmath>

#include "control/channel/channel.hpp"

namespace vmt::control::channel {

bool Channel::IndexingBeside(const std::vector<double>& from, const std::vector<double>& to) const {
  const size_t t = static_cast<size_t>(config_.tool_storage_drive);
  const ToolStorageAxis& ts = tool_storage_.axis();
  return ToolStorageNc() && (ts.positioning || ts.stepping) && t < from.size() && t < to.size() &&
         from[t] == to[t] && ts.target != from[t];
}

PathCheck Channel::GuardCheck(const std::vector<double>& from, const std::vector<double>& to,
                              bool measuring_path) {
  auto check = [&](const std::vector<double>& a, const std::vector<double>& b) {
    return measuring_path ? guard_.guard().CheckMeasuringPath(a, b)
                          : guard_.guard().CheckMove(a, b);
  };
  if (!IndexingBeside(from, to)) return check(from, to);
  const size_t t = static_cast<size_t>(config_.tool_storage_drive);
  const ToolStorageAxis& ts = tool_storage_.axis();
  // The two motions run side by side, each at its own pace: vmt checks the edges of what they
  // span together - the axis move with the turret where it stands and at its target station
  // (where it will be once the index ends, most likely before the axes arrive), and the rest
  // of the index with the axes at the move's start and at its end. Not every timing: a contact
  // inside what they span with all four edges clear is not excluded (MRY makes it sure). The
  // first contact found is the answer; clear, the check with the smallest clearance.
  std::vector<double> a = from, b = to;
  a[t] = b[t] = ts.target;
  std::vector<double> sweep_from = from, sweep_to = from;
  sweep_to[t] = ts.target;
  std::vector<double> sweep_end_from = to, sweep_end_to = to;
  sweep_end_to[t] = ts.target;
  PathCheck best = check(a, b);
  if (!best.clear) return best;
  for (const PathCheck& c : {check(from, to), guard_.guard().CheckMove(sweep_from, sweep_to),
                             guard_.guard().CheckMove(sweep_end_from, sweep_end_to)}) {
    if (!c.clear) return c;
    if (c.min_clearance < best.min_clearance) best = c;
  }
  return best;
}

bool Channel::GuardTurretIndex(const std::string& move, double from_deg, double to_deg) {
  if (!guard_.active()) return true;
  const size_t t = static_cast<size_t>(config_.tool_storage_drive);
  std::vector<double> from = GuardFrom();
  if (t >= from.size()) return true;
  // From where the command stands: an index may start while the last one is still on its way.
  // The axes stand where the channel commands them; a T word's block may move them as the
  // turret turns (asynchronously), which its own move's check (if it has one) covers.
  from[t] = from_deg;
  std::vector<double> to = from;
  to[t] = to_deg;
  if (from[t] == to[t]) return true;
  const PathCheck c = guard_.guard().CheckMove(from, to);
  if (c.clear) {
    guard_.Clear(move, from, to, c);
    return true;
  }
  return !GuardStops(move, from, to, c);
}

bool Channel::GuardTurretJog(int direction, double from_deg, double to_deg) {
  if (!guard_.active()) return false;
  if (!guard_.Due(ContinuousMove::kTurretJog, direction != 0)) return false;
  const size_t d = static_cast<size_t>(config_.tool_storage_drive);
  std::vector<double> from = GuardFrom();
  if (d >= from.size()) return false;
  from[d] = from_deg;
  std::vector<double> to = from;
  to[d] = to_deg;
  const std::string move = direction > 0 ? "turret index MGPOS" : "turret index MGNEG";
  const PathCheck c = guard_.guard().CheckMove(from, to);
  return StopAhead(guard_.Ahead(ContinuousMove::kTurretJog, move, from, to, c), move, from, to, c);
}

bool Channel::GuardSpindleStart(const std::string& move, const DriveSetpoint& sp) {
  if (!guard_.active() || config_.spindle_drive < 0) return true;
  // A spindle already turning sweeps its chuck now: the moves are checked against that. One
  // standing starts to turn on a speed, or on a position other than the one it holds (M19).
  const bool turning = sp_.command.mode == DriveMode::kVelocity && sp_.command.value != 0;
  const bool starts =
      sp.mode == DriveMode::kVelocity
          ? sp.value != 0
          : !(sp_.command.mode == DriveMode::kPosition && sp_.command.value == sp.value);
  if (turning || !starts) return true;
  const std::vector<double> at = GuardFrom();
  const PathCheck c = guard_.guard().CheckSpindleStart(at, config_.spindle_drive);
  if (c.clear) {
    guard_.Clear(move, at, at, c);
    return true;
  }
  return !GuardStops(move, at, at, c);
}

}  // namespace vmt::control::channel
