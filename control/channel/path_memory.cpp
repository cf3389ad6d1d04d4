#include "control/channel/path_memory.hpp"

#include <cmath>

namespace vmt::control::channel {

void PathMemory::Push(const BlockMotion& motion, bool rapid, bool decoded) {
  // A free slot of the ring (after Clear, the storage of steps forgotten) is reused first;
  // the ring grows only while every slot holds a step; full, the oldest step gives way.
  PathStep* slot;
  if (count_ < ring_.size()) {
    slot = &ring_[(head_ + count_) % ring_.size()];
    ++count_;
  } else if (ring_.size() < kBlocks) {
    slot = &ring_.emplace_back();  // head_ is 0 until the ring is full
    ++count_;
  } else {
    slot = &ring_[head_];
    head_ = (head_ + 1) % kBlocks;
  }
  slot->motion = motion;  // the vectors keep their storage
  slot->rapid = rapid;
  slot->decoded = decoded;
}

bool Retraceable(const BlockMotion& m) { return m.face_axes[0] < 0; }

BlockMotion PieceOf(const BlockMotion& m, double u0, double u1) {
  BlockMotion p = m;
  m.PointAt(u0, p.start);
  m.PointAt(u1, p.end);
  // A line's points, an arc's angle and a helix' other axes are all linear in u: a linear
  // change of parameter keeps the path and scales its limits.
  const double f = u1 - u0;
  const double span = std::abs(f);
  if (p.arc_axes[0] >= 0) {
    p.arc_start_angle = m.arc_start_angle + m.arc_sweep * u0;
    p.arc_sweep = m.arc_sweep * f;
  }
  if (span < 1e-12) {
    p.moves = false;
    return p;
  }
  p.length = m.length * span;
  p.max_rate = m.max_rate / span;
  p.max_accel = m.max_accel / span;
  p.max_jerk = m.max_jerk / span;
  return p;
}

}  // namespace vmt::control::channel
