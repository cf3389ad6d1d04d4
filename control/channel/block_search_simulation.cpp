// The skipped blocks of a block search. Technology goes to the PLC and is acknowledged as in a
// normal run (block search 2), technology of the continue block is only simulated (8).
//
// A spindle / rotary axis changeover (mtc200-c-axis.md) runs as in a run: the search requests
// it (ROTMOD / SPMOD to the PLC, its clutch sequence and acknowledgement) and waits, so the
// headstock is in the program's mode at the continue position. No axis moves, so C counts from
// where the changeover found it (where the spindle stood), exactly as a run rebases it: an
// absolute C is where the uninterrupted run has it, an increment after the changeover counts
// from the standing C.
//
// Measuring instructions (FastMeasurement::Simulate) cannot measure without motion: SETTING,
// SAVE and RESTORE only set state and run as in a run; MOVE, PROBE, COMPARE and CORRECTION
// follow their programmed path, measure and write nothing, and leave a warning. A continue
// position inside a measuring block is refused: the search would skip its measurement.
#include "control/channel/block_search_simulation.hpp"

#include <cmath>
#include <string>

#include "control/channel/block_search_support.hpp"
#include "control/channel/channel_messages.hpp"
#include "control/channel/continue_position.hpp"
#include "control/channel/further_spindles.hpp"
#include "control/channel/spindle_functions.hpp"
#include "control/nc/coordinate_transformation.hpp"

