// The channel's side of its spindle-synchronous blocks (synchronous_block.hpp): they select
// main spindle mode on a headstock (C-axis manual 4.2, ModeNeeded), which the block waits for
// like M3, and an error of theirs is the channel's at the block.
#include "control/channel/channel.hpp"

namespace vmt::control::channel {

SynchronousContext Channel::SynchronousContextNow() {
  return {work_.block, work_.motion, work_.profile, out_.commanded, sp_};
}

bool Channel::StartSynchronous(const AmplifierTelegram& at) {
  bool moves = false;
  if (const auto error = sync_.Start(SynchronousContextNow(), frames_.translation,
                                     FollowUpAxes(work_.block), at, moves)) {
    Fail(*ProgramOf(work_.block.program), work_.block.block, error->text, error->number);
    return false;
  }
  work_.continuation_ready = false;
  work_.targets.clear();
  if (moves) work_.active = true;
  return true;
}

void Channel::SynchronousCycle(const AmplifierTelegram& at, double dt) {
  if (const auto error = sync_.Cycle(SynchronousContextNow(), at, dt, SpindleSetpoint().value)) {
    Fail(*ProgramOf(work_.block.program), work_.block.block, error->text, error->number);
    return;
  }
  if (!sync_.active()) work_.active = false;  // at the programmed end point
}

}  // namespace vmt::control::channel
