#pragma once
// One NC channel: in automatic mode it runs a program through the interpreter, interpolates
// each prepared block on the NC cycle (G00 with every axis at its rapid limit, ending together;
// G01/G02/G03 at path feed, acceleration-limited; feed override; feed hold on the path),
// fine-interpolates to the drive tick, and commands the spindle. It writes setpoints for its own
// drives into the master telegram and leaves the others alone.

#include <algorithm>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "control/axes/axis_parameters.hpp"
#include "control/axes/headstock_changeover.hpp"
#include "control/axes/tool_table.hpp"
#include "control/axes/zero_offsets.hpp"
#include "control/channel/aux_output.hpp"
#include "control/channel/axis_jog.hpp"
#include "control/channel/axis_output.hpp"
#include "control/channel/backward_travel.hpp"
#include "control/channel/block_motion.hpp"
#include "control/channel/block_search.hpp"
#include "control/channel/block_search_run.hpp"
#include "control/channel/block_search_simulation.hpp"
#include "control/channel/cax_track.hpp"
#include "control/channel/channel_config.hpp"
#include "control/channel/channel_data.hpp"
#include "control/channel/channel_messages.hpp"
#include "control/channel/channel_types.hpp"
#include "control/channel/cycle_start.hpp"
#include "control/channel/enabling_signals.hpp"
#include "control/channel/fast_measurement.hpp"
#include "control/channel/further_spindle_control.hpp"
#include "control/channel/headstock_control.hpp"
#include "control/channel/jog_state.hpp"
#include "control/channel/look_ahead.hpp"
#include "control/channel/main_spindle_state.hpp"
#include "control/channel/nc_cycle_owner.hpp"
#include "control/channel/operator_messages.hpp"
#include "control/channel/path_guard_client.hpp"
#include "control/channel/path_profile.hpp"
#include "control/channel/program_events.hpp"
#include "control/channel/program_frames.hpp"
#include "control/channel/program_in_work.hpp"
#include "control/channel/programmed_stop.hpp"
#include "control/channel/repositioning.hpp"
#include "control/channel/spindle_synchronous_motion.hpp"
#include "control/channel/synchronous_block.hpp"
#include "control/channel/tool_storage_control.hpp"
#include "control/drive_bus.hpp"
#include "control/measure/measuring_cycle.hpp"
#include "control/measure/measuring_pages.hpp"
#include "control/nc/interpreter.hpp"
#include "control/path_guard.hpp"

namespace vmt::control::channel {

struct SpindleKeyMove;

/// A channel is a value: a copy, made or assigned at any NC cycle, runs on bit for bit as the
/// original would with the same inputs, and nothing either does reaches the other. What it was
/// given from outside is shared, not copied, and must outlive every copy: the programs, the event
/// source and sink, the measuring pages and PathGuard. A copy that is to run against others (a
/// copied run's gateway, pages, geometry) is given them again with the setters below. What
/// changes as it runs is its ChannelData (channel_data.hpp), apart from its constant config.
class Channel : private ChannelData {
 public:
  /// `programs`: the main program first, then the subprograms it may call; they must outlive
  /// the channel and its copies.
  Channel(ChannelConfig config, std::vector<const nc::Program*> programs);

  /// Everything the channel has changed since it was made: a value to keep and Restore.
  const ChannelData& data() const { return *this; }
  /// Back to where the channel stood when `data` was taken from it (or from a channel of the
  /// same config and programs). The data holds the outside parts as they were set then (event
  /// source and sink, measuring pages, PathGuard): set them again if they are others now.
  void Restore(const ChannelData& data) { static_cast<ChannelData&>(*this) = data; }

