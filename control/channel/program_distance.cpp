#include "control/channel/program_distance.hpp"

#include <algorithm>
#include <utility>

namespace vmt::control::channel {
namespace {

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

}  // namespace

void ProgramDistance::Restart() { *this = ProgramDistance{}; }

void ProgramDistance::BlockStarts(BlockMotion& motion,
                                  const std::vector<axes::AxisParameters>& axes) {
  block_start_ = distance_;
  block_length_ = LengthOf(motion, axes);
  distance_ += block_length_;
  rest_.reset();
  Cut(motion, 0);
}

double ProgramDistance::ContinueInBlock(double start, double length, double u,
                                        BlockMotion& motion) {
  block_start_ = start;
  block_length_ = length;
  distance_ = start + block_length_;
  if (u >= 1) return u;
  rest_.reset();
  Cut(motion, u);
  // The profile of a cut block runs over its first part only: u measured on that part.
  if (rest_) return cut_u_ > 1e-12 ? u / cut_u_ : 1;
  return u;
}

void ProgramDistance::Cut(BlockMotion& motion, double from_u) {
  // 3.5: the breakpoint stops the first time the path reaches it going forward.
  if (breakpoint_ <= 0 || block_length_ <= 0 || breakpoint_ > distance_ + 1e-9 ||
      breakpoint_ < block_start_ + from_u * block_length_ - 1e-9)
    return;
  const double u = std::clamp((breakpoint_ - block_start_) / block_length_, from_u, 1.0);
  breakpoint_ = 0;
  pending_ = true;
  cut_u_ = u;
  if (u < 1 - 1e-12) {
    rest_ = motion;
    motion = Truncated(motion, u);
  }
}

void ProgramDistance::Hold() {
  pending_ = false;
  holding_ = true;
}

std::optional<BlockMotion> ProgramDistance::Resume(double& u) {
  holding_ = false;
  u = cut_u_;
  cut_u_ = 0;
  std::optional<BlockMotion> rest = std::move(rest_);
  rest_.reset();
  return rest;
}

void ProgramDistance::Drop() {
  rest_.reset();
  holding_ = pending_ = false;
}

}  // namespace vmt::control::channel
