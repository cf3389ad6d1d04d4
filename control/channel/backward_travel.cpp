// Backward travel (block search manual 4.3, "Rückwärtsfahren"): block by block with an exact
// stop between them, at each block's own limits (feed, rapid) and the feed override; feed hold
// brakes on the path. The position is a step of the path memory and a parameter on it, so that
// a hold anywhere, and the way back from there, stays on the path.
//
// After block search the path is the one the search decoded up to the continue position: "in
// Rückwärtsrichtung ab der Startposition aus dem Satzvorlauf das real programmierte
// NC-Programm" - the axes go back along blocks they never travelled, so the G00 legs of those
// are asked of PathGuard first, as the return to the contour is: the stock the search skipped
// may still be there. Legs the axes did travel are clear by what happened (the stock only got
// smaller since), and a check would find the tool's own cut at their ends; feed legs are the
// program's cuts, not checked as the program's are not.
#include "control/channel/backward_travel.hpp"

#include <algorithm>
#include <cmath>

namespace vmt::control::channel {
namespace {

bool Near(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i] - b[i]) > 1e-6) return false;
  return true;
}

}  // namespace

void BackwardTravel::Record(const BlockMotion& motion, bool rapid, bool decoded) {
  if (!motion.moves) return;
  if (!Retraceable(motion)) return Forget();
  memory_.Push(motion, rapid, decoded);
}

bool BackwardTravel::LastStepIs(const BlockMotion& b) const {
  if (memory_.empty()) return false;
  const BlockMotion& a = memory_[memory_.size() - 1].motion;
  return a.moves && b.moves && a.start == b.start && a.end == b.end &&
         a.arc_axes[0] == b.arc_axes[0] && a.arc_sweep == b.arc_sweep && a.max_rate == b.max_rate;
}

bool BackwardTravel::AtLastStepEnd(const std::vector<double>& position) const {
  return !memory_.empty() && Near(position, memory_[memory_.size() - 1].motion.end);
}

bool BackwardTravel::CanGoBackFrom(double u) const {
  return u >= 0 && (u > 0 || memory_.size() >= 2);
}

void BackwardTravel::BeginAt(const std::vector<double>& position, double u) {
  PathReplay& r = replay_;
  r.away = true;
  r.home = position;
  r.index = memory_.size() - 1;
  r.u = u;
  r.home_u = u;
}

ReplayStep BackwardTravel::Back(std::vector<double>& commanded, const ReplayGuard& guard) {
  replay_.direction = -1;
  return StartLeg(commanded, guard);
}

ReplayStep BackwardTravel::Forward(std::vector<double>& commanded, const ReplayGuard& guard) {
  replay_.direction = 1;
  return StartLeg(commanded, guard);
}

ReplayStep BackwardTravel::StartLeg(std::vector<double>& commanded, const ReplayGuard& guard) {
  PathReplay& r = replay_;
  const size_t last = memory_.size() - 1;
  for (;;) {
    if (r.direction < 0 && r.u <= 0) {
      // The block before, if the path goes on into it (the memory has no gaps but where a
      // block it could not take was).
      if (r.index == 0 || !Near(memory_[r.index - 1].motion.end, memory_[r.index].motion.start)) {
        r.direction = 0;
        return ReplayStep::kMoving;  // the oldest block remembered: the axes stand at its start
      }
      --r.index;
      r.u = 1;
    }
    if (r.direction > 0 && r.index == last && r.u >= r.home_u) {
      // Back at the interruption point: the program goes on from it.
      commanded = r.home;
      r.away = false;
      r.direction = 0;
      return ReplayStep::kArrived;
    }
    if (r.direction > 0 && r.u >= 1) {
      ++r.index;
      r.u = 0;
    }
    const double to = r.direction < 0 ? 0 : r.index == last ? r.home_u : 1;
    const PathStep& step = memory_[r.index];
    r.leg = PieceOf(step.motion, r.u, to);
    r.leg_from = r.u;
    r.leg_to = to;
    if (!r.leg.moves) {
      r.u = to;
      continue;
    }
    if (step.rapid && step.decoded &&
        guard(r.direction < 0 ? "backward travel" : "forward travel", r.leg.end)) {
      r.direction = 0;
      return ReplayStep::kMoving;
    }
    r.profile = PathProfile{};
    r.profile.max_rate = r.leg.max_rate;
    r.profile.max_accel = r.leg.max_accel;
    r.profile.max_jerk = r.leg.max_jerk;
    r.stopping = false;
    return ReplayStep::kMoving;
  }
}

ReplayStep BackwardTravel::Cycle(double dt, double override, bool held,
                                 std::vector<double>& commanded, const ReplayGuard& guard) {
  PathReplay& r = replay_;
  if (r.direction == 0) return ReplayStep::kMoving;
  if (!held) {
    r.direction = 0;
    return ReplayStep::kMoving;
  }
  r.profile.Advance(dt, r.stopping ? 0.0 : override);
  r.leg.PointAt(std::min(r.profile.u, 1.0), commanded);
  if (r.profile.done()) {
    r.u = r.leg_to;
    memory_[r.index].motion.PointAt(r.u, commanded);
    if (r.stopping) {
      r.direction = 0;
      return ReplayStep::kMoving;
    }
    return StartLeg(commanded, guard);
  }
  if (r.stopping && r.profile.rate <= 0) {
    // Feed hold: at rest on the path, somewhere inside the step.
    r.u = r.leg_from + (r.leg_to - r.leg_from) * r.profile.u;
    r.direction = 0;
  }
  return ReplayStep::kMoving;
}

std::optional<std::vector<double>> BackwardTravel::Leave() {
  if (!replay_.away) return std::nullopt;
  replay_.away = false;
  return replay_.home;
}

void BackwardTravel::Reset() {
  memory_.Clear();
  const bool backward = replay_.backward_requested;
  replay_ = PathReplay{};
  replay_.backward_requested = backward;
}

}  // namespace vmt::control::channel
