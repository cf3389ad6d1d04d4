// Block search in the channel (twincat-cnc-block-search-de.md): at the program start the
// channel decodes the program without axis motion up to the continue position (types 1, 3, 4;
// 5 to the program end), rebuilding modal state, variables, offsets, tool and spindle, with
// every technology function going to the PLC and acknowledged as in a normal run. Found, it
// hands over to the PLC (7), returns the axes to the contour in one straight G00 move that
// PathGuard checks first (4.2; the manual leaves the obstacle to the operator, vmt refuses the
// move), or checks the manual return against mc_cmd_bs_deviation_max_w and keeps the offset,
// and goes on at the continue position, inside its block when a covered distance or a
// distance from program start says so (4.1). Under G41/G42 the search runs the tool nose
// radius compensation as the run does, so the continue position is on the tip path and the
// run goes on from the compensation's state; with #CAX TRACK on, the return aligns C first
// (4.2.2). A spindle / rotary axis changeover and measuring instructions of the skipped part:
// channel_block_search_technology.cpp. The breakpoint (3.5) and the distance from program start (4.1.2) live here too:
// they count in normal runs as well.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "control/channel/channel.hpp"
#include "control/nc/coordinate_transformation.hpp"

namespace vmt::control::channel {
namespace {

/// Blocks decoded per NC cycle in search mode: fast, yet a program looping for ever with
/// motion still leaves the cycle (and the scene's end) in charge.
constexpr int kSearchBlocksPerCycle = 20000;

bool MainAxis(const std::string& name) { return name == "X" || name == "Y" || name == "Z"; }

/// `motion` up to u (0 < u <= 1): the same path, ending at u, with its limits rescaled to the
/// shorter parameter range.
BlockMotion Truncated(const BlockMotion& motion, double u) {
  BlockMotion m = motion;
  if (u <= 1e-12) {
    m.end = m.start;
    m.moves = false;
    return m;
  }
  motion.PointAt(u, m.end);
  m.arc_sweep *= u;
  m.length *= u;
  m.max_rate /= u;
  m.max_accel /= u;
  m.max_jerk /= u;
  return m;
}

constexpr const char* kNotFound =
    "P-ERR-20704: the continue position was not found; the program ended in block search mode";

/// The profile of `motion` standing at u: a block taken up again from a point inside it.
PathProfile ProfileFrom(const BlockMotion& motion, double u) {
  PathProfile p;
  p.max_rate = motion.max_rate;
  p.max_accel = motion.max_accel;
  p.max_jerk = motion.max_jerk;
  p.u = u;
  return p;
}

std::string Mm(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", v);
  return text;
}

}  // namespace

bool Channel::SetBlockSearch(const BlockSearchParameters& p, std::string* text) {
  // Kept even when wrong: the program start reports it, where the operator looks.
  bs_next_ = p;
  const std::string error = CheckBlockSearch(p);
  if (text) *text = error;
  return error.empty();
}

void Channel::BeginBlockSearch() {
  bs_started_ = bs_next_;
  search_.reset();
  bs_state_ = BlockSearchState::kInactive;
  bs_command_ = false;
  bs_warnings_.clear();
  distance_on_ = true;  // 4.1.2: ON and CLEAR are the state at program start
  distance_ = block_distance_start_ = block_distance_ = 0;
  breakpoint_rest_.reset();
  breakpoint_hold_ = false;
  breakpoint_pending_ = false;
  breakpoint_ = 0;
  RemoveSearchOffset();
  if (mode_ != ChannelMode::kAutomatic || !interpreter_) return;
  if (const std::string e = CheckBlockSearch(bs_started_); !e.empty()) {
    Fail("block search: " + e, kMsgBlockSearch);
    return;
  }
  breakpoint_ = bs_started_.breakpoint_position * 1e-4;
  if (bs_started_.file_offset > 0 &&
      !interpreter_->StartAt(static_cast<uint32_t>(bs_started_.file_offset))) {
    Fail(programs_[0]->files[0] + ": error: the entry point mc_command_file_offset_w " +
             std::to_string(bs_started_.file_offset) + " lies beyond the program's last block",
         kMsgBlockSearch);
    return;
  }
  if (!bs_started_.searches()) return;
  search_.emplace(bs_started_);
  search_->position = commanded_;
  search_->spindle = spindle_;
  interpreter_->SetEveryBlock(true);
  bs_state_ = BlockSearchState::kWaitForPlcOn;
  bs_command_ = true;
}

bool Channel::SearchCycle(const AmplifierTelegram& at) {
  if (!search_ || bs_state_ == BlockSearchState::kInactive) return false;
  BlockSearchRun& s = *search_;
  // Technology functions of the search wait for the PLC as in a normal run (2, 7).
  if (!aux_output_.empty()) return true;
  // 4.2.1: from the return on the search moves axes; lent to the JogOfPath channel, they must
  // come back first ("Vor dem Weiterfahren des Satzvorlaufkanals wird die Kanal-Ausgabe wieder
  // auf den Satzvorlaufkanal umgeschaltet").
  if (output_suspended_ && bs_state_ >= BlockSearchState::kWaitReturnToContour) return true;
  switch (bs_state_) {
    case BlockSearchState::kWaitForPlcOn:
      // 7: with enable_w the NC asks and waits for the PLC's acknowledgement.
      bs_command_ = true;
      if (bs_plc_enable_ && !bs_plc_state_) return true;
      bs_state_ = BlockSearchState::kActive;
      [[fallthrough]];
    case BlockSearchState::kActive:
      if (state_ != ChannelState::kRunning) return true;
      if (waiting_for_ != axes::HeadstockMode::kNone) {
        // The block waits for its changeover as in a run (channel_block_search_technology.cpp).
        if (headstock_->mode() != waiting_for_) return true;
        EndSearchChangeover(block_);
        if (!SimulateBlock(block_) || !SearchGoesOn()) return true;
      }
      SimulateBlocks();
      return true;
    case BlockSearchState::kWaitForPlcOff:
      bs_command_ = false;
      if (bs_plc_enable_ && bs_plc_state_) return true;
      EndSearchMode();
      return true;
    case BlockSearchState::kWaitReturnToContour:
      if (!s.start_requested || state_ != ChannelState::kRunning) return true;
      // The spindle gets its last commanded speed back first (2: "gleichzeitig müssen auch die
      // Spindeln ... erreicht haben").
      if (spindle_.mode != s.spindle.mode || spindle_.value != s.spindle.value) {
        spindle_ = s.spindle;
        return true;  // the drive's at-speed answers the new command from the next cycle on
      }
      // In rotary axis mode the headstock holds the spindle still whatever its command.
      if ((!headstock_ || headstock_->mode() == axes::HeadstockMode::kSpindle) &&
          !SpindleReady(at))
        return true;
      s.start_requested = false;
      if (bs_started_.auto_return) {
        if (StartReturnToContour()) bs_state_ = BlockSearchState::kReturningToContour;
        return true;
      }
      if (ApplySearchOffset()) ContinueAfterSearch();
      return true;
    case BlockSearchState::kReturningToContour:
      if (active_) return true;  // the return move interpolates in Tick
      if (s.return_rest) {
        // 4.2.2: C is aligned; now the straight return of the other axes.
        s.return_rest = false;
        StartReturnMove(s.restart, "return to contour");
        return true;
      }
      if (bs_started_.no_hold_at_restart) {
        ContinueAfterSearch();
        return true;
      }
      state_ = ChannelState::kHold;
      s.start_requested = false;
      bs_state_ = BlockSearchState::kWaitForContinueContour;
      return true;
    case BlockSearchState::kWaitForContinueContour:
      if (breakpoint_hold_ || !s.start_requested || state_ != ChannelState::kRunning) return true;
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
    if (!SimulateBlock(block_)) return false;
    if (!SearchGoesOn()) return true;
  }
  return true;
}

bool Channel::SearchGoesOn() const {
  // Technology waits for the PLC: its acknowledgement, or the end of a changeover.
  return bs_state_ == BlockSearchState::kActive && aux_output_.empty() &&
         waiting_for_ == axes::HeadstockMode::kNone && state_ == ChannelState::kRunning;
}

bool Channel::NextSearchBlock() {
  BlockSearchRun& s = *search_;
  s.further_piece = s.inserted_piece = false;
  inserted_piece_ = false;
  const auto text_ended = [&] {
    if (interpreter_->error()) {
      Fail(nc::Format(*interpreter_->error(), {interpreter_->ErrorFile()}), kMsgProgramError);
      return false;
    }
    block_ = nc::PreparedBlock{};
    block_.end = true;  // the text ended without M30: its end all the same
    block_.motion = nc::Motion::kNone;
    block_.block = -1;
    return true;
  };
  if (!compensating_) {
    if (headstock_) s.rotary_start = interpreter_->position()[config_.rotary_axis];
    if (!interpreter_->Next(block_)) return text_ended();
    if (block_.modal.compensation == 40 || block_.motion == nc::Motion::kNone) return true;
    // G41/G42: the search reads ahead through the compensation as the run does
    // (NextBlock), so that the tip path it simulates is the one the run machines, and the
    // run takes over the compensation's state at the continue position.
    if (axis_z_ < 0 || axis_x_ < 0) {
      Fail(*ProgramOf(block_.program), block_.block,
           "tool nose radius compensation G41/G42 needs the axes Z and X", kMsgNotAvailable);
      return false;
    }
    compensating_ = true;
    source_done_ = false;
    trc_.Reset();
    ahead_.clear();
    ready_.clear();
    first_tag_ = next_tag_ = 0;
    last_run_tag_ = -1;
    // Where the program has the axes: the search moves none.
    contour_point_ = {s.position[axis_z_] - translation_[axis_z_],
                      s.position[axis_x_] - translation_[axis_x_]};
    if (!PushAhead(block_)) return false;
  }
  switch (FillReadyPiece(true)) {
    case Compensated::kFailed:
      return false;
    case Compensated::kDrained:
      if (source_done_) {
        source_done_ = false;
        return text_ended();
      }
      return NextSearchBlock();
    case Compensated::kPiece:
      break;
  }
  const ContourElement e = TakeReadyPiece();
  s.further_piece = e.tag == last_run_tag_;
  s.inserted_piece = inserted_piece_ = e.inserted;
  last_run_tag_ = e.tag;
  return true;
}

bool Channel::SimulateBlock(nc::PreparedBlock& b) {
  BlockSearchRun& s = *search_;
  if (b.block < 0) {  // the end of the text
    if (bs_started_.type != BlockSearchType::kProgramEnd)
      bs_warnings_.push_back(kNotFound);
    s.ends_program = true;
    bs_state_ = BlockSearchState::kWaitForPlcOff;
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
  if (s.matcher.EndMatches(b, program, b.program)) {
    // Type 1's end position before its continue position: nothing is left to machine.
    bs_warnings_.push_back("the end position came before the continue position");
    s.ends_program = true;
    bs_state_ = BlockSearchState::kWaitForPlcOff;
    return true;
  }
  // 4.1.2: reference moves and measuring moves end on an external signal; up to the block
  // boundary they are simulated, beyond it (the search by distance) they cannot be.
  if (s.by_distance && (b.homing || b.measuring))
    return fail(std::string(b.homing ? "G74" : "G100") +
                    " between the block of the continue position and its distance from program "
                    "start cannot be simulated (block search 4.1.2)",
                kMsgBlockSearch);
  if (b.repos) return fail("G77 cannot run in block search", kMsgBlockSearch);
  if (!b.calls.empty()) {
    // Section 8: the search cannot measure; the continue position after the instruction can.
    if (boundary)
      return fail("the continue position lies in measuring instruction " + b.calls.front().name +
                      ": block search cannot measure without motion (section 8); continue at "
                      "the block after it",
                  kMsgBlockSearch);
    return SimulateMeasuringInstruction(b);
  }
  for (uint32_t index : b.instructions) {
    const nc::Statement& st = program.statements[index];
    if (st.kind == nc::Statement::Kind::kHashCommand) {
      const std::string& text = program.texts[st.text];
      // 4.2.2: whether the C axis tracks the contour at the continue position.
      if (const auto on = CaxTrackCommand(text)) s.cax_track = *on;
      if (SteersBlockSearch(text)) continue;
    }
    return fail("instruction " +
                    (st.kind == nc::Statement::Kind::kHashCommand ? "#" + program.texts[st.text]
                                                                   : program.symbols.Name(st.name)) +
                    " is not available in block search yet",
                kMsgNotAvailable);
  }
  for (const auto& [n, set] : b.events) {
    own_events_[n] = set;
    if (event_sink_) event_sink_(n, set);
  }
  DistanceCommand(b);
  if (!UpdateTranslation(b.modal, program, b.block)) return false;
  if (b.set_position)
    for (size_t a = 0; a < s.position.size(); ++a)
      if (b.programmed >> a & 1) {
        shift_[a] += s.position[a] - (b.target[a] + translation_[a]);
        translation_[a] = s.position[a] - b.target[a];
        if (headstock_ && static_cast<int>(a) == config_.rotary_axis)
          rotary_translation_ = translation_[a];
      }
  SpindleFunctions(b, s.spindle);
  // An NC-controlled turret is technology too: the T word indexes it now, as in a run.
  if (!IndexToolStorage(b, program)) return false;
  // Technology goes to the PLC as in a normal run (2): it switches coolant, turret, ... now.
  if (config_.aux_handshake) {
    for (const nc::AuxFunction& f : b.aux)
      if (f.letter == 'M' || f.letter == 'H' || f.letter == 'Q' || f.letter == 'T')
        aux_output_.push_back(f);
    if (!aux_output_.empty()) ++aux_strobe_;
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
    if (const auto error = PlanBlockMotion(m, s.position, translation_, config_.axes,
                                           std::abs(rev_per_s), motion, FollowUpAxes(m))) {
      Fail(*ProgramOf(b.program), b.block, error->text, error->number);
      return false;
    }
  }
  const double length = distance_on_ ? DistanceOf(motion, config_.axes) : 0;
  const double permille = bs_started_.covered_distance / 1000;
  if (s.await_own_piece && !s.inserted_piece) {
    // The continue block's own piece after the corner the compensation inserted before it.
    s.await_own_piece = false;
    FoundContinuePosition(b, motion, motion.moves ? permille : 0);
    return true;
  }
  if (boundary) {
    s.found = true;
    const double wanted = bs_started_.distance_prog_start * 1e-4;
    if (wanted <= 0 && s.inserted_piece) {
      // The per mille measures the block's own piece of the tip path, not the corner arc
      // before it: the same point whatever the nose radius (4.1.1, note to figure 10).
      s.await_own_piece = true;
    } else if (wanted <= 0) {
      // 4.1.1 / 10: the covered distance splits a motion block; a block without motion is not.
      FoundContinuePosition(b, motion, motion.moves ? permille : 0);
      return true;
    } else if (wanted < distance_ - 1e-9) {
      // 4.1.2, figure 18: never back into blocks the search has passed.
      bs_warnings_.push_back("the distance from program start " + Mm(wanted) +
                             " mm lies before the block of the continue position (" +
                             Mm(distance_) + " mm): machining continues at its start");
      FoundContinuePosition(b, motion, 0);
      return true;
    } else {
      s.by_distance = true;
    }
  }
  if (s.by_distance && motion.moves && length > 0) {
    const double wanted = bs_started_.distance_prog_start * 1e-4;
    if (wanted <= distance_ + length + 1e-9) {
      FoundContinuePosition(b, motion, std::clamp((wanted - distance_) / length, 0.0, 1.0));
      return true;
    }
  }
  if (motion.moves) s.position = motion.end;
  distance_ += length;
  // The decoded path, for backward travel from the continue position (4.3); not to the
  // program's end (type 5), where the program ends in search mode.
  if (b.homing || b.measuring || nc::SpindleSynchronous(b.motion))
    PathBarrier();
  else if (bs_started_.type != BlockSearchType::kProgramEnd)
    RecordPath(motion, b.motion == nc::Motion::kRapid);
  if (b.end) {
    if (bs_started_.type != BlockSearchType::kProgramEnd)
      bs_warnings_.push_back(kNotFound);
    s.ends_program = true;
    bs_state_ = BlockSearchState::kWaitForPlcOff;
  }
  return true;
}

void Channel::FoundContinuePosition(const nc::PreparedBlock& b, const BlockMotion& motion,
                                    double u) {
  BlockSearchRun& s = *search_;
  s.face_return = b.modal.transformation == 31;
  s.restart_motion = motion;
  s.restart_u = u;
  s.restart_distance = distance_;
  s.restart_length = distance_on_ ? DistanceOf(motion, config_.axes) : 0;
  s.restart = s.position;
  if (motion.moves) motion.PointAt(u, s.restart);
  if (b.homing || b.measuring || nc::SpindleSynchronous(b.motion))
    PathBarrier();
  else
    RecordPath(motion, b.motion == nc::Motion::kRapid);
  s.position = s.restart;
  bs_state_ = BlockSearchState::kWaitForPlcOff;
}

void Channel::EndSearchMode() {
  BlockSearchRun& s = *search_;
  // Type 1 with an end position watches the blocks of the real run too (NextBlock).
  interpreter_->SetEveryBlock(bs_started_.type == BlockSearchType::kFileOffset &&
                              bs_started_.end.offset >= 0);
  if (s.ends_program) {
    // 3.4, 10: the whole program ran in block search mode.
    bs_state_ = BlockSearchState::kInactive;
    state_ = ChannelState::kEnded;
    reversing_ = false;
    return;
  }
  bs_state_ = BlockSearchState::kWaitReturnToContour;
  state_ = ChannelState::kHold;
  s.start_requested = false;
}

bool Channel::SpindleReady(const AmplifierTelegram& at) const {
  if (config_.spindle_drive < 0 || at.feedback.size() <= static_cast<size_t>(config_.spindle_drive))
    return true;
  const uint32_t status = at.feedback[config_.spindle_drive].status;
  if (spindle_.mode == DriveMode::kPosition) return status & drive_status::kInPosition;
  return spindle_.value == 0 || (status & drive_status::kAtSpeed);
}

bool Channel::StartReturnToContour() {
  BlockSearchRun& s = *search_;
  // 4.2.2: with #CAX TRACK on at the continue position the C axis is aligned first ("1.
  // Ausrichten der C-Achse ... 2. Wiederanfahren entsprechend der Satzvorlaufposition"). vmt
  // runs no tracking of its own, so C's alignment is where the program has C there.
  s.return_rest = false;
  // Outside rotary axis mode C is not positioned: it stays where the spindle has it.
  if (headstock_ && headstock_->mode() != axes::HeadstockMode::kRotary) {
    const size_t r = static_cast<size_t>(config_.rotary_axis);
    s.restart[r] = commanded_[r];
  }
  if (s.cax_track) {
    for (size_t a = 0; a < commanded_.size(); ++a) {
      if (config_.axes[a].name != "C" || std::abs(s.restart[a] - commanded_[a]) < 1e-12) continue;
      std::vector<double> aligned = commanded_;
      aligned[a] = s.restart[a];
      s.return_rest = true;
      return StartReturnMove(aligned, "C axis alignment (#CAX TRACK)");
    }
  }
  return StartReturnMove(s.restart, "return to contour");
}

bool Channel::StartReturnMove(const std::vector<double>& to, const std::string& move) {
  profile_ = PathProfile{};
  continuation_ready_ = false;
  carry_speed_ = carry_accel_ = carry_leftover_ = 0;
  // Under G31 (rotary axis mode) the return is a line of the face, as the programmed moves
  // around it are and as G77 X1=0 Y1=0 returns (REPOS manual 5.2): straight in X and C it
  // would sweep a spiral across the face. A line through the centre, where C is undefined,
  // stays straight in the axes (the operator's start there is no program's move to refuse).
  int x = -1, c = -1;
  if (search_->face_return && FictiveJogAxes(x, c) &&
      !nc::FaceLineOf(
           nc::MachineToFace(commanded_[x] - translation_[x], commanded_[c] - translation_[c]),
           nc::MachineToFace(to[x] - translation_[x], to[c] - translation_[c]))
           .through_centre) {
    nc::PreparedBlock b;
    b.motion = nc::Motion::kRapid;
    b.fictive = true;
    b.modal.transformation = 31;
    b.target.resize(to.size());
    for (size_t a = 0; a < to.size(); ++a) b.target[a] = to[a] - translation_[a];
    if (const auto error = PlanBlockMotion(b, commanded_, translation_, config_.axes, 0, motion_,
                                           FollowUpAxes(b))) {
      Fail("block search: return to contour: " + error->text, error->number);
      return false;
    }
    if (!motion_.moves) return true;
    if (!GuardBlockMove(move)) return false;
    profile_.max_rate = motion_.max_rate;
    profile_.max_accel = motion_.max_accel;
    profile_.max_jerk = motion_.max_jerk;
    active_ = true;
    return true;
  }
  // 4.2: one straight move at the rapid limits, every axis ending together.
  motion_ = BlockMotion{};
  motion_.start = commanded_;
  motion_.end = to;
  double rate = std::numeric_limits<double>::infinity(), accel = rate;
  for (size_t a = 0; a < commanded_.size(); ++a) {
    const double distance = std::abs(motion_.end[a] - motion_.start[a]);
    if (distance < 1e-12) continue;
    const ChannelAxis& axis = config_.axes[a];
    rate = std::min(rate, axis.rapid_per_s / distance);
    accel = std::min(accel, axis.acceleration / distance);
  }
  if (!std::isfinite(rate)) return true;  // already there
  motion_.moves = true;
  motion_.length = 0;
  for (size_t a = 0; a < commanded_.size(); ++a)
    motion_.length += std::pow(motion_.end[a] - motion_.start[a], 2);
  motion_.length = std::sqrt(motion_.length);
  // The manual leaves obstacles on this line to the operator (8); vmt asks PathGuard first.
  if (!GuardBlockMove(move)) return false;
  profile_.max_rate = rate;
  profile_.max_accel = accel;
  active_ = true;
  return true;
}

bool Channel::ApplySearchOffset() {
  BlockSearchRun& s = *search_;
  double deviation2 = 0;
  for (size_t a = 0; a < commanded_.size(); ++a)
    if (MainAxis(config_.axes[a].name)) deviation2 += std::pow(commanded_[a] - s.restart[a], 2);
  const double deviation = std::sqrt(deviation2);
  const double allowed = static_cast<double>(bs_started_.deviation_max) * 1e-4;
  if (deviation > allowed + 1e-9) {
    Fail("block search: the axes stand " + Mm(deviation) +
             " mm from the continue position, more than mc_cmd_bs_deviation_max_w allows (" +
             Mm(allowed) + " mm): bring them closer, or select the automatic return",
         kMsgBlockSearchDeviation);
    return false;
  }
  // 4.2, 8: the program goes on offset by where the axes stand, until its end or a reset.
  search_offset_.assign(commanded_.size(), 0.0);
  for (size_t a = 0; a < commanded_.size(); ++a) {
    const double offset = commanded_[a] - s.restart[a];
    search_offset_[a] = offset;
    shift_[a] += offset;
    translation_[a] += offset;
    s.restart_motion.start[a] += offset;
    s.restart_motion.end[a] += offset;
  }
  for (int k = 0; k < 2; ++k)
    if (const int axis = s.restart_motion.arc_axes[k]; axis >= 0)
      s.restart_motion.arc_centre[k] += search_offset_[static_cast<size_t>(axis)];
  return true;
}

void Channel::ContinueAfterSearch() {
  BlockSearchRun& s = *search_;
  bs_state_ = BlockSearchState::kInactive;
  state_ = ChannelState::kRunning;
  s.start_requested = false;
  if (spindle_.mode == DriveMode::kPosition) spindle_referencing_ = true;
  if (!s.restart_motion.moves) return;  // the next block starts the real run
  // The rest of the continue block, from the continue position on.
  motion_ = s.restart_motion;
  block_distance_start_ = s.restart_distance;
  block_distance_ = s.restart_length;
  distance_ = s.restart_distance + block_distance_;
  if (s.restart_u >= 1) return;
  profile_ = ProfileFrom(motion_, s.restart_u);
  continuation_ready_ = false;
  carry_speed_ = carry_accel_ = carry_leftover_ = 0;
  active_ = true;
}

bool Channel::StartBlockSearchHold() {
  if (breakpoint_hold_) {
    // 3.5: after the breakpoint the rest of its block runs on.
    breakpoint_hold_ = false;
    if (bs_state_ == BlockSearchState::kWaitForContinueContour)
      bs_state_ = BlockSearchState::kInactive;
    state_ = ChannelState::kRunning;
    if (breakpoint_rest_) {
      motion_ = *breakpoint_rest_;
      breakpoint_rest_.reset();
      profile_ = ProfileFrom(motion_, breakpoint_u_);
      active_ = true;
    }
    breakpoint_u_ = 0;
    return true;
  }
  if (!search_ || bs_state_ == BlockSearchState::kInactive) return false;
  if (bs_state_ == BlockSearchState::kWaitReturnToContour ||
      bs_state_ == BlockSearchState::kWaitForContinueContour)
    search_->start_requested = true;
  state_ = ChannelState::kRunning;  // a feed hold during the search or the return ends
  return true;
}

void Channel::DistanceCommand(const nc::PreparedBlock& b) {
  switch (b.distance_command) {
    case nc::DistanceCommand::kOn:
      distance_on_ = true;
      break;
    case nc::DistanceCommand::kOff:
      distance_on_ = false;
      break;
    case nc::DistanceCommand::kClear:
      distance_ = block_distance_start_ = 0;
      block_distance_ = 0;
      break;
    case nc::DistanceCommand::kNone:
      break;
  }
}

void Channel::CountDistance() {
  block_distance_start_ = distance_;
  block_distance_ = distance_on_ ? DistanceOf(motion_, config_.axes) : 0;
  distance_ += block_distance_;
  breakpoint_rest_.reset();
  // 3.5: the breakpoint stops the first time the path reaches it going forward.
  if (breakpoint_ <= 0 || block_distance_ <= 0 || breakpoint_ > distance_ + 1e-9 ||
      breakpoint_ < block_distance_start_ - 1e-9)
    return;
  const double u = std::clamp((breakpoint_ - block_distance_start_) / block_distance_, 0.0, 1.0);
  breakpoint_ = 0;
  breakpoint_pending_ = true;
  breakpoint_u_ = u;
  if (u < 1 - 1e-12) {
    breakpoint_rest_ = motion_;
    motion_ = Truncated(motion_, u);
  }
}

void Channel::HoldAtBreakpoint() {
  breakpoint_pending_ = false;
  breakpoint_hold_ = true;
  state_ = ChannelState::kHold;
  bs_state_ = BlockSearchState::kWaitForContinueContour;
}

void Channel::RemoveSearchOffset() {
  for (size_t a = 0; a < search_offset_.size() && a < shift_.size(); ++a) {
    shift_[a] -= search_offset_[a];
    translation_[a] -= search_offset_[a];
  }
  search_offset_.clear();
}

bool Channel::SpindleFunctions(const nc::PreparedBlock& b, DriveSetpoint& sp) const {
  bool orient = false;
  for (const nc::AuxFunction& f : b.aux) {
    if (f.letter != 'M' || config_.spindle_drive < 0) continue;
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
  BlockSearchStatus& st = bs_status_;
  st.state = bs_state_;
  st.command = bs_command_;
  const bool moving = motion_.moves && (active_ || breakpoint_hold_);
  // A corner the compensation inserted before its block is not yet the block's own path: the
  // per mille the search takes is measured in that (SimulateMotion).
  double u = moving && !inserted_piece_ ? std::clamp(profile_.u, 0.0, 1.0) : 0;
  // The breakpoint cut the block: its profile runs over the first part only.
  if (moving && breakpoint_rest_) u *= breakpoint_u_;
  st.covered_distance = u * 1000;
  st.dist_prog_start = active_ || breakpoint_hold_ ? block_distance_start_ + u * block_distance_
                                                   : distance_;
  st.block_count = block_.block_count;
  st.path_deviation = 0;
  st.continue_position.clear();
  if (search_ && !search_->restart.empty() && !breakpoint_hold_ &&
      (bs_state_ == BlockSearchState::kWaitForPlcOff ||
       bs_state_ == BlockSearchState::kWaitReturnToContour ||
       bs_state_ == BlockSearchState::kReturningToContour ||
       bs_state_ == BlockSearchState::kWaitForContinueContour)) {
    double d2 = 0;
    for (size_t a = 0; a < commanded_.size(); ++a)
      if (MainAxis(config_.axes[a].name)) d2 += std::pow(commanded_[a] - search_->restart[a], 2);
    st.path_deviation = std::sqrt(d2);
    st.continue_position = search_->restart;
    st.dist_prog_start = search_->restart_distance + search_->restart_u * search_->restart_length;
  }
  uint32_t sc = 0;
  using namespace stop_condition;
  const bool running = state_ == ChannelState::kRunning;
  const bool hold = state_ == ChannelState::kHold;
  if (breakpoint_hold_) sc |= kBreakpointStop;
  if (hold && single_block_) sc |= kSingleBlock;
  const bool search_hold = bs_state_ == BlockSearchState::kWaitReturnToContour ||
                           bs_state_ == BlockSearchState::kWaitForContinueContour;
  if (hold && !breakpoint_hold_ && !single_block_ && !search_hold) sc |= kFeedhold;
  if (!aux_output_.empty()) sc |= kPlcAcknowledge | kWaitTechnoAck;
  // The search waits for a changeover's acknowledgement as for a technology function's.
  if (bs_state_ == BlockSearchState::kActive && waiting_for_ != axes::HeadstockMode::kNone)
    sc |= kWaitTechnoAck;
  if (running && active_ && override_ == 0)
    sc |= block_.motion == nc::Motion::kRapid ? kOverrideRapidZero : kOverrideZero;
  if (dwell_left_s_ > 0) sc |= kDelayTime;
  if (state_ == ChannelState::kError) sc |= kChannelError;
  st.stop_conditions = sc;
  st.warnings = bs_warnings_;
}

}  // namespace vmt::control::channel
