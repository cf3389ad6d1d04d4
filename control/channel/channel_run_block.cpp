// A block's start in the channel (RunBlock): the headstock mode it needs, its instructions, its
// offsets, its spindle functions, the auxiliary functions for the PLC, then its motion.
#include <optional>
#include <string>

#include "control/channel/channel.hpp"
#include "control/channel/spindle_functions.hpp"

namespace vmt::control::channel {

bool Channel::RunBlock(const AmplifierTelegram& at) {
  const nc::Program& program = *ProgramOf(work_.block.program);
  // G77 (REPOS manual 4.2) is refused at the start of its block, before any changeover.
  if (work_.block.repos && !headstock_.waiting() && !CheckReposBlock()) return false;
  if (const std::optional<bool> waiting = HeadstockBlockStart(program)) return *waiting;
  auto unsupported = [&](const std::string& what) {
    Fail(program, work_.block.block, what + " is not supported by vmt (docs/conformance.md)",
         kMsgNotAvailable);
    return false;
  };
  if (work_.block.measuring) return unsupported("G100 measuring");
  if (work_.block.has_centre && work_.block.motion != nc::Motion::kArcCw &&
      work_.block.motion != nc::Motion::kArcCcw)
    return unsupported("I/J/K outside G02/G03");

  // The T word indexes an NC-controlled turret before MTP / MRY of its block act on it.
  if (!IndexToolStorage(work_.block, program)) return false;
  bool mry = false;
  if (!BlockInstructions(program, mry)) return false;
  // MRY: until the drive stands at the place, not only its command (a following error lags).
  if (mry) tool_storage_wait_ = !ToolStorageArrived();
  bs_.program_distance.Command(work_.block.distance_command);
  if (!work_.block.calls.empty()) {
    PathBarrier();  // a probing move is no path to travel back along
    return measuring_.Start(MeasuringLinkNow());
  }
  for (const auto& [n, set] : work_.block.events) {
    events_.own[n] = set;
    if (events_.sink) events_.sink(n, set);
  }
  if (!BlockOffsets(program)) return false;
  if (!BlockSpindles(program)) return false;

  // M, H, Q and T go to the PLC; the block goes on when it has acknowledged them.
  if (config_.aux_handshake) {
    for (const nc::AuxFunction& f : work_.block.aux)
      if (f.letter == 'M' || f.letter == 'H' || f.letter == 'Q' || f.letter == 'T')
        aux_.functions.push_back(f);
    if (!aux_.functions.empty()) ++aux_.strobe;
  }

  programmed_stop_.Prepare(work_.block);
  work_.dwell_left_s = work_.block.dwell_s;
  if (work_.block.end) state_ = ChannelState::kEnded, reversing_ = false;
  if (work_.block.motion == nc::Motion::kNone && !work_.block.homing && !work_.block.repos)
    return true;
  if (!aux_.functions.empty() || tool_storage_wait_) {
    work_.pending_motion = true;
    return true;
  }
  return StartMotion(at);
}

std::optional<bool> Channel::HeadstockBlockStart(const nc::Program& program) {
  if (!headstock_) return std::nullopt;
  const axes::HeadstockMode need = ModeNeeded(work_.block);
  if (need != axes::HeadstockMode::kNone && headstock_->mode() != need) {
    headstock_.RequestForBlock(need);
    return true;
  }
  if (headstock_.EndWait() == axes::HeadstockMode::kRotary) RebaseRotaryAxis();
  // X1/Y1 of G31/G32 position C, which the NC does only in rotary axis mode; unlike C they
  // do not select it (coordinate_transformation.hpp).
  if (work_.block.fictive && headstock_->mode() != axes::HeadstockMode::kRotary) {
    Fail(program, work_.block.block,
         "X1/Y1 of G" + std::to_string(nc::GCode(work_.block.modal.transformation)) +
             " need the headstock in rotary axis mode: select it (G00 " +
             config_.axes[config_.rotary_axis].name + "..) first",
         kMsgTransformation);
    return false;
  }
  // C-axis manual 2.3: offsets of the rotary axis are programmed only in rotary axis mode.
  // The manual is silent on G92 C in spindle mode; a control refuses it rather than shift an
  // axis it does not position.
  const size_t r = static_cast<size_t>(config_.rotary_axis);
  if (work_.block.set_position && (work_.block.programmed >> r & 1) &&
      headstock_->mode() != axes::HeadstockMode::kRotary) {
    Fail(program, work_.block.block,
         "G92 of " + config_.axes[r].name + " outside rotary axis mode: program " +
             config_.axes[r].name + " in a G00/G01 block first",
         kMsgOffsetInSpindleMode);
    return false;
  }
  return std::nullopt;
}

bool Channel::BlockInstructions(const nc::Program& program, bool& mry) {
  // Instructions vmt does not implement stop the program rather than pass unnoticed. The
  // #-commands that only steer block search (and its return to the contour) have no effect on
  // a normal run.
  for (uint32_t index : work_.block.instructions) {
    const nc::Statement& st = program.statements[index];
    if (st.kind == nc::Statement::Kind::kHashCommand) {
      const std::string& text = program.texts[st.text];
      if (const std::string refused = RefusedHashCommand(st.hash); !refused.empty()) {
        Fail(nc::Format({st.pos, refused}, program.files), kMsgNotAvailable);
        return false;
      }
      const int c = TrackedAxis();
      if (const auto done = CaxTrackInstruction(
              program, st, work_.block, c < 0 ? 0 : out_.commanded[static_cast<size_t>(c)])) {
        if (!*done) return false;
        continue;
      }
      if (SteersBlockSearch(st.hash)) continue;
      Fail(nc::Format({st.pos, "instruction #" + text.substr(0, text.find(' ')) +
                                   " is not supported by vmt (docs/conformance.md)"},
                      program.files),
           kMsgNotAvailable);
      return false;
    }
    const bool mtp = st.instruction == nc::Instruction::kMtp;
    const bool waits = st.instruction == nc::Instruction::kMry;
    // REPOS manual 4.2 Tool Storage Axis: in the REPOS subroutine MTP returns the tool storage
    // axis to where it was; the PLC controls the turret, so the NC outputs the T word of the
    // interruption again. MRY waits for the tool storage axis, which the acknowledgement of
    // that T word already does.
    // An NC-controlled tool storage axis the NC traverses back itself, and MRY waits for it.
    if (repos_.run() && repos_.interruption() && (mtp || waits)) {
      if (mtp && ToolStorageNc()) {
        if (!ReturnToolStorage()) return false;
      } else if (mtp) {
        work_.block.aux.push_back({'T', 0, static_cast<double>(repos_.interruption()->modal.tool)});
      } else {
        mry = true;
      }
      continue;
    }
    if (ToolStorageNc() && (waits || (mtp && tool_storage_.StationOf(1)))) {
      // In the program an NC-controlled one traverses asynchronously (4.2, "As in NC-program
      // controlled mode"): MRY waits for its traverse as in the REPOS subroutine, and MTP
      // ("Adjust tool turret", 8.3) brings the active tool's station back to the work, after
      // a jog in manual mode, say. A PLC-controlled one: the PLC's business, as before.
      if (mtp && !IndexToolStorage(work_.block.modal.tool, program, work_.block.block))
        return false;
      if (waits) mry = true;
      continue;
    }
    if (nc::IsMeasuringCall(st.instruction)) continue;  // StartMeasuring
    Fail(nc::Format({st.pos, "instruction " + program.symbols.Name(st.name) +
                                 " is not supported by vmt (docs/conformance.md)"},
                    program.files),
         kMsgNotAvailable);
    return false;
  }
  return true;
}

bool Channel::BlockOffsets(const nc::Program& program) {
  const std::vector<double> before = frames_.translation;
  if (!UpdateTranslation(work_.block.modal, program, work_.block.block)) return false;
  if (work_.block.set_position) {
    // G92: the programmed values become the current position of those axes (a shift that
    // stays until Control-Reset).
    for (size_t a = 0; a < out_.commanded.size(); ++a)
      if (work_.block.programmed >> a & 1) {
        frames_.shift[a] += out_.commanded[a] - (work_.block.target[a] + frames_.translation[a]);
        frames_.translation[a] = out_.commanded[a] - work_.block.target[a];
        if (headstock_ && static_cast<int>(a) == config_.rotary_axis)
          headstock_.set_rotary_translation(frames_.translation[a]);
      }
  }
  const bool arc =
      work_.block.motion == nc::Motion::kArcCw || work_.block.motion == nc::Motion::kArcCcw;
  if (arc && frames_.translation != before) {
    Fail(program, work_.block.block,
         "zero offset or tool correction changes in an arc block: program it in a straight block",
         kMsgTranslationInArc);
    return false;
  }
  return true;
}

bool Channel::BlockSpindles(const nc::Program& program) {
  // M3/M4 with S (rpm), M5, M19 (orient to 0 deg); a start is checked by PathGuard.
  DriveSetpoint spindle = sp_.command;
  const bool orient = MainSpindleFunctions(work_.block, config_.spindle_drive, spindle);
  if (!GuardSpindleStart("spindle start", spindle)) return false;
  // Sj= / Mj= of the further spindles (G77 Sj=0 restores them instead, StartReposMotion).
  if (!work_.block.repos) {
    const std::string error = further_.TakeWords(program, work_.block);
    if (!error.empty()) {
      Fail(error, kMsgNotAvailable);
      return false;
    }
  }
  sp_.command = spindle;
  if (orient) sp_.referencing = sp_.orienting = true;
  return true;
}

}  // namespace vmt::control::channel