namespace vmt::control::channel {
namespace {

constexpr const char* kNotFound =
    "P-ERR-20704: the continue position was not found; the program ended in block search mode";

}  // namespace

void BlockSearchSimulation::Begin(const BlockSearchParameters& p,
                                  const std::vector<double>& position,
                                  const DriveSetpoint& spindle) {
  run_.emplace(p);
  run_->position = position;
  run_->spindle = spindle;
}

bool BlockSearchSimulation::GoesOn(const SearchLink& link) {
  return link.data.state == BlockSearchState::kActive && link.aux.functions.empty() &&
         !link.headstock.waiting() && link.state == ChannelState::kRunning;
}

bool BlockSearchSimulation::ChangeoverEnded(const SearchLink& link, nc::PreparedBlock& b) {
  // The block waits for its changeover as in a run.
  if (!link.headstock.waiting() || link.headstock->mode() != link.headstock.waiting_for())
    return true;
  EndChangeover(link, b);
  return SimulateBlock(link, b);
}

void BlockSearchSimulation::EndsProgram(const SearchLink& link, const char* warning) {
  if (warning) link.data.warnings.push_back(warning);
  run_->ends_program = true;
  link.data.state = BlockSearchState::kWaitForPlcOff;
}

bool BlockSearchSimulation::SimulateBlock(const SearchLink& link, nc::PreparedBlock& b) {
  BlockSearchRun& s = *run_;
  const BlockSearchParameters& started = link.data.started;
  if (b.block < 0) {  // the end of the text, or type 1's end position (the reader)
    // Type 1's end position before its continue position: nothing is left to machine.
    if (s.end_reached)
      EndsProgram(link, "the end position came before the continue position");
    else
      EndsProgram(link, started.type != BlockSearchType::kProgramEnd ? kNotFound : nullptr);
    return true;
  }
  const nc::Program& program = link.program_of(b.program);
  auto fail = [&](const std::string& text, int number) {
    link.fail(program, b.block, text, number);
    return false;
  };
  // A further piece of a block's tip path: its functions ran with the first.
  if (s.further_piece) return SimulateMotion(link, b, false);
  // A spindle / rotary axis changeover runs as in a run; the block waits for its end.
  if (!Changeover(link, b)) return true;
  const bool boundary = !s.found && s.matcher.Matches(b, program, b.program);
  if (boundary && b.search_locked)
    return fail(
        "P-ERR-21399: the continue position lies in a region locked for block search "
        "(#BLOCKSEARCH LOCKED)",
        kMsgBlockSearchLocked);
  // 4.1.2: reference moves and measuring moves end on an external signal; up to the block
  // boundary they are simulated, beyond it (the search by distance) they cannot be.
  if (s.by_distance && (b.homing || b.measuring))
    return fail(std::string(b.homing ? "G74" : "G100") +
                    " between the block of the continue position and its distance from program "
                    "start cannot be simulated (block search 4.1.2)",
                kMsgBlockSearch);
  if (b.repos) return fail("G77 cannot run in block search", kMsgBlockSearch);
  // The search restores the main spindle's speed before the return to the contour; the further
  // spindles' it does not keep, so their words stop the search rather than be lost.
  for (const nc::AuxFunction& f : b.aux)
    if ((f.letter == 'S' || f.letter == 'M') && SpindleIndex(f.index) >= 2)
      return fail(std::string(1, f.letter) + std::to_string(f.index) +
                      "=: block search does not carry further spindles (Sj=, Mj= with j >= 2) "
                      "to the continue position",
                  kMsgBlockSearch);
  if (!b.calls.empty()) {
    // Section 8: the search cannot measure; the continue position after the instruction can.
    if (boundary)
      return fail("the continue position lies in measuring instruction " +
                      std::string(nc::InstructionName(b.calls.front().instruction)) +
                      ": block search cannot measure without motion (section 8); continue at "
                      "the block after it",
                  kMsgBlockSearch);
    return link.simulate_measuring(b, s.position);
  }
  if (!SimulateTechnology(link, b, program)) return false;
  return SimulateMotion(link, b, boundary);
}

bool BlockSearchSimulation::SimulateTechnology(const SearchLink& link, nc::PreparedBlock& b,
                                               const nc::Program& program) {
  BlockSearchRun& s = *run_;
  for (uint32_t index : b.instructions) {
    const nc::Statement& st = program.statements[index];
    if (st.kind == nc::Statement::Kind::kHashCommand) {
      if (const std::string refused = RefusedHashCommand(st.hash); !refused.empty()) {
        link.fail_message(nc::Format({st.pos, refused}, program.files), kMsgNotAvailable);
        return false;
      }
      // 4.2.2: the C axis tracks the contour in the search as in the run.
      const int c = link.tracked_axis;
      if (const auto done = link.cax_instruction(program, st, b,
                                                 c < 0 ? 0 : s.position[static_cast<size_t>(c)])) {
        if (!*done) return false;
        continue;
      }
      if (SteersBlockSearch(st.hash)) continue;
    }
    link.fail(program, b.block,
              "instruction " +
                  (st.kind == nc::Statement::Kind::kHashCommand ? "#" + program.texts[st.text]
                                                                : program.symbols.Name(st.name)) +
                  " is not supported in block search by vmt (docs/conformance.md)",
              kMsgNotAvailable);
    return false;
  }
  for (const auto& [n, set] : b.events) {
    link.events.own[n] = set;
    if (link.events.sink) link.events.sink(n, set);
  }
  link.data.program_distance.Command(b.distance_command);
  if (!link.take_offsets(b.modal, program, b.block)) return false;
  ProgramFrames& frames = link.frames;
  if (b.set_position)
    for (size_t a = 0; a < s.position.size(); ++a)
      if (b.programmed >> a & 1) {
        frames.shift[a] += s.position[a] - (b.target[a] + frames.translation[a]);
        frames.translation[a] = s.position[a] - b.target[a];
        if (link.headstock && static_cast<int>(a) == link.config.rotary_axis)
          link.headstock.set_rotary_translation(frames.translation[a]);
      }
  MainSpindleFunctions(b, link.config.spindle_drive, s.spindle);
  // An NC-controlled turret is technology too: the T word indexes it now, as in a run.
  if (link.index_tool_storage && !link.index_tool_storage(b, program)) return false;
  // Technology goes to the PLC as in a normal run (2): it switches coolant, turret, ... now.
  if (link.config.aux_handshake) {
    AuxOutput& aux = link.aux;
    for (const nc::AuxFunction& f : b.aux)
      if (f.letter == 'M' || f.letter == 'H' || f.letter == 'Q' || f.letter == 'T')
        aux.functions.push_back(f);
    if (!aux.functions.empty()) ++aux.strobe;
  }
  return true;
}

bool BlockSearchSimulation::SimulateMotion(const SearchLink& link, nc::PreparedBlock& b,
                                           bool boundary) {
  BlockSearchRun& s = *run_;
  BlockSearchData& data = link.data;
  // The block's path from where the program has the axes. G74 is left out (8: the axes stay),
  // G100 becomes a G01 to its target (8), a thread the straight line it is. Under G41/G42 the
  // block is a piece of the tip path (the reader): planned as the run plans it.
  BlockMotion motion;
  if ((b.motion != nc::Motion::kNone || b.measuring) && !b.homing) {
    nc::PreparedBlock m = b;
    if (m.measuring || nc::SpindleSynchronous(m.motion)) {
      m.motion = nc::Motion::kLinear;
      m.modal.feed_per_revolution = false;
      if (m.modal.feed <= 0) m.modal.feed = 1;  // the geometry only: no time passes
    }
    const double rev_per_s = s.spindle.mode == DriveMode::kVelocity ? s.spindle.value / 360 : 0;
    // #CAX TRACK: C as the run turns it; a turn beyond ANGLIMIT before the block is
    // simulated, so that C stands at the block's tangent from its start.
    std::optional<double> align;
    if (link.cax.command && !link.track_c(m, s.position, std::abs(rev_per_s), align)) return false;
    if (align) s.position[static_cast<size_t>(link.tracked_axis)] = *align;
    if (const auto error = PlanBlockMotion(
            m, s.position, link.frames.translation, link.config.axes, std::abs(rev_per_s), motion,
            link.headstock.FollowUpAxes(m, link.config.rotary_axis))) {
      link.fail(link.program_of(b.program), b.block, error->text, error->number);
      return false;
    }
  }
  if (b.homing) {
    // The interpreter took G74's words for targets; they are the homing order (ISG) or a
    // placeholder (MTC200), never positions. The skipped G74 leaves the axes where the program
    // had them (8), and the blocks after it count from there, as after a run's G74 they count
    // from the reference points.
    for (size_t a = 0; a < s.position.size(); ++a)
      if (b.programmed >> a & 1)
        link.interpreter.SetAxisPosition(a, s.position[a] - link.frames.translation[a]);
  }
  const double length = data.program_distance.LengthOf(motion, link.config.axes);
  if (boundary || s.Deciding()) {
    const ContinueStep step =
        DecideContinue(s, data.started, motion, length, data.program_distance.distance(), boundary);
    if (step.distance_passed)
      data.warnings.push_back(
          DistancePassedWarning(data.started, data.program_distance.distance()));
    if (step.found) return FoundContinuePosition(link, b, motion, step.u);
  }
  if (motion.moves) s.position = motion.end;
  data.program_distance.Pass(length);
  if (data.program_distance.BreakpointBefore(data.program_distance.distance()))
    return BreakpointAfter(link, data.program_distance.distance(), b);
  // The decoded path, for backward travel from the continue position (4.3); not to the
  // program's end (type 5), where the program ends in search mode.
  RecordPath(link, b, motion, data.started.type != BlockSearchType::kProgramEnd);
  if (b.end)
    EndsProgram(link, data.started.type != BlockSearchType::kProgramEnd ? kNotFound : nullptr);
  return true;
}

bool BlockSearchSimulation::BreakpointAfter(const SearchLink& link, double continue_mm,
                                            const nc::PreparedBlock& b) {
  // 3.5 requires the breakpoint to lie after the continue position. vmt reads a breakpoint
  // the search passes as a wrong parameter, not as one to drop: the operator asked
  // for a stop and machining must not run on without it. The search stops with an error where
  // it meets the breakpoint, before any axis moves; a breakpoint at the continue position
  // itself holds as soon as machining goes on there.
  const ProgramDistance& distance = link.data.program_distance;
  if (!distance.BreakpointBefore(continue_mm)) return true;
  link.fail(link.program_of(b.program), b.block,
            "the breakpoint mc_cmd_bs_breakpoint_position_w at " + Mm(distance.breakpoint()) +
                " mm from program start lies before the continue position of block search (" +
                Mm(continue_mm) + " mm and on): it must lie after it (block search 3.5)",
            kMsgBlockSearch);
  return false;
}

bool BlockSearchSimulation::FoundContinuePosition(const SearchLink& link,
                                                  const nc::PreparedBlock& b,
                                                  const BlockMotion& motion, double u) {
  BlockSearchRun& s = *run_;
  const ProgramDistance& distance = link.data.program_distance;
  const double length = distance.LengthOf(motion, link.config.axes);
  if (!BreakpointAfter(link, distance.distance() + u * length, b)) return false;
  s.face_return = b.modal.transformation == nc::Transformation::kFace;
  s.restart_motion = motion;
  s.restart_u = u;
  s.restart_distance = distance.distance();
  s.restart_length = length;
  s.restart = s.position;
  if (motion.moves) motion.PointAt(u, s.restart);
  RecordPath(link, b, motion, true);
  s.position = s.restart;
  link.data.state = BlockSearchState::kWaitForPlcOff;
  return true;
}

void BlockSearchSimulation::RecordPath(const SearchLink& link, const nc::PreparedBlock& b,
                                       const BlockMotion& motion, bool keep) {
  if (b.homing || b.measuring || nc::SpindleSynchronous(b.motion))
    link.backward.Forget();
  else if (keep)  // decoded: the search's blocks were never travelled
    link.backward.Record(motion, b.motion == nc::Motion::kRapid, true);
}

bool BlockSearchSimulation::Changeover(const SearchLink& link, const nc::PreparedBlock& b) {
  BlockSearchRun& s = *run_;
  if (!link.headstock || s.changed_over) {
    s.changed_over = false;
    return true;
  }
  const axes::HeadstockMode need = HeadstockControl::ModeNeeded(b, link.config.rotary_axis);
  if (need == axes::HeadstockMode::kNone || link.headstock->mode() == need) return true;
  // C-axis manual 1.2: block preparation waits until the changeover ends; the PLC's sequence
  // runs as in normal running (the channel's headstock cycle repeats the request if a key
  // turned it round).
  link.headstock.RequestForBlock(need);
  return false;
}

void BlockSearchSimulation::EndChangeover(const SearchLink& link, nc::PreparedBlock& b) {
  BlockSearchRun& s = *run_;
  const axes::HeadstockMode mode = link.headstock.EndWait();
  s.changed_over = true;
  if (mode != axes::HeadstockMode::kRotary) return;
  // Rotary axis mode starts where C stands (the headstock cycle keeps its command value on the
  // actual position, with the rotary offsets back): the search's C is there too.
  const size_t r = static_cast<size_t>(link.config.rotary_axis);
  s.position[r] = link.commanded[r];
  // As a run rebases the rotary axis: an increment counts from here; the interpreter goes on
  // from the block's corrected end. Under G41/G42 the blocks ahead are prepared already.
  if (link.compensating || b.homing) return;
  const double actual = link.commanded[r] - link.frames.translation[r];
  if (b.modal.incremental && (b.programmed >> r & 1)) b.target[r] += actual - s.rotary_start;
  link.interpreter.SetAxisPosition(r, b.target[r]);
}

}  // namespace vmt::control::channel
