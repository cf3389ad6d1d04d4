// Block search in the channel (twincat-cnc-block-search-de.md): at the program start the
// channel decodes the program without axis motion up to the continue position (types 1, 3, 4;
// 5 to the program end), rebuilding modal state, variables, offsets, tool and spindle, with
// every technology function going to the PLC and acknowledged as in a normal run. Found, it
// hands over to the PLC (7); where in its block machining goes on is continue_position.hpp's,
// the return to the contour and the continuation inside the block are
// channel_return_to_contour.cpp's. Under G41/G42 the search runs the tool nose
// radius compensation as the run does, so the continue position is on the tip path and the
// run goes on from the compensation's state; with #CAX TRACK on, the return aligns C first
// (4.2.2). A spindle / rotary axis changeover and measuring instructions of the skipped part:
// channel_block_search_technology.cpp. The breakpoint (3.5) and the distance from program start
// (4.1.2), which count in normal runs as well, are program_distance.hpp's.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "control/channel/block_search_support.hpp"
#include "control/channel/channel.hpp"
#include "control/channel/continue_position.hpp"
#include "control/nc/coordinate_transformation.hpp"

namespace vmt::control::channel {
namespace {

/// Blocks decoded per NC cycle in search mode: fast, yet a program looping for ever with
/// motion still leaves the cycle (and the scene's end) in charge.
constexpr int kSearchBlocksPerCycle = 20000;

constexpr const char* kNotFound =
    "P-ERR-20704: the continue position was not found; the program ended in block search mode";

}  // namespace

bool Channel::SetBlockSearch(const BlockSearchParameters& p, std::string* text) {
  // Kept even when wrong: the program start reports it, where the operator looks.
  bs_.next = p;
  const std::string error = CheckBlockSearch(p);
  if (text) *text = error;
  return error.empty();
}

void Channel::BeginBlockSearch() {
  bs_.started = bs_.next;
  search_.reset();
  bs_.state = BlockSearchState::kInactive;
  bs_.command = false;
  bs_.warnings.clear();
  bs_.program_distance.Restart();  // 4.1.2: ON and CLEAR are the state at program start
  cax_.command.reset();
  cax_.aligning = false;
  RemoveSearchOffset();
  if (mode_ != ChannelMode::kAutomatic || !work_.interpreter) return;
  if (const std::string e = CheckBlockSearch(bs_.started); !e.empty()) {
    Fail("block search: " + e, kMsgBlockSearch);
    return;
  }
  bs_.program_distance.SetBreakpoint(bs_.started.breakpoint_position * 1e-4);
  if (bs_.started.file_offset > 0 &&
      !work_.interpreter->StartAt(static_cast<uint32_t>(bs_.started.file_offset))) {
    Fail(programs_[0]->files[0] + ": error: the entry point mc_command_file_offset_w " +
             std::to_string(bs_.started.file_offset) + " lies beyond the program's last block",
         kMsgBlockSearch);
    return;
  }
  if (!bs_.started.searches()) return;
  search_.emplace(bs_.started);
  search_->position = out_.commanded;
  search_->spindle = sp_.command;
  work_.interpreter->SetEveryBlock(true);
  bs_.state = BlockSearchState::kWaitForPlcOn;
  bs_.command = true;
}

bool Channel::SearchCycle(const AmplifierTelegram& at) {
  if (!search_ || bs_.state == BlockSearchState::kInactive) return false;
  BlockSearchRun& s = *search_;
  // Technology functions of the search wait for the PLC as in a normal run (2, 7).
  if (!aux_.functions.empty()) return true;
  // 4.2.1: from the return on the search moves axes; lent to the JogOfPath channel, they must
  // come back first ("Vor dem Weiterfahren des Satzvorlaufkanals wird die Kanal-Ausgabe wieder
  // auf den Satzvorlaufkanal umgeschaltet").
  if (out_.suspended && bs_.state >= BlockSearchState::kWaitReturnToContour) return true;
  switch (bs_.state) {
    case BlockSearchState::kWaitForPlcOn:
      // 7: with enable_w the NC asks and waits for the PLC's acknowledgement.
      bs_.command = true;
      if (bs_.plc_enable && !bs_.plc_state) return true;
      bs_.state = BlockSearchState::kActive;
      [[fallthrough]];
    case BlockSearchState::kActive:
      if (state_ != ChannelState::kRunning) return true;
      if (headstock_.waiting()) {
        // The block waits for its changeover as in a run (channel_block_search_technology.cpp).
        if (headstock_->mode() != headstock_.waiting_for()) return true;
        EndSearchChangeover(work_.block);
        if (!SimulateBlock(work_.block) || !SearchGoesOn()) return true;
      }
      SimulateBlocks();
      return true;
    case BlockSearchState::kWaitForPlcOff:
      bs_.command = false;
      if (bs_.plc_enable && bs_.plc_state) return true;
      EndSearchMode();
      return true;
    case BlockSearchState::kWaitReturnToContour:
      if (!s.start_requested || state_ != ChannelState::kRunning) return true;
      // The spindle gets its last commanded speed back first (2: "gleichzeitig müssen auch die
      // Spindeln ... erreicht haben").
      if (sp_.command.mode != s.spindle.mode || sp_.command.value != s.spindle.value) {
        sp_.command = s.spindle;
        return true;  // the drive's at-speed answers the new command from the next cycle on
      }
      // In rotary axis mode the headstock holds the spindle still whatever its command.
      if ((!headstock_ || headstock_->mode() == axes::HeadstockMode::kSpindle) &&
          !SpindleReady(at))
        return true;
      s.start_requested = false;
      if (bs_.started.auto_return) {
        if (StartReturnToContour()) bs_.state = BlockSearchState::kReturningToContour;
        return true;
      }
      if (ApplySearchOffset()) ContinueAfterSearch();
      return true;
    case BlockSearchState::kReturningToContour:
      if (work_.active) return true;  // the return move interpolates in Tick
      if (s.return_rest) {
        // 4.2.2: C is aligned; now the straight return of the other axes.
        s.return_rest = false;
        StartReturnMove(s.restart, "return to contour");
        return true;
      }
      if (bs_.started.no_hold_at_restart) {
        ContinueAfterSearch();
        return true;
      }
      state_ = ChannelState::kHold;
      s.start_requested = false;
      bs_.state = BlockSearchState::kWaitForContinueContour;
      return true;
    case BlockSearchState::kWaitForContinueContour:
      if (bs_.program_distance.holding() || !s.start_requested || state_ != ChannelState::kRunning)
        return true;
      ContinueAfterSearch();
      return true;
    case BlockSearchState::kInactive:
      break;
  }
  return false;
}

bool Channel::SimulateBlocks() {
  for (int n = 0; n < kSearchBlocksPerCycle; ++n) {
    if (!NextSearchBlock()) return false;
    ++search_->blocks;
    if (!SimulateBlock(work_.block)) return false;
    if (!SearchGoesOn()) return true;
  }
  return true;
}

bool Channel::SearchGoesOn() const {
  // Technology waits for the PLC: its acknowledgement, or the end of a changeover.
  return bs_.state == BlockSearchState::kActive && aux_.functions.empty() &&
         !headstock_.waiting() && state_ == ChannelState::kRunning;
}

bool Channel::NextSearchBlock() {
  BlockSearchRun& s = *search_;
  s.further_piece = s.inserted_piece = false;
  inserted_piece_ = false;
  const auto text_ended = [&] {
    if (work_.interpreter->error()) {
      Fail(nc::Format(*work_.interpreter->error(), {work_.interpreter->ErrorFile()}),
           kMsgProgramError);
      return false;
    }
    work_.block = nc::PreparedBlock{};
    work_.block.end = true;  // the text ended without M30: its end all the same
    work_.block.motion = nc::Motion::kNone;
    work_.block.block = -1;
    return true;
  };
  if (!work_.feed.compensating()) {
    if (headstock_) s.rotary_start = work_.interpreter->position()[config_.rotary_axis];
    if (!ReadSource(work_.block)) return text_ended();
    if (work_.block.modal.compensation == nc::Compensation::kOff ||
        work_.block.motion == nc::Motion::kNone)
      return true;
    // G41/G42: the search reads ahead through the compensation as the run does
    // (NextBlock), so that the tip path it simulates is the one the run machines, and the
    // run takes over the compensation's state at the continue position.
    // Where the program has the axes: the search moves none.
    if (!StartCompensation(s.position)) return false;
  }
  switch (FillReadyPiece(true)) {
    case Compensated::kFailed:
      return false;
    case Compensated::kDrained:
      if (work_.feed.source_done()) {
        work_.feed.ForgetSourceDone();
        return text_ended();
      }
      return NextSearchBlock();
    case Compensated::kPiece:
      break;
  }
  const TakenPiece piece = work_.feed.TakePiece(FeedContextNow(), work_.block);
  s.further_piece = piece.further;
  s.inserted_piece = inserted_piece_ = piece.element.inserted;
  return true;
}

bool Channel::SimulateBlock(nc::PreparedBlock& b) {
  BlockSearchRun& s = *search_;
  if (b.block < 0) {  // the end of the text, or type 1's end position (ReadSource)
    if (s.end_reached)
      // Type 1's end position before its continue position: nothing is left to machine.
      bs_.warnings.push_back("the end position came before the continue position");
    else if (bs_.started.type != BlockSearchType::kProgramEnd)
      bs_.warnings.push_back(kNotFound);
    s.ends_program = true;
    bs_.state = BlockSearchState::kWaitForPlcOff;
    return true;
  }
  const nc::Program& program = *ProgramOf(b.program);
  auto fail = [&](const std::string& text, int number) {
    Fail(program, b.block, text, number);
    return false;
  };
  // A further piece of a block's tip path: its functions ran with the first.
  if (s.further_piece) return SimulateMotion(b, false);
  // A spindle / rotary axis changeover runs as in a run; the block waits for its end.
  if (!SearchChangeover(b)) return true;
  const bool boundary = !s.found && s.matcher.Matches(b, program, b.program);
  if (boundary && b.search_locked)
    return fail("P-ERR-21399: the continue position lies in a region locked for block search "
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
    return measuring_.Simulate(MeasuringLinkNow(), b, search_->position, bs_.warnings);
  }
  for (uint32_t index : b.instructions) {
    const nc::Statement& st = program.statements[index];
    if (st.kind == nc::Statement::Kind::kHashCommand) {
      if (const std::string refused = RefusedHashCommand(st.hash); !refused.empty()) {
        Fail(nc::Format({st.pos, refused}, program.files), kMsgNotAvailable);
        return false;
      }
      // 4.2.2: the C axis tracks the contour in the search as in the run.
      const int c = TrackedAxis();
      if (const auto done = CaxTrackInstruction(program, st, b,
                                                c < 0 ? 0 : s.position[static_cast<size_t>(c)])) {
        if (!*done) return false;
        continue;
      }
      if (SteersBlockSearch(st.hash)) continue;
    }
    return fail("instruction " +
                    (st.kind == nc::Statement::Kind::kHashCommand ? "#" + program.texts[st.text]
                                                                   : program.symbols.Name(st.name)) +
                    " is not supported in block search by vmt (docs/conformance.md)",
                kMsgNotAvailable);
  }
  for (const auto& [n, set] : b.events) {
    events_.own[n] = set;
    if (events_.sink) events_.sink(n, set);
  }
  bs_.program_distance.Command(b.distance_command);
  if (!UpdateTranslation(b.modal, program, b.block)) return false;
  if (b.set_position)
    for (size_t a = 0; a < s.position.size(); ++a)
      if (b.programmed >> a & 1) {
        frames_.shift[a] += s.position[a] - (b.target[a] + frames_.translation[a]);
        frames_.translation[a] = s.position[a] - b.target[a];
        if (headstock_ && static_cast<int>(a) == config_.rotary_axis)
          headstock_.set_rotary_translation(frames_.translation[a]);
      }
  SpindleFunctions(b, s.spindle);
  // An NC-controlled turret is technology too: the T word indexes it now, as in a run.
  if (!IndexToolStorage(b, program)) return false;
  // Technology goes to the PLC as in a normal run (2): it switches coolant, turret, ... now.
  if (config_.aux_handshake) {
    for (const nc::AuxFunction& f : b.aux)
      if (f.letter == 'M' || f.letter == 'H' || f.letter == 'Q' || f.letter == 'T')
        aux_.functions.push_back(f);
    if (!aux_.functions.empty()) ++aux_.strobe;
  }

  return SimulateMotion(b, boundary);
}

bool Channel::SimulateMotion(nc::PreparedBlock& b, bool boundary) {
  BlockSearchRun& s = *search_;
  // The block's path from where the program has the axes. G74 is left out (8: the axes stay),
  // G100 becomes a G01 to its target (8), a thread the straight line it is. Under G41/G42 the
  // block is a piece of the tip path (NextSearchBlock): planned as the run plans it.
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
    if (!TrackC(m, s.position, std::abs(rev_per_s), align)) return false;
    if (align) s.position[static_cast<size_t>(TrackedAxis())] = *align;
    if (const auto error = PlanBlockMotion(m, s.position, frames_.translation, config_.axes,
                                           std::abs(rev_per_s), motion, FollowUpAxes(m))) {
      Fail(*ProgramOf(b.program), b.block, error->text, error->number);
      return false;
    }
  }
  if (b.homing) {
    // The interpreter took G74's words for targets; they are the homing order (ISG) or a
    // placeholder (MTC200), never positions. The skipped G74 leaves the axes where the program
    // had them (8), and the blocks after it count from there, as after a run's G74 they count
    // from the reference points (NextHomingStage).
    for (size_t a = 0; a < s.position.size(); ++a)
      if (b.programmed >> a & 1)
        work_.interpreter->SetAxisPosition(a, s.position[a] - frames_.translation[a]);
  }
  const double length = bs_.program_distance.LengthOf(motion, config_.axes);
  if (boundary || s.Deciding()) {
    const ContinueStep step =
        DecideContinue(s, bs_.started, motion, length, bs_.program_distance.distance(), boundary);
    if (step.distance_passed)
      bs_.warnings.push_back(DistancePassedWarning(bs_.started, bs_.program_distance.distance()));
    if (step.found) return FoundContinuePosition(b, motion, step.u);
  }
  if (motion.moves) s.position = motion.end;
  bs_.program_distance.Pass(length);
  if (!BreakpointAfter(bs_.program_distance.distance(), b)) return false;
  // The decoded path, for backward travel from the continue position (4.3); not to the
  // program's end (type 5), where the program ends in search mode.
  if (b.homing || b.measuring || nc::SpindleSynchronous(b.motion))
    PathBarrier();
  else if (bs_.started.type != BlockSearchType::kProgramEnd)
    RecordPath(motion, b.motion == nc::Motion::kRapid);
  if (b.end) {
    if (bs_.started.type != BlockSearchType::kProgramEnd) bs_.warnings.push_back(kNotFound);
    s.ends_program = true;
    bs_.state = BlockSearchState::kWaitForPlcOff;
  }
  return true;
}