  void Start();  ///< cycle start: run, or resume after a hold
  void Stop();   ///< feed hold: brake on the path
  void Reset();  ///< Control-Reset: stop, back to the program start
  /// Feed override: the axes of the path, the rotary axis too (C-axis manual 2.3, 3.3).
  void SetFeedOverride(double fraction) { override_ = std::clamp(fraction, 0.0, 2.0); }
  /// Spindle override (AxxC.SOVR): the spindle's speed under M3/M4, never the feed axes.
  void SetSpindleOverride(double fraction) { sp_.override = std::clamp(fraction, 0.0, 2.0); }
  /// Process enabling signal (PxxC.ENABL). Removed: immediate stop (a running program holds, a
  /// changeover halts, jogging axes brake) and no start until it is back (C-axis manual 2.3).
  void SetProcessEnable(bool on);
  bool process_enabled() const { return enable_.process; }
  /// The spindle keys of manual mode, AxxC.M3 / M4 / M5 / M19 (rising edges; C-axis manual
  /// 4.2): `m` = 3, 4, 5 or 19. They select spindle mode on a headstock (aborting a changeover an
  /// immediate stop interrupted), then turn the spindle at its jogging speed, stop it or position
  /// it to its jogging spindle position. Ignored outside manual mode.
  void ManualSpindle(int m);
  /// The main spindle's jog keys AxxC.JGPOS / JGNEG (C-axis manual 2.3, 3.3, 4.3, 4.4): +1, -1,
  /// 0 released. Manual mode only. They select spindle mode on a headstock (aborting a
  /// changeover an immediate stop interrupted) and move the spindle as the jog mode says
  /// (PxxC.JOGM0..2): turning at its jogging speed (rapid) while held, or one increment or its
  /// parametric jogging distance per press; in handwheel mode the keys move nothing.
  void JogSpindle(int direction);
  /// AxxC.ENABL of a channel axis and of the main spindle (C-axis manual 4.2): without it the
  /// axis cannot be moved in manual mode, in rotary axis mode or spindle mode alike. Its keys
  /// start nothing and a continuous jog under way brakes (an increment runs to its end, as when
  /// the process enabling signal goes). Programmed motion does not ask for it.
  void SetAxisEnable(size_t axis, bool on);
  void SetSpindleEnable(bool on);
  bool axis_enabled(size_t axis) const { return axis >= enable_.axes.size() || enable_.axes[axis]; }
  /// AxxS.NC_NMAX of the main spindle: its speed command (override applied) at the speed limit
  /// Cxx.049 or beyond.
  bool SpindleAtSpeedLimit() const;
  /// Single block (semi-automatic): after each block the channel holds until the next start.
  void SetSingleBlock(bool on) { single_block_ = on; }
  /// The optional-stop signal: M01 holds like M00 while it is set (programmed_stop.hpp).
  void SetOptionalStop(bool on) { programmed_stop_.optional = on; }
  /// Changes the mode; refused (false) while a program runs. An interrupted program (hold)
  /// stays interrupted: the axes may be jogged away and the program continued later.
  bool SetMode(ChannelMode mode);
  ChannelMode mode() const { return mode_; }
  /// Drive ticks per NC cycle: the gateway is served once per cycle.
  int ticks_per_cycle() const { return config_.ticks_per_cycle; }
  /// Jog increment in mm | deg; 0 jogs continuously while the key is held.
  void SetJogIncrement(double increment);
  /// Jog key of a fictive axis of the active G31 transformation: `axis` 0 X1, 1 Y1 (REPOS
  /// manual 5.2: X and C move as a Cartesian jog). False, and nothing moves, outside manual
  /// mode or without G31 and rotary axis mode.
  bool JogFictive(int axis, int direction);
  /// Handwheel counts for a fictive axis of the active G31 transformation (JogMode::kHandwheel;
  /// `axis` 0 X1, 1 Y1): the point moves on a line of the face, as JogFictive's keys do. False,
  /// and nothing moves, where JogFictive would refuse or outside handwheel mode.
  bool HandwheelFictive(int axis, int counts);
  /// Jog mode from the JOGM0..2 code (0..7).
  void SetJogMode(int code);
  JogMode jog_mode() const { return jog_.mode; }
  /// Handwheel counts for a channel axis (JogMode::kHandwheel): the axis follows at most at
  /// its jogging rapid speed.
  void Handwheel(size_t axis, int counts);
  /// Program selection: `index` of the channel's programs becomes the main program of the next
  /// start; the others stay callable. Refused (false) while a program is active or interrupted
  /// (selecting another would drop the interruption point); the measuring pages, tool list and
  /// zero offsets stay as they are, so a calibration program's results serve the next program.
  bool SelectProgram(size_t index);
  /// MDI: the block(s) to run at the next start in MDI mode, in the main program's dialect.
  /// False, with the channel in its error state, if the text does not parse.
  bool Mdi(const std::string& text);
  /// Reverse program: while interrupted (hold) or after an error, continue at the main
  /// program's `.HOME` label (fast-measurement manual 4.4), first along a measuring
  /// instruction's reverse vectors and from the label of the REV valid at the interrupted block
  /// (REPOS manual 4.1; nc::Interpreter::Reverse). PxxS.REV while it runs.
  bool Reverse();
  bool reversing() const { return reversing_; }
  /// Auxiliary functions (M, H, Q, T) of the block in work that wait for the PLC.
  const std::vector<nc::AuxFunction>& aux_output() const { return aux_.functions; }
  /// Increments with every new output of auxiliary functions (the strobe).
  uint32_t aux_strobe() const { return aux_.strobe; }
  void AcknowledgeAux() { aux_.functions.clear(); }
  /// Jog key of a channel axis: +1 positive, -1 negative, 0 released. Manual mode only; an
  /// increment, once started, is completed.
  void Jog(size_t axis, int direction);
  /// AxxC.HOME of a channel axis (rising edge; C-axis manual 4.2: homing "like it does for the
  /// remaining axes"): in manual mode the axis travels to its reference point at its homing
  /// speed, as G74 takes it, and has its reference when it arrives. Gated like an increment
  /// (process and axis enabling signals, PathGuard); the rotary axis of a headstock selects
  /// rotary axis mode first. Ignored outside manual mode.
  void HomeAxis(size_t axis);
  /// AxxC.HOME of a main spindle that is no channel axis (section 3): homing as the manual
  /// homes a spindle, by positioning (2.3, 3.3 Homing: M19 crosses the zero impulse), here to
  /// its reference point; AxxS.HOMED when it is in position. Gated as AxxC.M19; manual mode.
  void HomeSpindle();
  /// PxxC.MGPOS / PxxC.MGNEG (REPOS manual 3.4): +1, -1, 0 released. In manual mode the NC
  /// jogs an NC-controlled tool storage axis as the jog mode jogs the feed axes: continuously
  /// at its jogging speed (rapid), one increment per press, or not at all in handwheel mode;
  /// also during repositioning and NC-block restart, where it may pass its target (endless
  /// rotation). Ignored for one the PLC controls (the PLC reads the same signals) and outside
  /// manual mode.
  void JogToolStorage(int direction);
  /// The tool storage axis' command (deg | mm), an NC-controlled one's; NaN otherwise.
  double tool_storage_command() const;
  /// A fault outside the program (the PLC stopped, ...): immediate stop, the error state with
  /// `number` and `text`; Control-Reset clears it.
  void MachineFault(const std::string& text, int number) {
    if (state_ != ChannelState::kError) Fail(text, number);
  }
  /// A safety switch of an axis or the main spindle opened (AxxC.OTRVL safety limit switch,
  /// AxxC.MTAS thermal protection, C-axis manual 4.2): immediate stop as for a drive fault,
  /// every jog and the spindle included, and the error state with `number` and `text`.
  /// Control-Reset clears it, so that the axis can then be jogged off the switch.
  void SafetyStop(const std::string& text, int number);
  /// The PLC's side of the headstock changeover (ROTMOD_Q, SPMOD_Q, enables, AXD idents),
  /// given by the gateway every NC cycle.
  void SetHeadstockPlc(const axes::HeadstockPlc& plc) { headstock_.SetPlc(plc); }
  /// The headstock changeover, null without one.
  const axes::HeadstockChangeover* headstock() const { return headstock_.changeover(); }
  /// The channel writes drive `d`'s setpoint at its next Tick: once started (or given the axes
  /// of another channel) it is the one owner of its feed axes', spindles' and headstock's
  /// drives, and of an NC-controlled tool storage axis it has taken. Before, the scene holds
  /// them (the timeline player).
  /// Drive `d` is one the channel writes once it holds its axes (WritesDrive), in some state.
  bool MayWriteDrive(size_t d) const {
    return (d < drives_written_.size() && drives_written_[d]) ||
           (config_.tool_storage_drive >= 0 &&
            d == static_cast<size_t>(config_.tool_storage_drive) && tool_storage_.nc());
  }
  bool WritesDrive(size_t d) const {
    // Tick takes the axes when a start or a hand-over is pending, before it writes.
    if (!out_.holding && !start_.program && !out_.take_over_pending) return false;
    if (d < drives_written_.size() && drives_written_[d]) return true;
    return config_.tool_storage_drive >= 0 &&
           d == static_cast<size_t>(config_.tool_storage_drive) && ToolStorageNc() &&
           tool_storage_.axis().taken;
  }
  /// Direction the axis is commanded to move this NC cycle: +1, -1 or 0 (MVPOS / MVNEG).
  int AxisMotion(size_t axis) const;
  /// Events (BES/BEC) come from here; without a source, the events the program set itself.
  void SetEventSource(std::function<bool(int)> source) { events_.source = std::move(source); }
  /// SE n / RE n of the program go here (the gateway's Pxx.EVn); the channel also keeps them.
  void SetEventSink(std::function<void(int, bool)> sink) { events_.sink = std::move(sink); }

