#include "control/channel/headstock_control.hpp"

#include "control/channel/further_spindles.hpp"

namespace vmt::control::channel {

void HeadstockControl::PowerOn() {
  // At the first NC cycle, whether or not the channel has taken its axes over yet, the NC
  // assumes the mode the PLC presents by ROTMOD_Q / SPMOD_Q and makes its drive parameter set
  // the one in force. Neither (or both) presented: no mode, and a changeover at the next
  // occasion that needs one.
  if (!changeover_ || known_) return;
  changeover_->TakeModeFromPlc(plc_);
  known_ = true;
  if (changeover_->mode() != axes::HeadstockMode::kNone) shown_mode_ = changeover_->mode();
}

bool HeadstockControl::RotaryReady() const {
  return changeover_->config().separate_servo() ? plc_.rotary_ready : plc_.spindle_ready;
}

std::optional<std::string> HeadstockControl::Cycle(const HeadstockCycleInput& in,
                                                   const AmplifierTelegram& at, double dt_s) {
  axes::HeadstockPlc plc = plc_;
  // Section 2: one axis, one AxxC.READY (4.2), whichever signal a caller filled in.
  plc.rotary_ready = rotary_ready_ = RotaryReady();
  const bool interrupted = in.hold && !manual_;
  plc.stop = plc.stop || interrupted || in.failed || !in.process_enabled;
  std::optional<std::string> error;
  if (!changeover_->Cycle(plc, at, dt_s) && !in.failed) error = changeover_->error();
  if (!changeover_->busy()) manual_ = false;
  // A key may have left the other mode, or neither (2.3 Jogging Movements): the block that
  // waits commands its changeover again at the next opportunity.
  if (waiting() && in.running && !error && !changeover_->busy() &&
      changeover_->mode() != waiting_for_)
    changeover_->Request(waiting_for_);
  // Position indication (2.3): the designation of the new mode once the changeover is done.
  if (changeover_->mode() != axes::HeadstockMode::kNone) shown_mode_ = changeover_->mode();
  return error;
}

bool HeadstockControl::RotaryFollowsFeedback() {
  const bool positioned =
      changeover_->mode() == axes::HeadstockMode::kRotary ||
      (changeover_->config().separate_servo() && !changeover_->busy() && rotary_ready_);
  return changeover_->TakeOverRotary() || !positioned || !rotary_ready_;
}

axes::HeadstockMode HeadstockControl::ModeNeeded(const nc::PreparedBlock& b, int rotary_axis) {
  // C-axis manual 4.2: G00/G01/G02/G03 with the rotary axis' name select rotary axis mode;
  // M3, M4, M5, M19 (and G33, G63, G64) spindle mode.
  for (const nc::AuxFunction& f : b.aux)
    if (f.letter == 'M' && SpindleIndex(f.index) == 1 &&
        (f.value == 3 || f.value == 4 || f.value == 5 || f.value == 19))
      return axes::HeadstockMode::kSpindle;
  if (nc::SpindleSynchronous(b.motion)) return axes::HeadstockMode::kSpindle;
  // G77 S1=0 restores the spindle in spindle mode, G77 C0 the rotary axis in rotary axis mode
  // (REPOS manual 4.2).
  if (b.repos)
    for (const nc::AuxFunction& f : b.aux)
      if (f.letter == 'S' && f.index <= 1) return axes::HeadstockMode::kSpindle;
  // X1/Y1 of a coordinate transformation need rotary axis mode but do not select it: without
  // it the block is an error (block_motion.cpp).
  if (b.fictive) return axes::HeadstockMode::kNone;
  const bool interpolates = b.motion == nc::Motion::kRapid || b.motion == nc::Motion::kLinear ||
                            b.motion == nc::Motion::kArcCw || b.motion == nc::Motion::kArcCcw;
  // G74 of the rotary axis homes it in position control: rotary axis mode too (the manual
  // names G74 as a way to home, 2.3, but not its mode; only rotary mode positions C).
  if ((interpolates || b.homing || b.repos) && (b.programmed >> rotary_axis & 1))
    return axes::HeadstockMode::kRotary;
  return axes::HeadstockMode::kNone;
}

void HeadstockControl::RequestForBlock(axes::HeadstockMode mode) {
  changeover_->Request(mode);
  manual_ = false;
  waiting_for_ = mode;
}

void HeadstockControl::ManualChangeover(axes::HeadstockMode target, bool program_stopped) {
  if (changeover_->busy() && !manual_ && program_stopped) changeover_->Abandon();
  changeover_->Request(target);
  if (changeover_->busy()) manual_ = true;
}

void HeadstockControl::Abandon() {
  if (changeover_) changeover_->Abandon();
  waiting_for_ = axes::HeadstockMode::kNone;
}

void HeadstockControl::TakeModeFromPlc() {
  if (changeover_) changeover_->TakeModeFromPlc(plc_);
  waiting_for_ = axes::HeadstockMode::kNone;
}

uint64_t HeadstockControl::FollowUpAxes(const nc::PreparedBlock& b, int rotary_axis) const {
  // Outside rotary axis mode the rotary axis tracks its actual position (the channel's headstock
  // cycle); a block that does not program it leaves it there rather than moving it back to where
  // the program last put it (with a load-side encoder it reads the turning spindle).
  if (!changeover_ || rotary_axis < 0 || changeover_->mode() == axes::HeadstockMode::kRotary)
    return 0;
  const uint64_t bit = uint64_t{1} << rotary_axis;
  // X1/Y1 program C but position it only in rotary axis mode (coordinate_transformation.hpp).
  return b.programmed & bit && !b.fictive ? 0 : bit;
}

}  // namespace vmt::control::channel
