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
// Measuring: a measuring cycle cannot measure without motion. SETTING, SAVE and RESTORE only
// set state and run as in a run (their Q functions to the PLC included). MOVE, PROBE, COMPARE and CORRECTION are simulated as their
// programmed path (the stylus ends where the plan's last move ends), nothing is measured and
// nothing written: measuring pages, results, tool wear and the reverse vectors keep their
// former values, and the search reports a warning naming the block. A continue position in a
// measuring block is refused: the search would skip its measurement.
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
  headstock_->Request(need);
  hs_.manual = false;
  hs_.waiting_for = need;
  return false;
}

void Channel::EndSearchChangeover(nc::PreparedBlock& b) {
  BlockSearchRun& s = *search_;
  const axes::HeadstockMode mode = hs_.waiting_for;
  hs_.waiting_for = axes::HeadstockMode::kNone;
  s.changed_over = true;
  if (mode != axes::HeadstockMode::kRotary) return;
  // Rotary axis mode starts where C stands (HeadstockCycle keeps its command value on the
  // actual position, with the rotary offsets back): the search's C is there too.
  const size_t r = static_cast<size_t>(config_.rotary_axis);
  s.position[r] = out_.commanded[r];
  // RebaseRotaryAxis: an increment counts from here; the interpreter goes on from the block's
  // corrected end. Under G41/G42 the blocks ahead are prepared already, as in a run.
  if (work_.compensating || b.homing) return;
  const double actual = out_.commanded[r] - frames_.translation[r];
  if (b.modal.incremental && (b.programmed >> r & 1)) b.target[r] += actual - s.rotary_start;
  work_.interpreter->SetAxisPosition(r, b.target[r]);
}

bool Channel::SimulateMeasuringInstruction(const nc::PreparedBlock& b) {
  BlockSearchRun& s = *search_;
  const nc::Program& program = *ProgramOf(b.program);
  auto fail = [&](const std::string& text) {
    Fail(program, b.block, text, kMsgMeasuringInstruction);
    return false;
  };
  if (b.calls.size() > 1)
    return fail("only one measuring instruction may be programmed in a block (4.1)");
  if (!meas_.pages) return fail("fast measurement needs its machine data pages (7.1)");
  const nc::InstructionCall& call = b.calls.front();
  // The context where the program has the stylus, not where it stands (the search moves none).
  measure::MeasuringContext context = MeasuringContextNow();
  context.compensation = b.modal.compensation;
  for (int n = 0; n < 3; ++n)
    if (const int a = SettingAxis(n); a >= 0)
      context.position[n] +=
          s.position[static_cast<size_t>(a)] - out_.commanded[static_cast<size_t>(a)];
  // Planned on copies: only what the instruction sets as state is taken over below.
  measure::MeasuringPages pages = *meas_.pages;
  measure::ReverseVectors reverse = meas_.reverse_vectors;
  const measure::MeasuringPlan plan = measure::PlanInstruction(call, context, pages, reverse);
  if (!plan.error.empty()) return fail(plan.error);
  if (call.instruction == nc::Instruction::kSetting || call.instruction == nc::Instruction::kSave ||
      call.instruction == nc::Instruction::kRestore) {
    // No motion, no measurement: as in a run (StartMeasuring).
    *meas_.pages = pages;
    ApplyMeasuringState(plan);
    // Their Q functions (SETTING's Q9992, 6.1) go to the PLC and wait for it, as in a run.
    if (config_.aux_handshake) {
      for (const measure::MeasuringStep& step : plan.steps)
        if (step.kind == measure::MeasuringStep::Kind::kAux)
          aux_.functions.push_back({'Q', 0, static_cast<double>(step.q)});
      if (!aux_.functions.empty()) ++aux_.strobe;
    }
    return true;
  }
  // The programmed path: the stylus' sphere centre ends where the plan's last move ends (a
  // measuring path at its programmed end: there is no contact to stop it).
  for (const measure::MeasuringStep& step : plan.steps) {
    if (step.kind != measure::MeasuringStep::Kind::kRapid &&
        step.kind != measure::MeasuringStep::Kind::kMeasure)
      continue;
    const std::vector<double> t = StylusTranslation(step.sphere);
    for (int n = 0; n < 3; ++n) {
      const int a = SettingAxis(n);
      if (a < 0 || !(step.axes >> n & 1)) continue;
      const auto i = static_cast<size_t>(a);
      s.position[i] = step.target[static_cast<size_t>(n)] + t[i];
    }
  }
  // Section 8: the operator has to know that nothing was measured.
  const nc::SourcePos& at = program.blocks[static_cast<size_t>(b.block)].pos;
  bs_.warnings.push_back(program.files[at.file] + ":" + std::to_string(at.line) + ":" +
                         std::to_string(at.column) + ": warning: measuring instruction " +
                         nc::InstructionName(call.instruction) +
                         " simulated without measuring in block search: its results keep "
                         "their former values");
  return true;
}

}  // namespace vmt::control::channel
