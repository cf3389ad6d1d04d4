#pragma once
// A measuring stylus on its compliant mount against the workpiece's true shape, stepped every
// drive tick (fast-measurement manual 7.3: the probe inputs are scanned every 250 µs). The part
// pushes a measuring sphere back by as much as the undeflected sphere would sink into it; the
// switch trips when that deflection exceeds the pre-travel and releases below it; NO/NC gives
// the contact's level; beyond the over-travel the stylus is damaged.
//
// Within a tick the sphere centres move in a straight line, and the instant the deflection
// crosses the pre-travel is solved on that line (to well below 0.1 µm), so a drive latch can
// interpolate its position to the contact exactly. Plain functions and data, SI (m).

#include <Eigen/Geometry>
#include <vector>

#include "sim/model/probe_stylus.hpp"
#include "sim/model/revolved_part.hpp"

namespace vmt::sim {

/// What the stylus remembers from tick to tick.
struct StylusState {
  bool tripped = false;  ///< the mount deflected beyond the pre-travel (the switch's mechanics)
  bool level = false;    ///< the contact input's level as last reported (0 before the first)
  bool damaged = false;  ///< deflected beyond the over-travel once
  double deflection_m = 0;
};

/// One tick's result. `changed`, `io_input`, `level` and `tick_fraction` are exactly the
/// arguments of MachineBackend::SetProbeSwitch(io_input, level, tick_fraction).
struct StylusTick {
  int io_input = -1;  ///< the stylus' contact input (I/O index)
  /// The contact input changed in this tick: to `level`, at `tick_fraction` of the tick (0: the
  /// previous tick's instant, 1: this one's), where the deflection crossed the pre-travel.
  bool changed = false;
  bool level = false;
  double tick_fraction = 0;
  /// The largest deflection of any sphere at the tick's end, m (0 when none touches), and the
  /// sphere it is (-1 when none).
  double deflection_m = 0;
  int sphere = -1;
  /// The event: the deflection passed the over-travel in this tick (once per stylus), at
  /// over_travel_fraction of the tick. The runner makes it a collision of sphere
  /// `over_travel_sphere` with the part at `over_travel_point_m` (part frame).
  bool over_travel = false;
  double over_travel_fraction = 0;
  int over_travel_sphere = -1;
  Eigen::Vector3d over_travel_point_m = Eigen::Vector3d::Zero();
};

/// The spheres' centres in the part's frame for the pose of the stylus' link in it.
std::vector<Eigen::Vector3d> SphereCentres(const ProbeStylus& stylus,
                                           const Eigen::Isometry3d& X_PartLink);

/// How much nearer the part every sphere at `centres` (part frame) could come, m, and a tick
/// ending there would still be a quiet one for StepStylus: the least, over the spheres, of the
/// room its bounding-cylinder test leaves. <= 0 when a sphere is near.
double FarRoom(const ProbeStylus& stylus, const RevolvedPart& part, const StylusState& state,
               const std::vector<Eigen::Vector3d>& centres);

/// A tick far from the part (what StepStylus does when no sphere comes near): the mount at
/// rest, the input set by the ready message alone.
StylusTick QuietTick(const ProbeStylus& stylus, StylusState& state, bool ready);

/// How far the part pushes sphere `index` back at `centre_m` (part frame): the depth the
/// undeflected sphere would sink in, 0 when it is clear.
double SphereDeflection(const ProbeStylus& stylus, const RevolvedPart& part, int index,
                        const Eigen::Vector3d& centre_m);

/// Advances the stylus over one tick. `before` and `after`: the sphere centres (SphereCentres)
/// at the previous tick's instant and at this one's, both in one frame of the part's axis: the
/// part is a solid of revolution, so its angle does not matter, and taking the spindle's pose
/// of this tick for both keeps a turning spindle from bending a straight move into a chord.
/// `ready`: the probe's ready message this tick (true for a stylus without one). While not
/// ready the input is 0, whatever the contact: no probe signal reaches it (an NC contact thus
/// reads "deflected", the fail-safe state). The mount deflects and can be damaged either way.
/// On the first step a sphere already deflected sets the switch at tick fraction 0.
StylusTick StepStylus(const ProbeStylus& stylus, const RevolvedPart& part, StylusState& state,
                      const std::vector<Eigen::Vector3d>& before,
                      const std::vector<Eigen::Vector3d>& after, bool ready);

}  // namespace vmt::sim
