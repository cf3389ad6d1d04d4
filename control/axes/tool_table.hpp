#pragma once
// The tool list: per tool (T) its cutting edges (D corrections) with the tool lengths along the
// channel axes, the nose radius and the cutting edge position. With G48 the channel moves the
// axes so that the cutting edge, not the tool carrier's reference point, follows the program:
// axis = program + zero offset - length (G49: + length).

#include <optional>
#include <string>
#include <vector>

namespace vmt::control::axes {

struct ToolEdge {
  int tool = 0;                ///< T
  int edge = 1;                ///< D
  std::vector<double> length;  ///< per channel axis, mm: the tip seen from the reference point
  double nose_radius = 0;      ///< mm, for G41/G42
  int edge_position = 0;       ///< cutting edge position 1..9 (0: nose centre)
};

struct ToolTable {
  std::vector<ToolEdge> edges;

  /// The edge of tool `t` with correction `d`; nullopt if the list has none.
  std::optional<ToolEdge> Find(int t, int d) const {
    for (const ToolEdge& e : edges)
      if (e.tool == t && e.edge == d) return e;
    return std::nullopt;
  }
};

}  // namespace vmt::control::axes