  /// The machine data pages of fast measurement (MTD, the measuring instructions); null: none.
  /// They must outlive the channel.
  void SetMeasuringPages(measure::MeasuringPages* pages) { measuring_.SetPages(pages); }
  /// The measuring setting of SETTING( ), until the program ends or Control-Reset.
  const std::optional<measure::MeasuringSetting>& measuring_setting() const {
    return measuring_.setting();
  }
  /// The stylus' way back for the reverse program (fast-measurement manual 4.4).
  const measure::ReverseVectors& reverse_vectors() const { return measuring_.reverse_vectors(); }

  /// The machine geometry's check of approach moves (ChannelConfig::path_guard says what a
  /// contact does); null: none. It must outlive the channel.
  void SetPathGuard(PathGuard* guard) { guard_.SetGuard(guard); }
  /// The checks made since the last call, oldest first.
  std::vector<GuardRecord> TakeGuardRecords() { return guard_.TakeRecords(); }
  /// Warnings of the measuring instructions since the last call ("file:line:col: warning: ...").
  std::vector<std::string> TakeMeasuringWarnings() { return measuring_.TakeWarnings(); }

  /// Repositioning and NC-block restart (REPOS manual): the PLC's PxxC.REPOS and PxxC.RESTA,
  /// levels given every NC cycle. They count only while the program is interrupted and an axis
  /// has been jogged off the contour (2.1, 7.1); both at once ask for neither.
  void SetReposition(bool repositioning, bool restart);
  /// PxxS.REPOS (7.2): the program is interrupted, until it resumes or Control-Reset.
  bool repos_allowed() const { return state_ == ChannelState::kHold || repos_.run(); }
  /// PxxS.CREST (7.3), as of the last NC cycle.
  bool conditions_restored() const { return repos_.conditions_restored(); }
  ReposFunction repos_function() const { return repos_.function(); }
  /// The REPOS screen's data (2.2); empty axes when nothing is interrupted. Without `whole`
  /// only the function, the status and the axes' and spindles' values and adjust symbols: not
  /// the program, line, tool, technology and G codes shown beside them (for a watcher that
  /// compares the screen every NC cycle).
  ReposStatus repos_status(const AmplifierTelegram* at = nullptr, bool whole = true) const;
  /// Operator edits during an interruption (2.5): a zero offset G54..G59 of a channel axis, and
  /// a tool edge's length along a channel axis. They move the interruption point and the block
  /// start with the contour. False if there is no such table entry.
  bool SetZeroOffset(int g, size_t axis, double value);
  bool SetToolLength(int tool, int edge, size_t axis, double value);

