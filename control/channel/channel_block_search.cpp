// Block search in the channel (twincat-cnc-block-search-de.md): the search's phases around the
// skipped blocks. At the program start the channel takes the CNC objects, the breakpoint and the
// entry point; in search mode it waits for the PLC's acknowledgement (7), reads the blocks (under
// G41/G42 through the tool nose radius compensation, as a run reads them, so the continue
// position is on the tip path and the run goes on from the compensation's state) and hands them
// to BlockSearchSimulation (block_search_simulation.hpp), which decodes them without axis motion
// up to the continue position. Found, it hands over to the PLC again; where in its block
// machining goes on is continue_position.hpp's, the return to the contour and the continuation
// inside the block are channel_return_to_contour.cpp's. The breakpoint (3.5) and the distance
// from program start (4.1.2), which count in normal runs as well, are program_distance.hpp's.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "control/channel/block_search_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {

bool Channel::SetBlockSearch(const BlockSearchParameters& p, std::string* text) {
  // Kept even when wrong: the program start reports it, where the operator looks.
  bs_.next = p;
  const std::string error = CheckBlockSearch(p);
  if (text) *text = error;
  return error.empty();
}

void Channel::BeginBlockSearch() {
  bs_.started = bs_.next;
  search_.Reset();
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
  search_.Begin(bs_.started, out_.commanded, sp_.command);
  work_.interpreter->SetEveryBlock(true);
  bs_.state = BlockSearchState::kWaitForPlcOn;
  bs_.command = true;
}

bool Channel::SearchCycle(const AmplifierTelegram& at) {
  if (!search_.active() || bs_.state == BlockSearchState::kInactive) return false;
  BlockSearchRun& s = search_.run();
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
      search_.SimulateBlocks(SearchLinkNow(), work_.block, [this] { return NextSearchBlock(); });
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
      if ((!headstock_ || headstock_->mode() == axes::HeadstockMode::kSpindle) && !SpindleReady(at))
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

SearchLink Channel::SearchLinkNow() {
  return SearchLink{
      .config = config_,
      .data = bs_,
      .interpreter = *work_.interpreter,
      .state = state_,
      .frames = frames_,
      .events = events_,
      .aux = aux_,
      .headstock = headstock_,
      .cax = cax_,
      .backward = backward_,
      .commanded = out_.commanded,
      .compensating = work_.feed.compensating(),
      .tracked_axis = TrackedAxis(),
      .program_of = [this](uint32_t index) -> const nc::Program& { return *ProgramOf(index); },
      .fail = [this](const nc::Program& program, int32_t block, const std::string& text,
                     int number) { Fail(program, block, text, number); },
      .fail_message = [this](const std::string& message, int number) { Fail(message, number); },
      .take_offsets = [this](const nc::ModalState& modal, const nc::Program& program,
                             int32_t block) { return UpdateTranslation(modal, program, block); },
      .index_tool_storage =
          ToolStorageNc() ? std::function<bool(const nc::PreparedBlock&, const nc::Program&)>(
                                [this](const nc::PreparedBlock& b, const nc::Program& program) {
                                  return IndexToolStorage(b, program);
                                })
                          : nullptr,
      .simulate_measuring =
          [this](const nc::PreparedBlock& b, std::vector<double>& position) {
            return measuring_.Simulate(MeasuringLinkNow(), b, position, bs_.warnings);
          },
      .cax_instruction =
          [this](const nc::Program& program, const nc::Statement& st, nc::PreparedBlock& b,
                 double c_machine) { return CaxTrackInstruction(program, st, b, c_machine); },
      .track_c =
          [this](nc::PreparedBlock& b, const std::vector<double>& from, double rev_per_s,
                 std::optional<double>& align_to) { return TrackC(b, from, rev_per_s, align_to); },
  };
}

bool Channel::NextSearchBlock() {
  BlockSearchRun& s = search_.run();
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

void Channel::EndSearchMode() {
  BlockSearchRun& s = search_.run();
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
  if (search_.active() && !search_.run().restart.empty() && !holding &&
      (bs_.state == BlockSearchState::kWaitForPlcOff ||
       bs_.state == BlockSearchState::kWaitReturnToContour ||
       bs_.state == BlockSearchState::kReturningToContour ||
       bs_.state == BlockSearchState::kWaitForContinueContour)) {
    const BlockSearchRun& s = search_.run();
    double d2 = 0;
    for (size_t a = 0; a < out_.commanded.size(); ++a)
      if (MainAxis(config_.axes[a].name)) d2 += std::pow(out_.commanded[a] - s.restart[a], 2);
    st.path_deviation = std::sqrt(d2);
    st.continue_position = s.restart;
    st.dist_prog_start = s.restart_distance + s.restart_u * s.restart_length;
  }
  uint32_t sc = 0;
  using namespace stop_condition;
  const bool running = state_ == ChannelState::kRunning;
  const bool hold = state_ == ChannelState::kHold;
  if (holding) sc |= kBreakpointStop;
  if (hold && single_block_) sc |= kSingleBlock;
  // M00 / M01 (programmed_stop.hpp). STOP_REVERSIBLE: at an M00 the program may still be
  // travelled back (channel_backward.cpp) while the path memory holds a path to take.
  const ProgrammedStop::Kind programmed =
      hold ? programmed_stop_.held : ProgrammedStop::Kind::kNone;
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
