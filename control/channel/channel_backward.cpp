// Backward travel (block search manual 4.3, "Rückwärtsfahren"): while the program is held the
// NC travels the path of its last blocks in reverse and forward again to the interruption point,
// from where the program goes on. After block search the path is the one the search decoded up
// to the continue position: "in Rückwärtsrichtung ab der Startposition aus dem Satzvorlauf das
// real programmierte NC-Programm" - the axes go back along blocks they never travelled, so the
// G00 legs of those are asked of PathGuard first, as the return to the contour is: the stock
// the search skipped may still be there. Legs the axes did travel are clear by what happened
// (the stock only got smaller since), and a check would find the tool's own cut at their ends;
// feed legs are the program's cuts, not checked as the program's are not.
//
// Block by block with an exact stop between them, at each block's own limits (feed, rapid) and
// the feed override; feed hold brakes on the path. The position is a step of the path memory
// and a parameter on it, so that a hold anywhere, and the way back from there, stays on the
// path.
#include <cmath>

#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

/// The same motion: `a` was copied from `b` when its block started (RecordPath).
bool SameMotion(const BlockMotion& a, const BlockMotion& b) {
  return a.moves && b.moves && a.start == b.start && a.end == b.end &&
         a.arc_axes[0] == b.arc_axes[0] && a.arc_sweep == b.arc_sweep &&
         a.max_rate == b.max_rate;
}

bool Near(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i] - b[i]) > 1e-6) return false;
  return true;
}

}  // namespace

void Channel::RecordPath(const BlockMotion& motion, bool rapid) {
  if (!motion.moves) return;
  if (!Retraceable(motion)) return PathBarrier();
  // Block search decodes without motion (bs_.state kActive): its blocks were never travelled.
  path_memory_.Push(motion, rapid, bs_.state == BlockSearchState::kActive);
}

void Channel::RefuseBackward(const std::string& why) {
  // A message with the program still held, like Q9998's: the next start clears it.
  error_ = "backward travel: " + why;
  error_number_ = kMsgBackward;
}

void Channel::StartReplay() {
  PathReplay& r = replay_;
  if (r.direction != 0) {  // a leg braking for feed hold: the start takes it up again
    r.stopping = false;
    return;
  }
  if (!r.backward_requested) {  // away from the interruption point: forward, back to it
    r.direction = 1;
    StartReplayLeg();
    return;
  }
  if (!r.away) {
    // Where on the path the axes stand: inside the block in work, inside the continue block of
    // a block search, or at the end of the last block.
    if (repos_.run || (repos_.interruption && repos_.interruption->left_contour)) {
      RefuseBackward("the axes are being repositioned; return them to the contour first");
      return;
    }
    for (double offset : bs_.offset)
      if (offset != 0) {
        // 4.2: "Bei einem Offset > 0 ist Rückwärtsfahren nicht möglich!"
        RefuseBackward("not possible with the offset of a manual return to the contour");
        return;
      }
    if (search_ && bs_.state != BlockSearchState::kInactive &&
        bs_.state != BlockSearchState::kWaitForContinueContour) {
      RefuseBackward("block search has not returned to the contour yet");
      return;
    }
    if (work_.active && work_.profile.rate != 0) {
      RefuseBackward("the axes are still braking");
      return;
    }
    double u = -1;
    if (!path_memory_.empty()) {
      const BlockMotion& last = path_memory_.back().motion;
      if (work_.active && SameMotion(last, work_.motion))
        u = work_.profile.u;
      else if (search_ && bs_.state == BlockSearchState::kWaitForContinueContour &&
               SameMotion(last, search_->restart_motion))
        u = search_->restart_u;
      else if (Near(commanded_, last.end))
        u = 1;
    }
    if (u < 0 || (u <= 0 && path_memory_.size() < 2)) {
      RefuseBackward("no path behind the axes (the program's start, or a block backward travel "
                     "cannot take: G74, a thread, measuring, G31)");
      return;
    }
    // Not jogged off: the interruption of a visit to manual mode is over.
    if (repos_.interruption) ClearRepos();
    r.away = true;
    r.home = commanded_;
    r.index = path_memory_.size() - 1;
    r.u = u;
    r.home_u = u;
  }
  r.direction = -1;
  StartReplayLeg();
}

void Channel::StartReplayLeg() {
  PathReplay& r = replay_;
  const size_t last = path_memory_.size() - 1;
  for (;;) {
    if (r.direction < 0 && r.u <= 0) {
      // The block before, if the path goes on into it (the memory has no gaps but where a
      // block it could not take was).
      if (r.index == 0 ||
          !Near(path_memory_[r.index - 1].motion.end, path_memory_[r.index].motion.start)) {
        r.direction = 0;
        return;  // the oldest block remembered: the axes stand at its start
      }
      --r.index;
      r.u = 1;
    }
    if (r.direction > 0 && r.index == last && r.u >= r.home_u) {
      // Back at the interruption point: the program goes on from it.
      commanded_ = r.home;
      r.away = false;
      r.direction = 0;
      if (!r.backward_requested) Start();
      return;
    }
    if (r.direction > 0 && r.u >= 1) {
      ++r.index;
      r.u = 0;
    }
    const double to = r.direction < 0 ? 0 : r.index == last ? r.home_u : 1;
    const PathStep& step = path_memory_[r.index];
    r.leg = PieceOf(step.motion, r.u, to);
    r.leg_from = r.u;
    r.leg_to = to;
    if (!r.leg.moves) {
      r.u = to;
      continue;
    }
    if (step.rapid && step.decoded && guarded_.guard && config_.path_guard != GuardReaction::kOff) {
      const std::string move = r.direction < 0 ? "backward travel" : "forward travel";
      const std::vector<double> from = GuardFrom();
      std::vector<double> to_drives = from;
      for (size_t a = 0; a < config_.axes.size(); ++a)
        if (static_cast<size_t>(config_.axes[a].drive) < to_drives.size())
          to_drives[config_.axes[a].drive] = r.leg.end[a];
      const PathCheck c = guarded_.guard->CheckMove(from, to_drives);
      if (c.clear) {
        guarded_.records.push_back({move, from, to_drives, c, 1, false});
      } else if (GuardStops(move, from, to_drives, c)) {
        r.direction = 0;
        return;
      }
    }
    r.profile = PathProfile{};
    r.profile.max_rate = r.leg.max_rate;
    r.profile.max_accel = r.leg.max_accel;
    r.profile.max_jerk = r.leg.max_jerk;
    r.stopping = false;
    return;
  }
}

void Channel::ReplayCycle(double dt) {
  PathReplay& r = replay_;
  if (r.direction == 0) return;
  if (state_ != ChannelState::kHold) {
    r.direction = 0;
    return;
  }
  r.profile.Advance(dt, r.stopping ? 0.0 : override_);
  r.leg.PointAt(std::min(r.profile.u, 1.0), commanded_);
  if (r.profile.done()) {
    r.u = r.leg_to;
    path_memory_[r.index].motion.PointAt(r.u, commanded_);
    if (r.stopping) {
      r.direction = 0;
      return;
    }
    StartReplayLeg();
    return;
  }
  if (r.stopping && r.profile.rate <= 0) {
    // Feed hold: at rest on the path, somewhere inside the step.
    r.u = r.leg_from + (r.leg_to - r.leg_from) * r.profile.u;
    r.direction = 0;
  }
}

}  // namespace vmt::control::channel
