// Technology in the skipped part of a block search (twincat-cnc-block-search-de.md 2: "alle
// Technologiefunktionen ... an die SPS ausgegeben und quittiert"; 8: technology in the restart
// block is only simulated): the spindle / rotary axis changeover (mtc200-c-axis.md) and the
// measuring instructions of fast measurement (mtc200-fast-measurement.md).
//
// Changeover: the search requests it as a run does (ROTMOD / SPMOD to the PLC, its clutch
// sequence and acknowledgement) and waits, so the headstock is in the program's mode at the
// continue position. No axis moves, so C counts from where the changeover found it (where the
// spindle stood), exactly as RebaseRotaryAxis has it in a run: an absolute C is where the
// uninterrupted run has it, an increment after the changeover counts from the standing C. The
// return to the contour takes C to its continue position in rotary axis mode (with the other
// axes, or first under #CAX TRACK); in spindle mode C is not positioned and stays.
//
// Measuring (FastMeasurement::Simulate): a measuring cycle cannot measure without motion. SETTING,
// SAVE and RESTORE only set state and run as in a run (their Q functions to the PLC included).
// MOVE, PROBE, COMPARE and CORRECTION are simulated as their programmed path (the stylus ends where
// the plan's last move ends), nothing is measured and nothing written: measuring pages, results,
// tool wear and the reverse vectors keep their former values, and the search reports a warning
// naming the block. A continue position in a measuring block is refused: the search would skip its
// measurement.
#include "control/channel/channel.hpp"

namespace vmt::control::channel {

bool Channel::SearchChangeover(const nc::PreparedBlock& b) {
  BlockSearchRun& s = *search_;
  if (!headstock_ || s.changed_over) {
    s.changed_over = false;
    return true;
  }
  const axes::HeadstockMode need = ModeNeeded(b);
  if (need == axes::HeadstockMode::kNone || headstock_->mode() == need) return true;
  // C-axis manual 1.2: block preparation waits until the changeover ends; the PLC's sequence
  // runs as in normal running (HeadstockCycle repeats the request if a key turned it round).
  headstock_.RequestForBlock(need);
  return false;
}

void Channel::EndSearchChangeover(nc::PreparedBlock& b) {
  BlockSearchRun& s = *search_;
  const axes::HeadstockMode mode = headstock_.EndWait();
  s.changed_over = true;
  if (mode != axes::HeadstockMode::kRotary) return;
  // Rotary axis mode starts where C stands (HeadstockCycle keeps its command value on the
  // actual position, with the rotary offsets back): the search's C is there too.
  const size_t r = static_cast<size_t>(config_.rotary_axis);
  s.position[r] = out_.commanded[r];
  // RebaseRotaryAxis: an increment counts from here; the interpreter goes on from the block's
  // corrected end. Under G41/G42 the blocks ahead are prepared already, as in a run.
  if (work_.feed.compensating() || b.homing) return;
  const double actual = out_.commanded[r] - frames_.translation[r];
  if (b.modal.incremental && (b.programmed >> r & 1)) b.target[r] += actual - s.rotary_start;
  work_.interpreter->SetAxisPosition(r, b.target[r]);
}

}  // namespace vmt::control::channel
