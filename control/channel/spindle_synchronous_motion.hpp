#pragma once
// Spindle-synchronous moves: G33 thread cutting, G63 tapping with a compensating chuck, G64
// tapping without one (rigid). The C-axis manual (2.3, 4.2) names them among the commands of
// main spindle mode but gives no syntax or law; this is vmt's reading, the usual one of lathe
// controls:
// - the block is a straight move of linear axes; its lead (mm per spindle revolution) is along
//   the axis that travels furthest, so the path advances ratio x lead per revolution with
//   ratio = path length / that axis' travel;
// - G33 ties the path to the spindle's ACTUAL position: s = k (phi - phi_sync) with
//   k = ratio x lead / 360 mm per degree. phi_sync is a zero mark of the spindle (a multiple of
//   360 degrees in the direction of rotation), so every pass of a thread cuts the same groove
//   whatever its spindle speed. The axes ramp in at their acceleration a on a parabola that
//   meets the law with its slope (it starts v / (2a) s before the mark, joins at v / a s after
//   its start, v = k |dphi/dt|) and run out the same way before the target: the thread is
//   incomplete over v^2 / (2a) mm at either end, as on any lathe (programs leave a run-in and
//   run-out), but the axes never jump and the block ends exactly at its target;
// - G63 runs at the path velocity lead x S (the commanded speed), feed and spindle override
//   held at 100 %: the chuck absorbs what the spindle and the axes do not share;
// - G64 puts the spindle in position control and interpolates it with the path:
//   phi = phi0 + dir x s / k, s on the normal path profile at lead x S, limited so that neither
//   the axes nor the spindle exceed their velocity and acceleration.
// Feed override has no effect on any of them; spindle override acts on G33 (through the spindle
// speed) and G64 (through the profile), not on G63 (C-axis manual 2.3: "the previous effect of
// feed and spindle overrides remains unchanged").

#include <optional>
#include <vector>

#include "control/axes/axis_parameters.hpp"
#include "control/channel/block_motion.hpp"
#include "control/channel/path_profile.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

/// G33's law over the spindle phase psi = dir (phi - phi_sync), degrees: path position s (mm
/// from the block start) with ramp-in and run-out.
struct ThreadLaw {
  double mm_per_deg = 0;       ///< k: path mm per spindle degree
  double length = 0;           ///< L: path length, mm
  double ramp_in_deg = 0;      ///< psi0: the ramp runs over psi in [-psi0, psi0]
  double run_out_deg = 0;      ///< psi1 once the run-out has begun (0 before)
  double run_out_end_deg = 0;  ///< psi where the run-out reaches the target (s = L)

  /// s at phase psi (degrees past the zero mark); 0 before the ramp, L after the run-out.
  double PathAt(double psi) const;
  /// Half the spindle phase (degrees) a ramp from rest to the law takes at spindle speed w
  /// deg/s and path acceleration a mm/s^2: k w^2 / (2a) (the ramp lasts v / a s, v = k |w|).
  static double RampDeg(double mm_per_deg, double spindle_deg_per_s, double accel);
  /// Locks the run-out at phase psi: s follows the law up to psi and then a parabola that
  /// reaches L with zero slope at psi + 2 psi1.
  void BeginRunOut(double psi);
  bool running_out() const { return run_out_deg > 0; }
  /// Phase at which the law itself reaches L.
  double LawEndDeg() const { return length / mm_per_deg; }
};

/// The zero mark (unwrapped spindle degrees, a multiple of 360) a thread starts from: the
/// first one at least `ramp_in_deg` ahead of `phi` in the direction of rotation `direction`.
double ThreadZeroMark(double phi, int direction, double ramp_in_deg);

/// The geometry of a spindle-synchronous block, with the limits of its axes.
struct SynchronousPath {
  BlockMotion line;       ///< start/end in axis positions; its max_rate x length: the axes' rapid
  double length = 0;      ///< path length over the linear axes, mm
  double mm_per_deg = 0;  ///< k = length / dominant travel x lead / 360
  double max_speed = 0;   ///< mm/s the axes allow along the path (their rapid)
  double max_accel = 0;   ///< mm/s^2 along the path (the least axis limit, as G01)
  double max_jerk = 0;    ///< mm/s^3, 0: none
};

/// Plans `block` (G33/G63/G64) from `start` like PlanBlockMotion; errors: a rotary axis
/// programmed, no move, a target beyond the travel.
std::optional<MotionError> PlanSynchronousPath(const nc::PreparedBlock& block,
                                               const std::vector<double>& start,
                                               const std::vector<double>& translation,
                                               const std::vector<axes::AxisParameters>& axes,
                                               uint64_t follow_up, SynchronousPath& out);

/// G64: the path profile's limits (over u) at S rpm with spindle limits (deg/s, deg/s^2; 0:
/// none): path speed k x S x 6, within the axes' and the spindle's speed and acceleration.
void RigidTappingLimits(const SynchronousPath& path, double spindle_rpm,
                        double spindle_max_deg_per_s, double spindle_max_accel,
                        PathProfile& profile);

}  // namespace vmt::control::channel