  /// Block search (twincat-cnc-block-search-de.md): the CNC objects mc_cmd_bs_*_w as they
  /// stand; the next program start takes them (5: later changes do not touch the running
  /// program). False, with the error in `text`, if they are out of range.
  bool SetBlockSearch(const BlockSearchParameters& p, std::string* text = nullptr);
  /// The parameters the running program was started with (the _r read-backs).
  const BlockSearchParameters& block_search_parameters() const { return bs_.started; }
  /// The PLC's side of the on/off handshake (7): enable_w (it wants to be told) and its
  /// acknowledgement, the PLC's signal of bahn_lc_control.block_search.
  void SetBlockSearchPlc(bool enable, bool acknowledged) {
    bs_.plc_enable = enable;
    bs_.plc_state = acknowledged;
  }
  /// State and status data of block search and path (5.5, 5.6), as of the last NC cycle.
  const BlockSearchStatus& block_search() const { return bs_.status; }

  /// Backward travel (block search manual 4.3): the direction the next start takes while the
  /// program is held. Backward, the NC travels the path of the blocks it ran - or, after block
  /// search, decoded - in reverse, block by block, at their feeds (G00 at rapid), until feed
  /// hold or the oldest block it remembers (PathMemory::kBlocks); forward, it travels the path
  /// again up to the interruption point and the program goes on from there. The manual does not
  /// name the command; the gateway's is vmt's. Not possible (message kMsgBackward, the program
  /// stays held) with an offset from a manual return after block search (4.2: "Bei einem
  /// Offset > 0 ist Rückwärtsfahren nicht möglich"), during repositioning, or across a block
  /// it cannot travel back (G74, G33/G63/G64, measuring, G31: the path memory starts after it).
  void SetBackward(bool on) { backward_.Request(on); }
  /// HLI.channel.SuspendAxisOutput (block search 4.2.1): the PLC lends the channel's feed axes
  /// to its JogOfPath channel (jog_of_path.hpp). While the output is suspended the channel
  /// follows where the other channel commands them (FollowAxesOf: its setpoints are that
  /// channel's, which writes after it) and moves none of them itself; block search
  /// decodes on, and every motion of its own (the return to the contour too) waits for the axes
  /// to come back. The change is taken at standstill, both ways ("grundsätzlich im Stillstand
  /// der Achsen"). The rotary axis of a headstock rides on the spindle and is never lent.
  void SetSuspendOutput(bool on) { out_.suspend_requested = on; }
  /// Another channel still holds the axes: the output stays suspended until it gives them back.
  void SetAxesElsewhere(bool on) { out_.axes_elsewhere = on; }
  bool suspend_output_requested() const { return out_.suspend_requested; }
  bool output_suspended() const { return out_.suspended; }
  /// While the output is suspended: the lent axes stand where `holder` commands them, and the
  /// channel goes on from there without a step when they come back.
  void FollowAxesOf(const Channel& holder);
  /// No axis of the channel moved in the last NC cycle and no jog is under way.
  bool AxesAtRest() const;
  /// The axes stand (or move) on the path behind the interruption point.
  bool travelling_back() const { return backward_.away(); }
  /// Blocks of the path memory behind the axes while travelling back (0 at the interruption
  /// point).
  size_t blocks_back() const { return backward_.blocks_back(); }

