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
  if (work_.compensating) return NextCompensated(at);
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

bool Channel::StartCompensation(const std::vector<double>& position) {
  if (axis_z_ < 0 || axis_x_ < 0) {
    Fail(*ProgramOf(work_.block.program), work_.block.block,
         "tool nose radius compensation G41/G42 needs the axes Z and X", kMsgNotAvailable);
    return false;
  }
  work_.compensating = true;
  work_.source_done = false;
  work_.trc.Reset();
  work_.ahead.clear();
  work_.ready.clear();
  work_.first_tag = work_.next_tag = 0;
  work_.last_run_tag = -1;
  work_.contour_point = {position[axis_z_] - frames_.translation[axis_z_],
                         position[axis_x_] - frames_.translation[axis_x_]};
  return PushAhead(work_.block);
}

bool Channel::PushAhead(const nc::PreparedBlock& b) {
  const nc::Program& program = *ProgramOf(b.program);
  if (b.homing || b.set_position || b.repos || b.measuring) {
    Fail(program, b.block,
         "G74, G77, G92 and G100 are not allowed while tool nose radius compensation "
         "(G41/G42) is active: cancel it with G40 first",
         kMsgNotAvailable);
    return false;
  }
  ContourElement e;
  e.tag = work_.next_tag;
  e.start = work_.contour_point;
  e.end = e.start;
  e.rapid = b.motion == nc::Motion::kRapid;
  e.side = b.modal.compensation == nc::Compensation::kLeft    ? CompensationSide::kLeft
           : b.modal.compensation == nc::Compensation::kRight ? CompensationSide::kRight
                                                              : CompensationSide::kOff;
  if (e.side != CompensationSide::kOff) {
    const auto edge = config_.tools.Find(b.modal.tool, b.modal.correction);
    if (!edge && b.modal.correction != 0) {
      Fail(program, b.block,
           "T" + std::to_string(b.modal.tool) + " D" + std::to_string(b.modal.correction) +
               " is not in the tool list (G" + std::to_string(nc::GCode(b.modal.compensation)) + ")",
           kMsgToolNotInList);
      return false;
    }
    e.nose_radius_mm = edge ? edge->nose_radius : 0;
    e.edge_position = edge ? edge->edge_position : 0;
  }
  if (b.motion != nc::Motion::kNone) {
    if (b.modal.plane != nc::Plane::kZX) {
      Fail(program, b.block, "tool nose radius compensation G41/G42 works in the plane G18",
           kMsgNotAvailable);
      return false;
    }
    e.end = {b.target[axis_z_], b.target[axis_x_]};
    if (b.motion == nc::Motion::kArcCw || b.motion == nc::Motion::kArcCcw) {
      e.kind = b.motion == nc::Motion::kArcCw ? ElementKind::kArcCw : ElementKind::kArcCcw;
      if (b.has_centre) {
        e.centre = {e.start.z + b.centre[2], e.start.x + b.centre[0]};
      } else if (b.radius != 0) {
        // Centre from R, as the interpolation computes it (R < 0: the arc over 180 degrees).
        const double dz = e.end.z - e.start.z, dx = e.end.x - e.start.x;
        const double chord = std::hypot(dz, dx), r = std::abs(b.radius);
        if (chord < 1e-12 || chord > 2 * r + kArcTolerance) {
          Fail(program, b.block, "radius R too small for the end point", kMsgArcGeometry);
          return false;
        }
        const double h = std::sqrt(std::max(0.0, r * r - chord * chord / 4));
        const double side = ((b.radius > 0) == (b.motion == nc::Motion::kArcCw)) ? -1 : 1;
        e.centre = {(e.start.z + e.end.z) / 2 - side * h * dx / chord,
                    (e.start.x + e.end.x) / 2 + side * h * dz / chord};
      } else {
        Fail(program, b.block, "G02/G03 needs a centre (I/J/K) or a radius R", kMsgArcGeometry);
        return false;
      }
    }
  }
  ++work_.next_tag;
  work_.contour_point = e.end;
  work_.ahead.push_back(b);
  work_.trc.Push(e);
  return true;
}

Channel::Compensated Channel::FillReadyPiece(bool searching) {
  ContourElement e;
  while (work_.ready.empty()) {
    while (work_.trc.Pop(e)) work_.ready.push_back(e);
    if (!work_.ready.empty()) break;
    if (const auto& err = work_.trc.error()) {
      const nc::PreparedBlock& b = work_.ahead[static_cast<size_t>(err->tag - work_.first_tag)];
      Fail(*ProgramOf(b.program), b.block, err->message, kMsgGouge);
      return Compensated::kFailed;
    }
    if (work_.source_done || (!work_.trc.active() && !work_.trc.pending())) {
      // Everything read ahead is given out: back to block by block.
      work_.compensating = false;
      work_.ahead.clear();
      return Compensated::kDrained;
    }
    nc::PreparedBlock b;
    if (!(searching ? ReadSource(b) : ReadNext(b))) {
      if (work_.interpreter->error()) {
        Fail(nc::Format(*work_.interpreter->error(), {work_.interpreter->ErrorFile()}),
             kMsgProgramError);
        return Compensated::kFailed;
      }
      work_.source_done = true;
      work_.trc.Flush();
      continue;
    }
    if (!PushAhead(b)) return Compensated::kFailed;
    if (b.end) work_.source_done = true, work_.trc.Flush();
  }
  return Compensated::kPiece;
}

