// Block preparation of the channel: blocks come from the interpreter, or, under G41/G42, from
// the tool nose radius compensation, which reads ahead until each piece of the tip path is
// final; the look-ahead reads on to choose the speed at which the block in work may end.
#include <cmath>

#include "control/channel/channel.hpp"
#include "control/channel/look_ahead.hpp"

namespace vmt::control::channel {

bool Channel::NextBlock(const AmplifierTelegram& at) {
  // The REPOS subroutine has returned (or there is none): close in and continue the program.
  if (repos_.run() && (repos_.finish() || repos_.closing() || work_.block.returned))
    return FinishReposRun(at);
  if (work_.feed.compensating()) return NextCompensated(at);
  const bool read = ReadNext(work_.block);
  if (!read) {
    if (work_.interpreter->error())
      Fail(nc::Format(*work_.interpreter->error(), {work_.interpreter->ErrorFile()}),
           kMsgProgramError);
    else
      state_ = ChannelState::kEnded, reversing_ = false;
    return false;
  }
  if (work_.block.modal.compensation != nc::Compensation::kOff &&
      work_.block.motion != nc::Motion::kNone) {
    if (!StartCompensation(out_.commanded)) return false;
    return NextCompensated(at);
  }
  inserted_piece_ = false;
  return RunBlock(at);
}

FeedContext Channel::FeedContextNow() const { return {tools_, axis_z_, axis_x_}; }

void Channel::FailAt(const BlockError& e) {
  Fail(*ProgramOf(e.program), e.block, e.text, e.number);
}

bool Channel::StartCompensation(const std::vector<double>& position) {
  if (work_.feed.StartCompensation(FeedContextNow(), position, frames_.translation, work_.block))
    return true;
  FailAt(work_.feed.error());
  return false;
}

Channel::Compensated Channel::FillReadyPiece(bool searching) {
  const ReadBlock read = [this, searching](nc::PreparedBlock& b) {
    return searching ? ReadSource(b) : ReadNext(b);
  };
  for (;;) {
    switch (work_.feed.FillPiece(FeedContextNow(), read)) {
      case BlockFeed::Fill::kPiece:
        return Compensated::kPiece;
      case BlockFeed::Fill::kDrained:
        return Compensated::kDrained;
      case BlockFeed::Fill::kFailed:
        FailAt(work_.feed.error());
        return Compensated::kFailed;
      case BlockFeed::Fill::kSourceEnded:
        if (work_.interpreter->error()) {
          Fail(nc::Format(*work_.interpreter->error(), {work_.interpreter->ErrorFile()}),
               kMsgProgramError);
          return Compensated::kFailed;
        }
        work_.feed.EndOfSource();
        break;
    }
  }
}

bool Channel::NextCompensated(const AmplifierTelegram& at) {
  switch (FillReadyPiece(false)) {
    case Compensated::kFailed:
      return false;
    case Compensated::kDrained:
      if (work_.feed.source_done()) {
        state_ = ChannelState::kEnded, reversing_ = false;
        return false;
      }
      return NextBlock(at);
    case Compensated::kPiece:
      break;
  }
  const TakenPiece piece = work_.feed.TakePiece(FeedContextNow(), work_.block);
  inserted_piece_ = piece.element.inserted;
  return piece.further ? StartMotion(at) : RunBlock(at);
}

bool Channel::ReadNext(nc::PreparedBlock& b) {
  switch (work_.feed.TakeEarly(b)) {
    case BlockFeed::Early::kTaken:
      break;
    case BlockFeed::Early::kEnded:
      return false;
    case BlockFeed::Early::kNone:
      if (headstock_) work_.rotary_next_start = work_.interpreter->position()[config_.rotary_axis];
      if (!ReadSource(b)) return false;
      break;
  }
  // Blocks leave here in the interpreter's order: each starts, for the interpreter, where the
  // one before ended (an increment of the rotary axis adds to this; see RebaseRotaryAxis).
  if (headstock_) {
    work_.rotary_start = work_.rotary_next_start;
    work_.rotary_next_start = b.target[config_.rotary_axis];
  }
  return true;
}

bool Channel::ReadSource(nc::PreparedBlock& b) {
  if (search_.active() && search_.run().end_reached) return false;
  // BES/BEC and TLD/OTD/MTD reach this channel through what is handed in here, not through
  // anything the interpreter keeps: a copy of the channel runs its copy of the interpreter.
  const std::function<bool(int)> events = [this](int n) {
    if (events_.source) return events_.source(n);
    auto it = events_.own.find(n);
    return it != events_.own.end() && it->second;
  };
  if (!work_.interpreter->Next(b, events, MakeDataAccess())) return false;
  // Block search type 1 (3.1): machining ends at the end position, before its block runs.
  // Tested where the blocks leave the interpreter, in their order and each once (the pass
  // count), so that it holds whatever path the channel makes of them afterwards: block by
  // block, blended by the look-ahead, or offset by G41/G42, whose read-ahead then meets the
  // end as it meets the text's end (the tip path closes there).
  if (search_.active() && !mdi_.running &&
      search_.run().matcher.EndMatches(b, *ProgramOf(b.program), b.program)) {
    search_.run().end_reached = true;
    return false;
  }
  return true;
}

void Channel::RebaseRotaryAxis() {
  // C-axis manual 1.2: block preparation waits until the changeover ends. The block that asked
  // for rotary axis mode was prepared before, from where the program last put the rotary axis;
  // the spindle has turned since. Rotary axis mode starts where it stands (in program
  // coordinates, with the rotary axis' zero offsets back, 2.3), so an increment counts from
  // here, and the interpreter prepares the next blocks from the block's corrected end. Under
  // G41/G42 the blocks ahead are already prepared: they keep the program's values.
  if (work_.feed.compensating() || work_.feed.read_early() || work_.block.homing) return;
  const size_t r = static_cast<size_t>(config_.rotary_axis);
  const double actual = out_.commanded[r] - frames_.translation[r];
  if (work_.block.modal.incremental && (work_.block.programmed >> r & 1))
    work_.block.target[r] += actual - work_.rotary_start;
  work_.interpreter->SetAxisPosition(r, work_.block.target[r]);
  work_.rotary_next_start = work_.block.target[r];
}

void Channel::LookAhead(const AmplifierTelegram& at) {
  // Blending between feed moves: read the blocks after this one while they continue the path
  // (feed moves with nothing to wait for, in the same frame); their corners and feeds become
  // the speed targets the profile brakes for (look_ahead.hpp), the last one at rest.
  const auto feed_move = [](nc::Motion m) {
    return m == nc::Motion::kLinear || m == nc::Motion::kArcCw || m == nc::Motion::kArcCcw;
  };
  work_.continuation_ready = false;
  work_.targets.clear();
  // The blocks of approach moves start at rest: PathGuard may refuse each before it moves.
  // A block with M00 / M01 ends at rest: the stop is decided at its end.
  if (single_block_ || programmed_stop_.pending != ProgrammedStop::Kind::kNone ||
      state_ != ChannelState::kRunning || !feed_move(work_.block.motion) || work_.block.end ||
      work_.homing || !work_.motion.moves || repos_.run() || config_.approach_program ||
      cax_.command)  // tracking sets each block's C as it starts: the look-ahead cannot know it
    return;
  const LookAheadView view{config_.axes,
                           frames_.translation,
                           frames_.homed,
                           SpindleRevPerS(at),
                           config_.tick_s * config_.ticks_per_cycle,
                           [this](const nc::PreparedBlock& n) {
                             // A block that needs a spindle / rotary axis changeover is reached at
                             // rest.
                             return headstock_ && ModeNeeded(n) != axes::HeadstockMode::kNone &&
                                    ModeNeeded(n) != headstock_->mode();
                           },
                           [this](const nc::PreparedBlock& n) { return FollowUpAxes(n); }};
  const ReadBlock read = [this](nc::PreparedBlock& b) { return ReadSource(b); };
  work_.continuation_ready =
      work_.feed.PlanAhead(FeedContextNow(), read, work_.block, work_.motion, view, work_.targets);
}
}  // namespace vmt::control::channel
