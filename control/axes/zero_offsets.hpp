#pragma once
// Settable zero offsets G54..G59: per table a shift per channel axis. G53 selects none. The
// shift is added to the programmed position: machine = program + offset.

#include <array>
#include <vector>

namespace vmt::control::axes {

struct ZeroOffsetTable {
  std::array<std::vector<double>, 6> g54_to_g59;  ///< [G - 54][channel axis], mm | deg

  /// Shift of `axis` under G`g` (53..59); 0 for G53 and unset entries.
  double Offset(int g, size_t axis) const {
    if (g < 54 || g > 59) return 0;
    const std::vector<double>& t = g54_to_g59[g - 54];
    return axis < t.size() ? t[axis] : 0;
  }
};

}  // namespace vmt::control::axes
