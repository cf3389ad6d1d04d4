// The channel's side of fast measurement (fast_measurement.hpp): what the measuring run is
// handed for one call, and the motion of the blocks an instruction generates, planned as the
// channel plans its own blocks. An error it reports is the channel's, at the instruction's block.
#include "control/channel/channel.hpp"

namespace vmt::control::channel {

MeasuringLink Channel::MeasuringLinkNow() {
  return {
      work_,
      out_.commanded,
      frames_.translation,
      state_,
      events_,
      aux_,
      [this](uint32_t index) -> const nc::Program& { return *ProgramOf(index); },
      [this](const nc::ModalState& modal) { return TranslationOf(modal); },
      [this](const nc::ModalState& modal, uint32_t program, int32_t block) {
        return UpdateTranslation(modal, *ProgramOf(program), block);
      },
      [this] { return PlanGeneratedMotion(); },
      [this](const std::string& move, const std::vector<double>* end, bool measuring_path) {
        return GuardBlockMove(move, end, measuring_path);
      },
      [this](const MeasuringError& e) {
        if (e.block < 0) return Fail(e.text, e.number);
        const nc::Program& program = *ProgramOf(e.program);
        if (!e.hold) return Fail(program, e.block, e.text, e.number);
        state_ = ChannelState::kHold;
        error_ =
            nc::Format({program.blocks[static_cast<size_t>(e.block)].pos, e.text}, program.files);
        error_number_ = e.number;
      },
  };
}

bool Channel::PlanGeneratedMotion() {
  const nc::PreparedBlock& b = work_.block;
  const nc::Program& program = *ProgramOf(b.program);
  for (size_t a = 0; a < out_.commanded.size(); ++a)
    if (!frames_.homed[a] && (b.programmed >> a & 1)) {
      Fail(program, b.block,
           "axis " + config_.axes[a].name + " has no reference: home it first (G74)", kMsgNotHomed);
      return false;
    }
  sync_.Clear();
  if (const auto error =
          PlanBlockMotion(work_.block, out_.commanded, frames_.translation, config_.axes, 0,
                          work_.motion, FollowUpAxes(work_.block))) {
    Fail(program, b.block, error->text, error->number);
    return false;
  }
  look_.carry_speed = look_.carry_accel = look_.carry_leftover = 0;
  return true;
}

}  // namespace vmt::control::channel
