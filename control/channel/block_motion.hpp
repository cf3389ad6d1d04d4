#pragma once
// The motion of one prepared block in axis space: its path (a straight line, or an arc in the
// plane with the other axes following linearly: a helix), its length and the limits of its feed
// profile. A function of the block, where it starts and the machine data only, so that the
// look-ahead can plan blocks before they run.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "control/axes/axis_parameters.hpp"
#include "control/nc/coordinate_transformation.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

/// mm: an arc's radius at its start and at its end may differ this much.
inline constexpr double kArcTolerance = 0.01;

struct BlockMotion {
  std::vector<double> start, end;  ///< axis positions, mm | deg
  int arc_axes[2] = {-1, -1};      ///< channel axes of the arc plane; -1: not an arc
  double arc_centre[2] = {0, 0};
  double arc_radius = 0, arc_start_angle = 0, arc_sweep = 0;  ///< sweep < 0: clockwise
  double length = 1;  ///< |dP/du| in axis space (mm and degrees together)
  /// Limits of the profile over u (PathProfile): rate at the programmed feed, acceleration,
  /// jerk (0: none).
  double max_rate = 0, max_accel = 0, max_jerk = 0;
  bool moves = false;  ///< false: nothing to move, the block is done at once
  /// G31 (coordinate_transformation.hpp): X and C follow a straight line of the face plane
  /// from `face_from` to `face_to` (program coordinates), or the arc `face_arc` between them
  /// (G02/G03, `face_is_arc`); u runs along it with the other axes.
  /// face_axes: the channel axes X and C; -1: no transformation.
  int face_axes[2] = {-1, -1};
  nc::FictivePoint face_from, face_to;
  bool face_is_arc = false;
  nc::FaceArc face_arc;
  double face_shift[2] = {0, 0};  ///< program -> axis translation of X and C

  /// G31: the point of the face at u, and the geometry the limits and PathGuard need.
  nc::FictivePoint FacePoint(double u) const;
  nc::FaceLine FaceBounds() const;

  /// Axis positions at u (0..1).
  void PointAt(double u, std::vector<double>& out) const;
  /// Direction of travel at u = 0 or u = 1: dP/du, not normalised.
  std::vector<double> Direction(double u) const;
};

struct MotionError {
  std::string text;
  int number = 0;  ///< channel_messages.hpp
};

/// Plans `block` from the axis positions `start`. The programmed target is in program
/// coordinates; `translation` (zero offset, G92 shift, tool length) takes it to the axes.
/// `spindle_rev_per_s` turns a feed per revolution (G95) into a path feed. A target beyond an
/// axis' travel is an error before the move starts, so the axis never meets its limit switch.
/// Axes in `follow_up` (bit per axis) stay where they are: the NC does not position them (a
/// rotary axis while its spindle is in spindle mode, C-axis manual 4.3), so their actual
/// position, which start holds, is no move of the block.
std::optional<MotionError> PlanBlockMotion(const nc::PreparedBlock& block,
                                           const std::vector<double>& start,
                                           const std::vector<double>& translation,
                                           const std::vector<axes::AxisParameters>& axes,
                                           double spindle_rev_per_s, BlockMotion& out,
                                           uint64_t follow_up = 0);

}  // namespace vmt::control::channel