bool Channel::BreakpointAfter(double continue_mm, const nc::PreparedBlock& b) {
  // 3.5 requires the breakpoint to lie after the continue position. vmt reads a breakpoint
  // the search passes as a wrong parameter, not as one to drop: the operator asked
  // for a stop and machining must not run on without it. The search stops with an error where
  // it meets the breakpoint, before any axis moves; a breakpoint at the continue position
  // itself holds as soon as machining goes on there (ContinueAfterSearch).
  if (!bs_.program_distance.BreakpointBefore(continue_mm)) return true;
  Fail(*ProgramOf(b.program), b.block,
       "the breakpoint mc_cmd_bs_breakpoint_position_w at " +
           Mm(bs_.program_distance.breakpoint()) +
           " mm from program start lies before the continue position of block search (" +
           Mm(continue_mm) + " mm and on): it must lie after it (block search 3.5)",
       kMsgBlockSearch);
  return false;
}

bool Channel::FoundContinuePosition(const nc::PreparedBlock& b, const BlockMotion& motion,
                                    double u) {
  BlockSearchRun& s = *search_;
  const double length = bs_.program_distance.LengthOf(motion, config_.axes);
  if (!BreakpointAfter(bs_.program_distance.distance() + u * length, b)) return false;
  s.face_return = b.modal.transformation == nc::Transformation::kFace;
  s.restart_motion = motion;
  s.restart_u = u;
  s.restart_distance = bs_.program_distance.distance();
  s.restart_length = length;
  s.restart = s.position;
  if (motion.moves) motion.PointAt(u, s.restart);
  if (b.homing || b.measuring || nc::SpindleSynchronous(b.motion))
    PathBarrier();
  else
    RecordPath(motion, b.motion == nc::Motion::kRapid);
  s.position = s.restart;
  bs_.state = BlockSearchState::kWaitForPlcOff;
  return true;
}