  /// One drive tick: reads the feedback, interpolates on the NC cycle, writes setpoints.
  void Tick(const AmplifierTelegram& at, MasterTelegram& mdt);

  ChannelState state() const { return state_; }
  /// "file:line:column: error: text" of the error that stopped the program.
  const std::string& error() const { return error_; }
  /// Its message number (channel_messages.hpp), 0 when there is none.
  int error_number() const { return error_number_; }
  /// The PLC's message (MSG_WR / MSG_WR_N), as the gateway reads it each NC cycle.
  void SetPlcMessage(const PlcMessage& m) { plc_message_ = m; }
  const PlcMessage& plc_message() const { return plc_message_; }
  /// The NC's message list: the error in force, then the PLC's message.
  std::vector<OperatorMessage> messages() const;
  /// The modal state of the program (initial state before the first block).
  const nc::ModalState& modal() const;
  /// Axis referenced (homed): from the start, or after G74; the rotary axis of a headstock
  /// also after M19 on the same drive, and it loses it when its encoder runs too fast.
  bool homed(size_t axis) const { return frames_.homed[axis]; }
  /// The main spindle's reference (AxxS.HOMED of the spindle): established by M19, lost when
  /// its encoder's frequency exceeds the limit (C-axis manual 2.3, 3.3 Homing).
  bool spindle_homed() const;
  /// Position indication of a headstock (C-axis manual 2.3, 3.3): the axis designation shown,
  /// the spindle's (S1) or the rotary axis' (C), switched only when a changeover has completed.
  /// Empty without a headstock.
  std::string HeadstockAxisName() const;
  /// The value shown beside it, 0..360 deg: the rotary axis' position in program coordinates
  /// (modulo one turn, though the program may run C past it), or the spindle's actual position.
  double HeadstockPosition() const;
  /// Status indication of the main spindle (as of the last NC cycle); a channel without a
  /// spindle shows its overrides only.
  SpindleStatus spindle_status() const;
  /// Translation program -> axis position of a channel axis under the current modal state:
  /// zero offset + G92 shift - tool length.
  double Translation(size_t axis) const { return frames_.translation[axis]; }
  /// The program address of channel axis `axis` (X, Z, C).
  const std::string& AxisName(size_t axis) const { return config_.axes[axis].name; }
  /// Commanded position of a channel axis: the axis position the drive is commanded to (mm |
  /// deg); the program's coordinate is this less Translation(). Valid once holds_positions().
  double position(size_t axis) const { return out_.commanded[axis]; }
  /// The channel has taken its axes over (the first start or jog): it commands their setpoints.
  bool holds_positions() const { return out_.holding; }
  const ChannelConfig& config() const { return config_; }
  /// Source line of the block in work, 0 when none.
  uint32_t line() const;

