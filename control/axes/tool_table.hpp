#pragma once
// The tool list: per tool (T) its cutting edges (D corrections) with the tool lengths along the
// channel axes, the nose radius and the cutting edge position. With G48 the channel moves the
// axes so that the cutting edge, not the tool carrier's reference point, follows the program:
// axis = program + zero offset - length (G49: + length). A length is the edge's geometry plus its
// wear register (fast-measurement manual 5.5, 5.6: the measured correction goes there, the
// geometry stays as set up).

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace vmt::control::axes {

/// The tool list's length registers L1, L2, L3 and the axes they lie along. The manual names the
/// registers, not their axes; its lathe program (fast measurement 5.6, steps 12 and 13) corrects
/// the Z face with wear L1 and the X diameter with wear L2, so L1 is Z and L2 is X; L3 along Y
/// continues the pattern (vmt's choice, as measure::WearElement). The plane (G17/G18/G19) does
/// not turn them: vmt's lathes work in G18 only. 0, 1, 2 for L1, L2, L3; -1 for other axes (C).
inline int LengthRegister(const std::string& axis_name) {
  if (axis_name.empty()) return -1;
  switch (axis_name[0]) {
    case 'Z':
      return 0;
    case 'X':
      return 1;
    case 'Y':
      return 2;
    default:
      return -1;
  }
}

struct ToolEdge {
  int tool = 0;                ///< T
  int edge = 1;                ///< D
  std::vector<double> length;  ///< per channel axis, mm: the tip seen from the reference point
  double nose_radius = 0;      ///< mm, for G41/G42
  int edge_position = 0;       ///< cutting edge position 1..9 (0: nose centre)
  /// Wear L1, L2, L3 (TLD elements 11, 12, 13), mm: added to the length along the register's
  /// axis (LengthRegister), G48 and G49 alike.
  std::array<double, 3> wear{};

  /// The length the channel applies along channel axis `axis` named `axis_name`: geometry + wear.
  double Length(size_t axis, const std::string& axis_name) const {
    const double geometry = axis < length.size() ? length[axis] : 0;
    const int l = LengthRegister(axis_name);
    return geometry + (l >= 0 ? wear[static_cast<size_t>(l)] : 0);
  }
};

struct ToolTable {
  std::vector<ToolEdge> edges;

  /// The edge of tool `t` with correction `d`; null if the list has none.
  const ToolEdge* Edge(int t, int d) const {
    for (const ToolEdge& e : edges)
      if (e.tool == t && e.edge == d) return &e;
    return nullptr;
  }
  /// The same as a copy; nullopt if the list has none.
  std::optional<ToolEdge> Find(int t, int d) const {
    if (const ToolEdge* e = Edge(t, d)) return *e;
    return std::nullopt;
  }
};

}  // namespace vmt::control::axes