void Channel::EndSearchMode() {
  BlockSearchRun& s = *search_;
  // Type 1 with an end position watches the blocks of the real run too (NextBlock).
  work_.interpreter->SetEveryBlock(bs_.started.type == BlockSearchType::kFileOffset &&
                                   bs_.started.end.offset >= 0);
  if (s.ends_program) {
    // 3.4, 10: the whole program ran in block search mode.
    bs_.state = BlockSearchState::kInactive;
    state_ = ChannelState::kEnded;
    reversing_ = false;
    return;
  }
  bs_.state = BlockSearchState::kWaitReturnToContour;
  state_ = ChannelState::kHold;
  s.start_requested = false;
}

void Channel::HoldAtBreakpoint() {
  bs_.program_distance.Hold();
  state_ = ChannelState::kHold;
  bs_.state = BlockSearchState::kWaitForContinueContour;
}

bool Channel::SpindleFunctions(const nc::PreparedBlock& b, DriveSetpoint& sp) const {
  bool orient = false;
  for (const nc::AuxFunction& f : b.aux) {
    if (f.letter != 'M' || SpindleIndex(f.index) != 1 || config_.spindle_drive < 0) continue;
    const int m = static_cast<int>(f.value);
    const double rpm = b.modal.spindle_speed;
    // G64 keeps the spindle in position control: M3/M4 give its direction only.
    if ((m == 3 || m == 4) && b.motion == nc::Motion::kRigidTapping) continue;
    if (m == 3) sp = {DriveMode::kVelocity, rpm * 6, 0};
    if (m == 4) sp = {DriveMode::kVelocity, -rpm * 6, 0};
    if (m == 5) sp = {DriveMode::kVelocity, 0, 0};
    if (m == 19) sp = {DriveMode::kPosition, 0, 0}, orient = true;
  }
  // An S word alone changes the speed of a running spindle.
  if (sp.mode == DriveMode::kVelocity && sp.value != 0)
    sp.value = std::copysign(b.modal.spindle_speed * 6, sp.value);
  return orient;
}