 private:
  /// TLD(...) the tool list, OTD(...) the zero offsets, MTD(...) the machine data pages
  /// (SetMeasuringPages; null: MTD is an error), for the interpreters (channel_data_access.cpp).
  nc::DataAccess MakeDataAccess();
  /// Who owns this NC cycle: the first that applies, in the order of NcCycleOwner
  /// (channel_cycle.cpp); ProgramCycleOwner is its part within a running or held program.
  NcCycleOwner CycleOwner() const;
  NcCycleOwner ProgramCycleOwner() const;
  /// The program's NC cycle: what `owner` does, then the block in work's motion.
  void ProgramCycle(NcCycleOwner owner, const AmplifierTelegram& at, double dt);
  bool NextBlock(const AmplifierTelegram& at);
  /// The block in work starts (channel_run_block.cpp): false if it failed the channel.
  bool RunBlock(const AmplifierTelegram& at);
  /// The headstock mode the block needs: a changeover requested (true: the block waits), a
  /// block the mode forbids (false, failed); nullopt: it goes on.
  std::optional<bool> HeadstockBlockStart(const nc::Program& program);
  /// Its instructions (MTP, MRY, #-commands ...); `mry`: it waits for the tool storage axis.
  bool BlockInstructions(const nc::Program& program, bool& mry);
  /// Its zero offset, tool length and G92 shift.
  bool BlockOffsets(const nc::Program& program);
  /// Its functions of the main and further spindles.
  bool BlockSpindles(const nc::Program& program);
  // The blocks after the one in work (block_feed.hpp; the channel's side in
  // channel_read_ahead.cpp). The feed's context and reporting a block's error it found.
  FeedContext FeedContextNow() const;
  void FailAt(const BlockError& e);
  bool NextCompensated(const AmplifierTelegram& at);
  /// Under G41/G42, reads on (through ReadNext, or straight from the interpreter while
  /// `searching`) until the compensation has a final piece ready (kPiece), has given out all it
  /// read (kDrained: the feed compensates no more; its source_done says whether the text ended)
  /// or failed.
  enum class Compensated { kPiece, kDrained, kFailed };
  Compensated FillReadyPiece(bool searching);
  /// G41/G42 begins with work_.block: from here on the channel reads ahead, so that each
  /// block's path is offset with its successor in view. `position`: where the program has the
  /// axes (machine coordinates), the start of the contour.
  bool StartCompensation(const std::vector<double>& position);
  void DropLookahead();
  bool StartMotion(const AmplifierTelegram& at);
  void LookAhead(const AmplifierTelegram& at);
  bool ReadNext(nc::PreparedBlock& b);
  /// The program's next block from the interpreter: every read of the program (block by
  /// block, the look-ahead, the G41/G42 read-ahead, the search) goes through here. False at
  /// the text's end, on an interpreter error, and at block search type 1's end position (3.1).
  bool ReadSource(nc::PreparedBlock& b);
  double SpindleRevPerS(const AmplifierTelegram& at) const;
  bool UpdateTranslation(const nc::ModalState& modal, const nc::Program& program, int32_t block);
  bool NextHomingStage();
  void Interpolate(double dt);
  void Fail(const std::string& message, int number = kMsgProgramError);
  void Fail(const nc::Program& program, int32_t block, const std::string& text, int number);
  nc::Interpreter MakeInterpreter();
  /// After the program end: its interpreter, interruption and measuring setting are dropped, so
  /// that the next start (of it or of another selected program) begins at the first block.
  void ForgetEndedProgram();
  const nc::Program* ProgramOf(uint32_t index) const;

  ChannelConfig config_;  ///< never written after construction (a channel is copy-assignable)
  std::vector<const nc::Program*> programs_;

  /// The drives Tick writes once the channel holds its axes (WritesDrive), by drive index;
  /// the tool storage axis' aside.
  std::vector<bool> DrivesWritten() const;
  std::vector<bool> drives_written_ = DrivesWritten();
  /// What Start() would do now; it changes nothing.
  CycleStart StartCase() const;
  /// Start() while the program holds on its path: it goes on if no axis has left the contour.
  void ContinueHeldProgram();
  /// The output is suspended and `axis` is one the JogOfPath channel takes.
  bool Lent(size_t axis) const {
    return out_.suspended && !(headstock_ && static_cast<int>(axis) == config_.rotary_axis);
  }
  void Jogging(double dt);
  /// The handwheel's counts start afresh from where each jogged axis (X1/Y1 too) comes to rest.
  void RestartHandwheel();
  // Jogging X1/Y1 under G31 (channel_fictive_jog.cpp).
  /// The jog mode's rules for every jogged axis: feed axes, X1/Y1 and the tool storage axis
  /// (REPOS manual 3.4: "as it would in jog mode").
  JogRules jog_rules() const;
  static constexpr double kFictiveJogCentre = 0.1;  ///< mm: the jog stops this far from the centre
  bool FictiveJogAxes(int& x, int& c) const;
  void FictiveJogging(double dt);
  bool GuardFictiveJog(int x, int c, nc::FictivePoint next);