ContourElement Channel::TakeReadyPiece() {
  const ContourElement e = work_.ready.front();
  work_.ready.pop_front();
  while (work_.first_tag < e.tag) work_.ahead.pop_front(), ++work_.first_tag;
  work_.block = ElementBlock(e, work_.ahead.front());
  return e;
}

bool Channel::NextCompensated(const AmplifierTelegram& at) {
  switch (FillReadyPiece(false)) {
    case Compensated::kFailed:
      return false;
    case Compensated::kDrained:
      if (work_.source_done) {
        state_ = ChannelState::kEnded, reversing_ = false;
        return false;
      }
      return NextBlock(at);
    case Compensated::kPiece:
      break;
  }
  const ContourElement e = TakeReadyPiece();
  inserted_piece_ = e.inserted;
  if (e.tag != work_.last_run_tag) {
    work_.last_run_tag = e.tag;
    return RunBlock(at);
  }
  return StartMotion(at);
}

bool Channel::ReadNext(nc::PreparedBlock& b) {
  // Blocks the look-ahead has read, a block it read but could not take (its error comes now),
  // or the end it met.
  if (!work_.peeked.empty()) {
    b = std::move(work_.peeked.front());
    work_.peeked.pop_front();
  } else if (work_.unpushed) {
    b = *work_.unpushed;
    work_.unpushed.reset();
  } else {
    if (work_.source_returned_false) return false;
    if (headstock_) work_.rotary_next_start = work_.interpreter->position()[config_.rotary_axis];
    if (!ReadSource(b)) return false;
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
  if (search_ && search_->end_reached) return false;
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
  if (search_ && !mdi_.running &&
      search_->matcher.EndMatches(b, *ProgramOf(b.program), b.program)) {
    search_->end_reached = true;
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
  if (work_.compensating || !work_.peeked.empty() || work_.block.homing) return;
  const size_t r = static_cast<size_t>(config_.rotary_axis);
  const double actual = out_.commanded[r] - frames_.translation[r];
  if (work_.block.modal.incremental && (work_.block.programmed >> r & 1))
    work_.block.target[r] += actual - work_.rotary_start;
  work_.interpreter->SetAxisPosition(r, work_.block.target[r]);
  work_.rotary_next_start = work_.block.target[r];
}

bool Channel::Peek(size_t k) {
  // Reads on from the interpreter until block k after the one in work is there.
  while (work_.peeked.size() <= k) {
    if (work_.unpushed || work_.source_returned_false) return false;
    nc::PreparedBlock b;
    if (!ReadSource(b)) {
      work_.source_returned_false = true;
      return false;
    }
    work_.peeked.push_back(std::move(b));
  }
  return true;
}

void Channel::FillCompensated(size_t elements) {
  // Reads ahead under G41/G42 until the compensation has `elements` final pieces; errors are
  // left for NextCompensated to report when the channel gets there.
  ContourElement e;
  for (size_t reads = 0; reads < elements + 4 && work_.ready.size() < elements; ++reads) {
    if (work_.source_done || work_.trc.error() || (!work_.trc.active() && !work_.trc.pending()) ||
        work_.unpushed || work_.source_returned_false)
      return;
    nc::PreparedBlock b;
    if (!work_.peeked.empty()) {
      b = std::move(work_.peeked.front());
      work_.peeked.pop_front();
    } else if (!ReadSource(b)) {
      work_.source_returned_false = true;
      return;
    }
    look_.planning_only = true;
    look_.plan_failed = false;
    const bool pushed = PushAhead(b) && !look_.plan_failed;
    look_.planning_only = false;
    if (!pushed) {
      work_.unpushed = b;
      return;
    }
    if (b.end) work_.source_done = true, work_.trc.Flush();
    while (work_.trc.Pop(e)) work_.ready.push_back(e);
  }
}

bool Channel::PeekCompensated(size_t k, nc::PreparedBlock& out) {
  // Piece k after the one in work of the tip path, as a block of its own.
  FillCompensated(k + 1);
  if (work_.ready.size() <= k) return false;
  const ContourElement& e = work_.ready[k];
  const auto index = static_cast<size_t>(e.tag - work_.first_tag);
  if (e.tag < work_.first_tag || index >= work_.ahead.size()) return false;
  out = ElementBlock(e, work_.ahead[index]);
  if (e.tag == (k == 0 ? work_.last_run_tag : work_.ready[k - 1].tag)) {
    // A further piece of a block already started: its functions have run already.
    out.aux.clear(), out.events.clear(), out.instructions.clear();
    out.dwell_s = 0;
  }
  out.modal.compensation = nc::Compensation::kOff;  // the tip path itself is not offset again
  return true;
}

nc::PreparedBlock Channel::ElementBlock(const ContourElement& e, nc::PreparedBlock b) const {
  // The block runs the tip path the compensation made of it: lines and arcs in Z/X.
  b.target[axis_z_] = e.end.z;
  b.target[axis_x_] = e.end.x;
  b.radius = 0;
  b.has_centre = false;
  if (e.kind != ElementKind::kLine) {
    b.motion = e.kind == ElementKind::kArcCw ? nc::Motion::kArcCw : nc::Motion::kArcCcw;
    b.centre[2] = e.centre.z - e.start.z;
    b.centre[0] = e.centre.x - e.start.x;
    b.has_centre = true;
  } else if (b.motion == nc::Motion::kArcCw || b.motion == nc::Motion::kArcCcw) {
    b.motion = nc::Motion::kLinear;  // an arc the compensation shrank to a point
  } else if (e.inserted && b.motion == nc::Motion::kNone) {
    b.motion = e.rapid ? nc::Motion::kRapid : nc::Motion::kLinear;
  }
  return b;
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
  const double cycle_s = config_.tick_s * config_.ticks_per_cycle;
  const double speed = work_.motion.max_rate * work_.motion.length;
  const double accel = work_.motion.max_accel * work_.motion.length;
  const double spindle_rev_per_s = SpindleRevPerS(at);
  look_.legs.clear();
  std::vector<double> direction = work_.motion.Direction(1);
  std::vector<double> from = work_.motion.end;
  double reach = 0, top_speed = speed, least_accel = accel, least_jerk = HUGE_VAL;
  nc::PreparedBlock next;
  BlockMotion m;
  for (size_t k = 0; k < kLookAheadBlocks; ++k) {
    if (work_.compensating ? !PeekCompensated(k, next) : !Peek(k)) break;
    const nc::PreparedBlock& n = work_.compensating ? next : work_.peeked[k];
    const nc::ModalState &m0 = work_.block.modal, &m1 = n.modal;
    if (!feed_move(n.motion) || !n.aux.empty() || !n.events.empty() || !n.instructions.empty() ||
        n.dwell_s != 0 || n.homing || n.set_position || n.repos || n.measuring || n.end ||
        n.returned || m1.compensation != nc::Compensation::kOff || m1.zero_offset != m0.zero_offset ||
        m1.tool_length != m0.tool_length || m1.tool != m0.tool || m1.correction != m0.correction)
      break;
    // A block that needs a spindle / rotary axis changeover is reached at rest.
    if (headstock_ && ModeNeeded(n) != axes::HeadstockMode::kNone &&
        ModeNeeded(n) != headstock_->mode())
      break;
    bool homed = true;
    for (size_t a = 0; a < frames_.homed.size(); ++a)
      if (!frames_.homed[a] && (n.programmed >> a & 1)) homed = false;
    // A block that moves nothing, or cannot be planned (its error comes in its turn), ends the
    // path known.
    if (!homed ||
        PlanBlockMotion(n, from, frames_.translation, config_.axes, spindle_rev_per_s, m,
                        FollowUpAxes(n))
            .has_value() ||
        !m.moves)
      break;
    const std::vector<double> d = m.Direction(0);
    double n1 = 0, n2 = 0, dot = 0;
    for (size_t a = 0; a < d.size(); ++a)
      n1 += direction[a] * direction[a], n2 += d[a] * d[a], dot += direction[a] * d[a];
    if (n1 <= 0 || n2 <= 0) break;
    LookAheadLeg leg;
    // A block takes at least one NC cycle, however short it is.
    leg.max_speed = std::min(m.max_rate * m.length, m.length / cycle_s);
    leg.accel = m.max_accel * m.length;
    leg.jerk = m.max_jerk * m.length;
    leg.length = m.length;
    leg.cos_turn = std::clamp(dot / std::sqrt(n1 * n2), -1.0, 1.0);
    look_.legs.push_back(leg);
    direction = m.Direction(1);
    from = m.end;
    // Enough known once the path so far could stop from the fastest speed in it.
    reach += m.length;
    top_speed = std::max(top_speed, leg.max_speed);
    least_accel = std::min(least_accel, leg.accel);
    if (leg.jerk > 0) least_jerk = std::min(least_jerk, leg.jerk);
    if (reach >= BrakingDistance(top_speed, 0, least_accel,
                                 std::isfinite(least_jerk) ? least_jerk : 0, cycle_s))
      break;
  }
  if (look_.legs.empty()) return;
  PlanTargets(work_.motion.length, speed, accel, work_.motion.max_jerk * work_.motion.length,
              look_.legs, work_.targets);
  work_.continuation_ready = std::min(work_.targets[0].corner, work_.targets[0].feed) > 1e-9;
  if (!work_.continuation_ready) work_.targets.clear();
}
}  // namespace vmt::control::channel
