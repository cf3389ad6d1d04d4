#pragma once
// The workpiece as the lathe turns it, for PathGuard and the pictures: a solid of revolution
// about the spindle axis, kept per slice of Z as the spans of radius that hold material. It
// starts as the scene's part (its stock cylinder, or its sections with their bores and face
// grooves); while the spindle turns, a cutting part sweeps, in every slice it passes through,
// the ring from its smallest to its largest distance from the axis, and that ring is cut away,
// widened by a small allowance, so that a tool standing in its own cut is clear of the part and
// an approach back into the cut meets only the material that is left.
//
// Which side a tool came in from decides what is gone. A part that reaches out of the material
// somewhere (a turning insert, a grooving blade, a facing tool) came in from outside: in each
// slice it takes everything above its nearest point, so the surface falls, also where the
// slices ahead of its leading face hold the chip it is cutting. A part wholly inside the
// material (a boring bar in its bore, a drill or a grooving blade in the end face) takes only
// the ring it sweeps: the slice keeps a core and a ring (a face groove), or only a ring (a
// bore). A cutting part counts as its convex hull, as inserts are.
//
// Plain data: the runner cuts it from the cutting parts' poses, the collision world and the
// renderer take the cylinders and tubes it gives (one per run of slices of one shape).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "sim/collision/collision_world.hpp"
#include "sim/model/revolved_part.hpp"

namespace vmt::sim {

/// Material of a slice between two distances from the axis (inner 0: it reaches the axis).
struct StockSpan {
  double inner_m = 0, outer_m = 0;
};

struct TurnedStock {
  std::string name;  ///< the collision part's name ("workpiece")
  std::string link;  ///< the link it turns with (the spindle)
  double z0_m = 0;   ///< where the part starts along the spindle axis, link frame
  double slice_m = 0.0005;
  /// Per slice, its material from the axis outwards (disjoint, rising); none: cut through, or
  /// no material there.
  std::vector<std::vector<StockSpan>> slices;

  /// The part's sections in slices of `slice_m` from the first one's left face; a slice holds
  /// the union of the sections it overlaps, so no material is missing.
  static TurnedStock FromPart(const RevolvedPart& part, double slice_m);

  /// The stock cylinder in slices of `slice_m` (its length rounded up to whole slices).
  static TurnedStock FromCylinder(const CylinderPart& stock, double slice_m);

  /// The slice's outermost radius; 0 where nothing is left.
  double OuterRadius(size_t slice) const;

  /// A point of a turning edge at `z_m` along the spindle axis and `r_m` from it, come from
  /// outside: the slices within `allowance_m` of it along z lose everything above r less the
  /// allowance (the slice ahead of a leading face is cut up to a slice's width early). True if
  /// the part changed.
  bool TurnDown(double z_m, double r_m, double allowance_m);

  /// A cutting part (spindle frame, m) as its triangles, three corners each: in every slice
  /// within `allowance_m` of it along z, the ring its hull sweeps there as the part turns (from
  /// its smallest distance from the axis to its largest, widened by the allowance) is cut away,
  /// and all above it where the part reaches out of the material. True if the part changed.
  bool CutSolid(const std::vector<Eigen::Vector3d>& corners, double allowance_m);

  /// The part as cylinders and tubes: per run of slices with the same number of spans whose
  /// radii differ by at most `tolerance_m`, one per span, from the span's smallest inner to its
  /// largest outer radius in the run, so nothing left of the part is missing.
  std::vector<CylinderPart> Cylinders(double tolerance_m) const;

 private:
  /// Adds material from `inner_m` to `outer_m` to a slice (union).
  void Add(size_t slice, double inner_m, double outer_m);
  /// No material in the slice from `inner_m` to `outer_m`. True if some was there.
  bool Remove(size_t slice, double inner_m, double outer_m);
};

}  // namespace vmt::sim
