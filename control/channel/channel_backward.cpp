// The channel's side of backward travel (backward_travel.hpp): which blocks it records, whether
// a start may travel back and from where on the path, PathGuard's check of a decoded G00 leg,
// and the program going on once the travel is forward again at the interruption point.
#include <string>
#include <vector>

#include "control/channel/channel.hpp"

namespace vmt::control::channel {

void Channel::RecordPath(const BlockMotion& motion, bool rapid) {
  // Block search decodes without motion (bs_.state kActive): its blocks were never travelled.
  backward_.Record(motion, rapid, bs_.state == BlockSearchState::kActive);
}

void Channel::RefuseBackward(const std::string& why) {
  // A message with the program still held, like Q9998's: the next start clears it.
  error_ = "backward travel: " + why;
  error_number_ = kMsgBackward;
}

ReplayGuard Channel::ReplayGuardOf() {
  return [this](const std::string& move, const std::vector<double>& leg_end) {
    if (!guard_.active()) return false;
    const std::vector<double> from = GuardFrom();
    std::vector<double> to = from;
    for (size_t a = 0; a < config_.axes.size(); ++a)
      if (static_cast<size_t>(config_.axes[a].drive) < to.size())
        to[config_.axes[a].drive] = leg_end[a];
    const PathCheck c = guard_.guard().CheckMove(from, to);
    if (!c.clear) return GuardStops(move, from, to, c);
    guard_.Clear(move, from, to, c);
    return false;
  };
}

void Channel::StartReplay() {
  if (backward_.moving()) {  // a leg braking for feed hold: the start takes it up again
    backward_.Resume();
    return;
  }
  if (!backward_.backward_requested()) {  // away from the interruption point: forward, back to it
    ReplayArrived(backward_.Forward(out_.commanded, ReplayGuardOf()));
    return;
  }
  if (!backward_.away()) {
    // Where on the path the axes stand: inside the block in work, inside the continue block of
    // a block search, or at the end of the last block.
    if (repos_.run() || (repos_.interruption() && repos_.interruption()->left_contour)) {
      RefuseBackward("the axes are being repositioned; return them to the contour first");
      return;
    }
    for (double offset : bs_.offset)
      if (offset != 0) {
        // 4.2: "Bei einem Offset > 0 ist Rückwärtsfahren nicht möglich!"
        RefuseBackward("not possible with the offset of a manual return to the contour");
        return;
      }
    if (search_.active() && bs_.state != BlockSearchState::kInactive &&
        bs_.state != BlockSearchState::kWaitForContinueContour) {
      RefuseBackward("block search has not returned to the contour yet");
      return;
    }
    if (work_.active && work_.profile.rate != 0) {
      RefuseBackward("the axes are still braking");
      return;
    }
    double u = -1;
    if (work_.active && backward_.LastStepIs(work_.motion))
      u = work_.profile.u;
    else if (search_.active() && bs_.state == BlockSearchState::kWaitForContinueContour &&
             backward_.LastStepIs(search_.run().restart_motion))
      u = search_.run().restart_u;
    else if (backward_.AtLastStepEnd(out_.commanded))
      u = 1;
    if (!backward_.CanGoBackFrom(u)) {
      RefuseBackward(
          "no path behind the axes (the program's start, or a block backward travel "
          "cannot take: G74, a thread, measuring, G31)");
      return;
    }
    // Not jogged off: the interruption of a visit to manual mode is over.
    if (repos_.interruption()) repos_.Clear();
    backward_.BeginAt(out_.commanded, u);
  }
  ReplayArrived(backward_.Back(out_.commanded, ReplayGuardOf()));
}

void Channel::ReplayCycle(double dt) {
  ReplayArrived(backward_.Cycle(dt, override_, state_ == ChannelState::kHold, out_.commanded,
                                ReplayGuardOf()));
}

void Channel::ReplayArrived(ReplayStep step) {
  // Forward again at the interruption point: the program goes on from it, unless the operator
  // has asked for backward travel meanwhile.
  if (step == ReplayStep::kArrived && !backward_.backward_requested()) Start();
}

}  // namespace vmt::control::channel
