#include "control/channel/block_feed.hpp"

#include <algorithm>
#include <cmath>

#include "control/channel/channel_messages.hpp"

namespace vmt::control::channel {

void BlockFeed::Drop() {
  peeked_.clear();
  unpushed_.reset();
  source_returned_false_ = false;
  compensating_ = false;
  source_done_ = false;
  trc_.Reset();
  ahead_.clear();
  ready_.clear();
}

BlockFeed::Early BlockFeed::TakeEarly(nc::PreparedBlock& b) {
  // Blocks the look-ahead has read, a block it read but could not take (its error comes now),
  // or the end it met.
  if (!peeked_.empty()) {
    b = std::move(peeked_.front());
    peeked_.pop_front();
    return Early::kTaken;
  }
  if (unpushed_) {
    b = *unpushed_;
    unpushed_.reset();
    return Early::kTaken;
  }
  return source_returned_false_ ? Early::kEnded : Early::kNone;
}

bool BlockFeed::StartCompensation(const FeedContext& ctx, const std::vector<double>& position,
                                  const std::vector<double>& translation,
                                  const nc::PreparedBlock& first) {
  if (ctx.axis_z < 0 || ctx.axis_x < 0) {
    error_ = {first.program, first.block,
              "tool nose radius compensation G41/G42 needs the axes Z and X", kMsgNotAvailable};
    return false;
  }
  const auto z = static_cast<size_t>(ctx.axis_z), x = static_cast<size_t>(ctx.axis_x);
  compensating_ = true;
  source_done_ = false;
  trc_.Reset();
  ahead_.clear();
  ready_.clear();
  first_tag_ = next_tag_ = 0;
  last_run_tag_ = -1;
  contour_point_ = {position[z] - translation[z], position[x] - translation[x]};
  if (auto e = Push(ctx, first)) {
    error_ = std::move(*e);
    return false;
  }
  return true;
}

std::optional<BlockError> BlockFeed::Push(const FeedContext& ctx, const nc::PreparedBlock& b) {
  const auto fail = [&](std::string text, int number) {
    return BlockError{b.program, b.block, std::move(text), number};
  };
  if (b.homing || b.set_position || b.repos || b.measuring)
    return fail(
        "G74, G77, G92 and G100 are not allowed while tool nose radius compensation "
        "(G41/G42) is active: cancel it with G40 first",
        kMsgNotAvailable);
  ContourElement e;
  e.tag = next_tag_;
  e.start = contour_point_;
  e.end = e.start;
  e.rapid = b.motion == nc::Motion::kRapid;
  e.side = b.modal.compensation == nc::Compensation::kLeft    ? CompensationSide::kLeft
           : b.modal.compensation == nc::Compensation::kRight ? CompensationSide::kRight
                                                              : CompensationSide::kOff;
  if (e.side != CompensationSide::kOff) {
    const axes::ToolEdge* edge = ctx.tools.Edge(b.modal.tool, b.modal.correction);
    if (!edge && b.modal.correction != 0)
      return fail("T" + std::to_string(b.modal.tool) + " D" + std::to_string(b.modal.correction) +
                      " is not in the tool list (G" +
                      std::to_string(nc::GCode(b.modal.compensation)) + ")",
                  kMsgToolNotInList);
    e.nose_radius_mm = edge ? edge->nose_radius : 0;
    e.edge_position = edge ? edge->edge_position : 0;
  }
  if (b.motion != nc::Motion::kNone) {
    if (b.modal.plane != nc::Plane::kZX)
      return fail("tool nose radius compensation G41/G42 works in the plane G18", kMsgNotAvailable);
    e.end = {b.target[ctx.axis_z], b.target[ctx.axis_x]};
    if (b.motion == nc::Motion::kArcCw || b.motion == nc::Motion::kArcCcw) {
      e.kind = b.motion == nc::Motion::kArcCw ? ElementKind::kArcCw : ElementKind::kArcCcw;
      if (b.has_centre) {
        e.centre = {e.start.z + b.centre[2], e.start.x + b.centre[0]};
      } else if (b.radius != 0) {
        // Centre from R, as the interpolation computes it (R < 0: the arc over 180 degrees).
        const double dz = e.end.z - e.start.z, dx = e.end.x - e.start.x;
        const double chord = std::hypot(dz, dx), r = std::abs(b.radius);
        if (chord < 1e-12 || chord > 2 * r + kArcTolerance)
          return fail("radius R too small for the end point", kMsgArcGeometry);
        const double h = std::sqrt(std::max(0.0, r * r - chord * chord / 4));
        const double side = ((b.radius > 0) == (b.motion == nc::Motion::kArcCw)) ? -1 : 1;
        e.centre = {(e.start.z + e.end.z) / 2 - side * h * dx / chord,
                    (e.start.x + e.end.x) / 2 + side * h * dz / chord};
      } else {
        return fail("G02/G03 needs a centre (I/J/K) or a radius R", kMsgArcGeometry);
      }
    }
  }
  ++next_tag_;
  contour_point_ = e.end;
  ahead_.push_back(b);
  trc_.Push(e);
  return std::nullopt;
}

BlockFeed::Fill BlockFeed::FillPiece(const FeedContext& ctx, const ReadBlock& read) {
  ContourElement e;
  while (ready_.empty()) {
    while (trc_.Pop(e)) ready_.push_back(e);
    if (!ready_.empty()) break;
    if (const auto& err = trc_.error()) {
      const nc::PreparedBlock& b = ahead_[static_cast<size_t>(err->tag - first_tag_)];
      error_ = {b.program, b.block, err->message, kMsgGouge};
      return Fill::kFailed;
    }
    if (source_done_ || (!trc_.active() && !trc_.pending())) {
      // Everything read ahead is given out: back to block by block.
      compensating_ = false;
      ahead_.clear();
      return Fill::kDrained;
    }
    nc::PreparedBlock b;
    if (!read(b)) return Fill::kSourceEnded;
    if (auto err = Push(ctx, b)) {
      error_ = std::move(*err);
      return Fill::kFailed;
    }
    if (b.end) EndOfSource();
  }
  return Fill::kPiece;
}

void BlockFeed::EndOfSource() {
  source_done_ = true;
  trc_.Flush();
}

TakenPiece BlockFeed::TakePiece(const FeedContext& ctx, nc::PreparedBlock& block) {
  TakenPiece taken;
  taken.element = ready_.front();
  ready_.pop_front();
  const int64_t tag = taken.element.tag;
  while (first_tag_ < tag) ahead_.pop_front(), ++first_tag_;
  block = ElementBlock(ctx, taken.element, ahead_.front());
  taken.further = tag == last_run_tag_;
  last_run_tag_ = tag;
  return taken;
}

bool BlockFeed::Peek(size_t k, const ReadBlock& read) {
  // Reads on from the program until block k after the one in work is there.
  while (peeked_.size() <= k) {
    if (unpushed_ || source_returned_false_) return false;
    nc::PreparedBlock b;
    if (!read(b)) {
      source_returned_false_ = true;
      return false;
    }
    peeked_.push_back(std::move(b));
  }
  return true;
}

void BlockFeed::FillCompensated(const FeedContext& ctx, const ReadBlock& read, size_t elements) {
  // Reads ahead under G41/G42 until the compensation has `elements` final pieces. A block that
  // cannot be taken waits (unpushed_): its error comes when the channel reaches it.
  ContourElement e;
  for (size_t reads = 0; reads < elements + 4 && ready_.size() < elements; ++reads) {
    if (source_done_ || trc_.error() || (!trc_.active() && !trc_.pending()) || unpushed_ ||
        source_returned_false_)
      return;
    nc::PreparedBlock b;
    if (!peeked_.empty()) {
      b = std::move(peeked_.front());
      peeked_.pop_front();
    } else if (!read(b)) {
      source_returned_false_ = true;
      return;
    }
    if (Push(ctx, b)) {
      unpushed_ = b;
      return;
    }
    if (b.end) EndOfSource();
    while (trc_.Pop(e)) ready_.push_back(e);
  }
}

bool BlockFeed::PeekCompensated(const FeedContext& ctx, const ReadBlock& read, size_t k,
                                nc::PreparedBlock& out) {
  // Piece k after the one in work of the tip path, as a block of its own.
  FillCompensated(ctx, read, k + 1);
  if (ready_.size() <= k) return false;
  const ContourElement& e = ready_[k];
  const auto index = static_cast<size_t>(e.tag - first_tag_);
  if (e.tag < first_tag_ || index >= ahead_.size()) return false;
  out = ElementBlock(ctx, e, ahead_[index]);
  if (e.tag == (k == 0 ? last_run_tag_ : ready_[k - 1].tag)) {
    // A further piece of a block already started: its functions have run already.
    out.aux.clear(), out.events.clear(), out.instructions.clear();
    out.dwell_s = 0;
  }
  out.modal.compensation = nc::Compensation::kOff;  // the tip path itself is not offset again
  return true;
}

nc::PreparedBlock BlockFeed::ElementBlock(const FeedContext& ctx, const ContourElement& e,
                                          nc::PreparedBlock b) {
  // The block runs the tip path the compensation made of it: lines and arcs in Z/X.
  b.target[ctx.axis_z] = e.end.z;
  b.target[ctx.axis_x] = e.end.x;
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

bool BlockFeed::PlanAhead(const FeedContext& ctx, const ReadBlock& read,
                          const nc::PreparedBlock& block, const BlockMotion& motion,
                          const LookAheadView& view, std::vector<SpeedTarget>& targets) {
  targets.clear();
  const auto feed_move = [](nc::Motion m) {
    return m == nc::Motion::kLinear || m == nc::Motion::kArcCw || m == nc::Motion::kArcCcw;
  };
  const double speed = motion.max_rate * motion.length;
  const double accel = motion.max_accel * motion.length;
  legs_.clear();
  std::vector<double> direction = motion.Direction(1);
  std::vector<double> from = motion.end;
  double reach = 0, top_speed = speed, least_accel = accel, least_jerk = HUGE_VAL;
  nc::PreparedBlock next;
  BlockMotion m;
  for (size_t k = 0; k < kLookAheadBlocks; ++k) {
    if (compensating_ ? !PeekCompensated(ctx, read, k, next) : !Peek(k, read)) break;
    const nc::PreparedBlock& n = compensating_ ? next : peeked_[k];
    const nc::ModalState &m0 = block.modal, &m1 = n.modal;
    if (!feed_move(n.motion) || !n.aux.empty() || !n.events.empty() || !n.instructions.empty() ||
        n.dwell_s != 0 || n.homing || n.set_position || n.repos || n.measuring || n.end ||
        n.returned || m1.compensation != nc::Compensation::kOff ||
        m1.zero_offset != m0.zero_offset || m1.tool_length != m0.tool_length ||
        m1.tool != m0.tool || m1.correction != m0.correction)
      break;
    if (view.at_rest_before(n)) break;
    bool homed = true;
    for (size_t a = 0; a < view.homed.size(); ++a)
      if (!view.homed[a] && (n.programmed >> a & 1)) homed = false;
    // A block that moves nothing, or cannot be planned (its error comes in its turn), ends the
    // path known.
    if (!homed ||
        PlanBlockMotion(n, from, view.translation, view.axes, view.spindle_rev_per_s, m,
                        view.follow_up(n))
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
    leg.max_speed = std::min(m.max_rate * m.length, m.length / view.cycle_s);
    leg.accel = m.max_accel * m.length;
    leg.jerk = m.max_jerk * m.length;
    leg.length = m.length;
    leg.cos_turn = std::clamp(dot / std::sqrt(n1 * n2), -1.0, 1.0);
    legs_.push_back(leg);
    direction = m.Direction(1);
    from = m.end;
    // Enough known once the path so far could stop from the fastest speed in it.
    reach += m.length;
    top_speed = std::max(top_speed, leg.max_speed);
    least_accel = std::min(least_accel, leg.accel);
    if (leg.jerk > 0) least_jerk = std::min(least_jerk, leg.jerk);
    if (reach >= BrakingDistance(top_speed, 0, least_accel,
                                 std::isfinite(least_jerk) ? least_jerk : 0, view.cycle_s))
      break;
  }
  if (legs_.empty()) return false;
  PlanTargets(motion.length, speed, accel, motion.max_jerk * motion.length, legs_, targets);
  const bool at_speed = std::min(targets[0].corner, targets[0].feed) > 1e-9;
  if (!at_speed) targets.clear();
  return at_speed;
}

}  // namespace vmt::control::channel
