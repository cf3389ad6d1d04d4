#pragma once
// The path the program's blocks took, kept for backward travel (block search manual 4.3,
// "Rückwärtsfahren"): the motions of the last blocks in axis space, the oldest forgotten first.
// Block search records the blocks it decodes too, so that after it the NC can travel the
// programmed path backwards from the continue position although the axes never went along it.
// Plain geometry: what each block's motion was, and pieces of it in either direction.

#include <cstddef>
#include <vector>

#include "control/channel/block_motion.hpp"

namespace vmt::control::channel {

/// One block's motion as it ran, or as block search decoded it (`decoded`: the axes never went
/// along it). `rapid`: a G00 move.
struct PathStep {
  BlockMotion motion;
  bool rapid = false;
  bool decoded = false;
};

/// A ring of the last kPathMemoryBlocks steps: recording reuses the steps' storage, so block
/// search through a long program does not allocate per block.
class PathMemory {
 public:
  /// Blocks the NC can travel back. The manual leaves the number to the machine data; vmt keeps
  /// the last thousand, far more than an operator steps back through by hand.
  static constexpr size_t kBlocks = 1000;

  void Push(const BlockMotion& motion, bool rapid, bool decoded);
  void Clear() { count_ = 0, head_ = 0; }
  size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  /// 0 is the oldest step kept, size() - 1 the last.
  const PathStep& operator[](size_t i) const { return ring_[(head_ + i) % ring_.size()]; }
  PathStep& back() { return ring_[(head_ + count_ - 1) % ring_.size()]; }

 private:
  std::vector<PathStep> ring_;
  size_t head_ = 0, count_ = 0;
};

/// Whether backward travel can take `m` again: G31's face lines and arcs are curves of X and C
/// the piece below does not cut out (vmt leaves them to the REPOS functions).
bool Retraceable(const BlockMotion& m);

/// The piece of `m` from u0 to u1 (0..1 each; u1 < u0 runs it backwards) as a motion of its
/// own: u' = 0..1 follows m from m's u0 to u1 with m's limits along the path.
BlockMotion PieceOf(const BlockMotion& m, double u0, double u1);

}  // namespace vmt::control::channel
