#pragma once
// The workpiece as the lathe turns it, for PathGuard: a solid of revolution about the spindle
// axis, kept as its radius per slice of Z. It starts as the scene's stock cylinder; while the
// spindle turns, every point of a cutting edge inside it lowers the slices it passes over to
// the radius it reaches, less a small allowance, so that a tool standing in its own cut is
// clear of the part, and an approach back into the cut meets only the material that is left.
//
// Plain data: the runner cuts it from the cutting edges' poses, the collision world poses the
// cylinders it gives (one per run of slices of one radius). Only the solid core is turned:
// the part's rings (a bore, the ring outside a face groove) stay as the scene made them.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "sim/collision/collision_world.hpp"
#include "sim/model/revolved_part.hpp"

namespace vmt::sim {

struct TurnedStock {
  std::string name;  ///< the collision part's name ("workpiece")
  std::string link;  ///< the link it turns with (the spindle)
  double z0_m = 0;   ///< where the part starts along the spindle axis, link frame
  double slice_m = 0.0005;
  std::vector<double> radius_m;     ///< per slice; 0: cut through, or no core there
  std::vector<CylinderPart> rings;  ///< the sections with a bore, as they are

  /// The part's solid sections in slices of `slice_m` from the first one's left face; a slice
  /// takes the largest radius of the sections it overlaps, so no material is missing.
  static TurnedStock FromPart(const RevolvedPart& part, double slice_m);

  /// The stock cylinder in slices of `slice_m` (its length rounded up to whole slices).
  static TurnedStock FromCylinder(const CylinderPart& stock, double slice_m);

  /// A point of a cutting edge at `z_m` along the spindle axis and `r_m` from it: the slices
  /// within `allowance_m` of it along z fall to r - allowance where they stood higher (the
  /// slice ahead of a leading face is cut up to a slice's width early). True if the part
  /// changed.
  bool Cut(double z_m, double r_m, double allowance_m);

  /// A triangle of a cutting part (spindle frame, m), exactly: every slice within
  /// `allowance_m` of it along z falls to the smallest distance from the axis of the piece of
  /// the triangle over that slice, less the allowance. A turning insert's flank lies lowest in
  /// the middle of a face, between its edges. True if the part changed.
  bool CutTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   double allowance_m);

  /// The part as cylinders, one per run of slices whose radii differ by at most `tolerance_m`
  /// (the run keeps its largest radius, so nothing left of the part is missing), then the rings.
  std::vector<CylinderPart> Cylinders(double tolerance_m) const;
};

}  // namespace vmt::sim