void Channel::UpdateBlockSearchStatus() {
  BlockSearchStatus& st = bs_.status;
  st.state = bs_.state;
  st.command = bs_.command;
  const bool holding = bs_.program_distance.holding();
  const bool moving = work_.motion.moves && (work_.active || holding);
  // A corner the compensation inserted before its block is not yet the block's own path: the
  // per mille the search takes is measured in that (SimulateMotion); nor is the C-only turn of
  // #CAX TRACK before its block, which has not started counting its distance yet.
  const bool aside = inserted_piece_ || cax_.aligning;
  double u = moving && !aside ? std::clamp(work_.profile.u, 0.0, 1.0) : 0;
  // The breakpoint cut the block: its profile runs over the first part only.
  if (moving) u *= bs_.program_distance.CutFraction();
  st.covered_distance = u * 1000;
  st.dist_prog_start = (work_.active || holding) && !cax_.aligning
                           ? bs_.program_distance.DistanceAt(u)
                           : bs_.program_distance.distance();
  st.block_count = work_.block.block_count;
  st.path_deviation = 0;
  st.continue_position.clear();
  if (search_ && !search_->restart.empty() && !holding &&
      (bs_.state == BlockSearchState::kWaitForPlcOff ||
       bs_.state == BlockSearchState::kWaitReturnToContour ||
       bs_.state == BlockSearchState::kReturningToContour ||
       bs_.state == BlockSearchState::kWaitForContinueContour)) {
    double d2 = 0;
    for (size_t a = 0; a < out_.commanded.size(); ++a)
      if (MainAxis(config_.axes[a].name))
        d2 += std::pow(out_.commanded[a] - search_->restart[a], 2);
    st.path_deviation = std::sqrt(d2);
    st.continue_position = search_->restart;
    st.dist_prog_start = search_->restart_distance + search_->restart_u * search_->restart_length;
  }
  uint32_t sc = 0;
  using namespace stop_condition;
  const bool running = state_ == ChannelState::kRunning;
  const bool hold = state_ == ChannelState::kHold;
  if (holding) sc |= kBreakpointStop;
  if (hold && single_block_) sc |= kSingleBlock;
  // M00 / M01 (programmed_stop.hpp). STOP_REVERSIBLE: at an M00 the program may still be
  // travelled back (channel_backward.cpp) while the path memory holds a path to take.
  const ProgrammedStop::Kind programmed = hold ? programmed_stop_.held : ProgrammedStop::Kind::kNone;
  if (programmed == ProgrammedStop::Kind::kM00)
    sc |= kM00OrM01 | kM0Stop | (backward_.empty() ? 0 : kStopReversible);
  if (programmed == ProgrammedStop::Kind::kM01) sc |= kM00OrM01 | kM1Stop;
  // Q9998 (fast measurement 6.1, fault category 2) holds the program with a fault message: an
  // error in the channel that a new start acknowledges, not a feed hold.
  const bool measuring_fault = hold && error_number_ == kMsgMeasuringContinuable;
  if (measuring_fault) sc |= kChannelError;
  const bool search_hold = bs_.state == BlockSearchState::kWaitReturnToContour ||
                           bs_.state == BlockSearchState::kWaitForContinueContour;
  if (hold && !holding && !single_block_ && !search_hold &&
      programmed == ProgrammedStop::Kind::kNone && !measuring_fault)
    sc |= kFeedhold;
  if (!aux_.functions.empty()) sc |= kPlcAcknowledge | kWaitTechnoAck;
  // A changeover waits for the PLC's ROTMOD / SPMOD acknowledgement (C-axis manual 2.3), in the
  // search as in a run: a technology function's acknowledgement. Meanwhile, as while MRY waits
  // for the tool storage axis, block preparation delivers nothing: the interpolator's input
  // is empty.
  if (headstock_.waiting()) sc |= kWaitTechnoAck;
  if (running && !work_.active && (headstock_.waiting() || tool_storage_wait_))
    sc |= kIpoInputEmpty;
  // Block search 4.2.1: the axes change hands at standstill only; until then the channel
  // waits for the exchange it asked for. While its output is suspended a program (not a
  // search, which decodes on) reads no blocks.
  if ((out_.suspend_requested || out_.axes_elsewhere) != out_.suspended) sc |= kWaitForAxes;
  if (out_.suspended && (running || hold) && bs_.state == BlockSearchState::kInactive)
    sc |= kIpoInputDisabled;
  if (running && work_.active && override_ == 0)
    sc |= work_.block.motion == nc::Motion::kRapid ? kOverrideRapidZero : kOverrideZero;
  if (work_.dwell_left_s > 0) sc |= kDelayTime;
  if (state_ == ChannelState::kError) sc |= kChannelError;
  // PathGuard stops a move before a contact with an NC error (kMsgCollision): the motion
  // stands after a detected collision until Control-Reset.
  if (state_ == ChannelState::kError && error_number_ == kMsgCollision)
    sc |= kWaitContinueAfterCollision;
  st.stop_conditions = sc;
  st.warnings = bs_.warnings;
}

}  // namespace vmt::control::channel