  int axis_z_ = -1, axis_x_ = -1;  ///< channel axes of the G18 plane
  /// A feed axis or X1/Y1 still jogs: braking after a mode change, or an increment under way.
  bool JogsMoving() const;
  // PathGuard of the jog moves (channel_path_guard.cpp).
  void GuardJog(double dt);
  /// An increment of `axis` to `to_position`, checked whole before it starts: false if stopped.
  bool GuardIncrement(size_t axis, double to_position);
  /// The block motion about to start (work_.motion), checked whole (or up to `end`, per channel
  /// axis): false if stopped. `measuring_path`: a probe's, on which the ruby may touch the part.
  bool GuardBlockMove(const std::string& move, const std::vector<double>* end = nullptr,
                      bool measuring_path = false);
  std::vector<double> GuardFrom() const;  ///< every drive's position, the channel's commanded
  /// A curved block motion (an arc, or G31's line or arc of the face) as chords, each within
  /// kChordTolerance of the curve.
  bool GuardCurvedMove(const std::string& move);
  static constexpr double kChordTolerance = 1e-3;  ///< mm
  static constexpr int kMaxChords = 20000;         ///< a bound on the work (0.1 mm min. clearance)
  bool GuardStops(const std::string& move, const std::vector<double>& from,
                  const std::vector<double>& to, const PathCheck& check);
  /// After a contact PathGuardClient recorded: with `stop`, the NC error naming the parts and
  /// where, and true.
  bool StopAhead(bool stop, const std::string& move, const std::vector<double>& from,
                 const std::vector<double>& to, const PathCheck& check);
  // PathGuard of the NC turret's index and of a spindle start (channel_turret_guard.cpp).
  /// A straight move of the drives; while the NC turret indexes, against it as it turns on.
  PathCheck GuardCheck(const std::vector<double>& from, const std::vector<double>& to,
                       bool measuring_path = false);
  /// The NC turret indexes while the drives move from `from` to `to` (its drive standing).
  bool IndexingBeside(const std::vector<double>& from, const std::vector<double>& to) const;
  /// The turret's index from `from` to `to` (deg), its sweep checked whole before it starts:
  /// false if stopped.
  bool GuardTurretIndex(const std::string& move, double from, double to);
  /// A continuous turret jog (`direction`) that could reach `to` checked ahead as GuardJog: true
  /// if it stopped the jog.
  bool GuardTurretJog(int direction, double from, double to);
  /// The main spindle about to take setpoint `sp`: a start sweeps what turns with it. False
  /// if stopped.
  bool GuardSpindleStart(const std::string& move, const DriveSetpoint& sp);
  // Repositioning and NC-block restart (repositioning.hpp); the REPOS subroutine's run in
  // channel_repositioning.cpp.
  /// What repositioning reads of the channel now.
  ReposView ReposViewNow() const;
  // Backward travel (backward_travel.hpp; the channel's side in channel_backward.cpp).
  /// A block's motion starts: remembered for backward travel (`rapid`: G00).
  void RecordPath(const BlockMotion& motion, bool rapid);
  /// A block backward travel cannot take: the path before it is forgotten.
  void PathBarrier() { backward_.Forget(); }
  /// Start() while held on backward travel's path: a backward or forward leg.
  void StartReplay();
  void ReplayCycle(double dt);
  /// PathGuard's check of a G00 leg along a path block search decoded.
  ReplayGuard ReplayGuardOf();
  void ReplayArrived(ReplayStep step);
  void RefuseBackward(const std::string& why);
  void SwapProgramInWork();
  void CaptureInterruption();
  /// Program -> axis translation of `modal` with the tables as they are now (no G92 check).
  std::vector<double> TranslationOf(const nc::ModalState& modal) const;
  bool ToolStorageKnown() const;
  // An NC-controlled tool storage axis (tool_storage_control.hpp); the program's side of it in
  // channel_tool_storage.cpp.
  bool ToolStorageNc() const { return tool_storage_.nc() && ToolStorageKnown(); }
  /// PathGuard's checks of the tool storage axis' moves (channel_turret_guard.cpp).
  TurretGuard TurretGuardOf();
  void ToolStorageCycle(double dt);
  /// MTP (4.2 Tool Storage Axis): the NC traverses it back to the interruption's position.
  /// False if PathGuard stopped it.
  bool ReturnToolStorage();
  /// An NC-controlled tool storage axis starts for tool `tool`'s station (4.2: asynchronously,
  /// the block does not wait): a T word, MTP outside the REPOS subroutine. T0 and a turret
  /// without stations stay where they are. False, with the channel in its error state at
  /// `block`, for a tool that has no station.
  bool IndexToolStorage(int tool, const nc::Program& program, int32_t block);
  /// The T words of `b` (IndexToolStorage); true without an NC-controlled tool storage axis.
  bool IndexToolStorage(const nc::PreparedBlock& b, const nc::Program& program);
  /// The program's traverse (T, MTP) has ended and the drive stands within kToolStorageWindow
  /// of its place; true when there is none.
  bool ToolStorageArrived() const;
  void ReposCycle(const AmplifierTelegram& at);
  void StartReposRun();
  bool CheckReposBlock();
  bool StartReposMotion(const AmplifierTelegram& at);
  bool FinishReposRun(const AmplifierTelegram& at);
  /// The REPOS subroutine's @ variables back to the interrupted program (one set, 8.3).
  void HandBackVariables();
  // Fast measurement (fast_measurement.hpp; the channel's side in channel_measuring.cpp).
  /// What the fast measurement is handed for one call: the block in work, the axis output,
  /// the events, the PLC's functions, PathGuard's check and the channel's error state.
  MeasuringLink MeasuringLinkNow();
  /// work_.block, a block a measuring instruction generated, planned from where the axes are
  /// commanded: false, failed, for an axis without its reference or a plan's error.
  bool PlanGeneratedMotion();
  // Block search's phases (channel_block_search.cpp); the skipped blocks are search_'s.
  // #CAX TRACK (cax_track.hpp, channel_cax_track.cpp): on with its options, in a run and in
  // the search alike; a C-only move of a turn beyond ANGLIMIT runs before the block.
  int TrackedAxis() const;
  /// #CAX TRACK in `st` of block `b`, C standing at `c_machine`: nothing if `st` is another
  /// command, false if it failed (Fail called).
  std::optional<bool> CaxTrackInstruction(const nc::Program& program, const nc::Statement& st,
                                          nc::PreparedBlock& b, double c_machine);
  /// While tracking: `b`'s C target from its path's tangent, the block starting at `from`;
  /// `align_to` set (machine coordinates) when C turns alone first. False on an error.
  bool TrackC(nc::PreparedBlock& b, const std::vector<double>& from, double rev_per_s,
              std::optional<double>& align_to);
  bool StartCaxAlignment(double to);
  /// A program start: block search, breakpoint and entry point as the parameters say.
  void BeginBlockSearch();
  /// The search's part of an NC cycle; true while it owns the cycle (no normal block flow).
  bool SearchCycle(const AmplifierTelegram& at);
  /// What the skipped blocks are handed (block_search_simulation.hpp) for one NC cycle.
  SearchLink SearchLinkNow();
  /// The search's next block into work_.block: from the interpreter, or under G41/G42 the next
  /// piece of the tip path. False on an error.
  bool NextSearchBlock();
  void EndSearchMode();
  bool SpindleReady(const AmplifierTelegram& at) const;
  bool StartReturnToContour();
  /// One straight move from where the axes stand to `to` at the rapid limits, PathGuard first.
  bool StartReturnMove(const std::vector<double>& to, const std::string& move);
  bool ApplySearchOffset();
  void ContinueAfterSearch();
  /// A start while the search or the breakpoint holds.
  void StartBlockSearchHold();
  void RemoveSearchOffset();
  /// Block search 3.5: the breakpoint stops the path like an M0 until the next start.
  void HoldAtBreakpoint();
  void UpdateBlockSearchStatus();
  /// The headstock mode block `b` needs (HeadstockControl::ModeNeeded).
  axes::HeadstockMode ModeNeeded(const nc::PreparedBlock& b) const {
    return HeadstockControl::ModeNeeded(b, config_.rotary_axis);
  }
  /// The rotary axis as a PlanBlockMotion follow_up bit while the NC does not position it.
  uint64_t FollowUpAxes(const nc::PreparedBlock& b) const;
  /// The headstock's NC cycle (HeadstockControl::Cycle) and what it means for the channel: its
  /// error, the rotary axis' offsets, the rotary axis' command following its actual position.
  void HeadstockCycle(const AmplifierTelegram& at, double dt);
  /// 4.2: the one drive of a spindle with rotary axis capability is monitored by its axis'
  /// AxxC.READY in both modes.
  void CheckAxisReady();
  /// A changeover commanded by a manual key (jog of the rotary axis, spindle keys).
  void ManualChangeover(axes::HeadstockMode target);
  /// Takes a main spindle key's move (main_spindle_keys.hpp) as the spindle's command.
  void ApplySpindleKey(const SpindleKeyMove& move);
  /// References of spindle and rotary axis: M19, encoder frequency (2.3, 3.3).
  void TrackReferences(const AmplifierTelegram& at, double dt);
  /// Drives: faults stop the channel; Control-Reset acknowledges trips.
  void CheckDrives(const AmplifierTelegram& at);
  void CollectTrips(const AmplifierTelegram& at);
  void AcknowledgeDriveTrips(MasterTelegram& mdt);
  DriveSetpoint SpindleSetpoint() const;
  // Spindle-synchronous block in work (G33/G63/G64, channel_spindle_synchronous.cpp).
  SynchronousContext SynchronousContextNow();
  bool StartSynchronous(const AmplifierTelegram& at);
  void SynchronousCycle(const AmplifierTelegram& at, double dt);
  bool InSynchronousBlock() const { return work_.active && sync_.active(); }
  /// A changeover to rotary axis mode has ended: the block in work and the interpreter take
  /// the rotary axis' actual position.
  void RebaseRotaryAxis();
};

}  // namespace vmt::control::channel
