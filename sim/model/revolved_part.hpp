#pragma once
// A part of a lathe as its true dimensions: a solid of revolution about its link's z axis (the
// spindle axis), given as annular sections along z; the part is their union. A stepped shaft is
// sections with r_inner 0 one after another; a face groove is two sections over the groove's
// depth, the core inside the groove and the ring outside it. The probe measures against this
// shape exactly, so the scene knows every dimension the NC measures.
//
// Plain data in the link frame, SI (m).

#include <Eigen/Core>
#include <string>
#include <vector>

namespace vmt::sim {

/// The ring between r_inner_m and r_outer_m from z0_m to z1_m (z0_m < z1_m, 0 <= r_inner_m <
/// r_outer_m). Sections may share a stretch of z (a groove between two rings), not material.
struct RevolvedSection {
  double z0_m = 0, z1_m = 0;
  double r_inner_m = 0, r_outer_m = 0;
};

struct RevolvedPart {
  std::string name;  ///< e.g. "workpiece"
  std::string link;  ///< the link it turns with (the spindle)
  std::vector<RevolvedSection> sections;
};

/// The nearest point of a part's surface to a point, link frame, SI.
struct RevolvedDistance {
  /// Signed distance: > 0 outside, < 0 inside (minus the depth), 0 on the surface; +infinity
  /// for a part without sections.
  double distance_m = 0;
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();  ///< nearest surface point
  /// Outward unit normal there: the direction in which the distance grows fastest. On the axis
  /// every meridian is nearest; the one towards +x is taken.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};

/// Exact signed distance from p_Link_m to the part: the nearest point of a solid of revolution
/// lies in the point's own meridian half-plane, so this is the 2D distance from (r, z) to the
/// union of the sections' rectangles. Where two sections meet, their sides count only where
/// one stands beyond the other (the shoulder of a step, the floor of a face groove); the axis
/// is no surface.
RevolvedDistance SignedDistance(const RevolvedPart& part, const Eigen::Vector3d& p_Link_m);

/// A bound SignedDistance never falls below (but for rounding, a few ulps), from the part's
/// bounding cylinder alone (no outline is walked): the distance to that cylinder, or -infinity
/// for a point within it (where the point may lie inside the part) and +infinity for a part
/// without sections.
double DistanceLowerBound(const RevolvedPart& part, const Eigen::Vector3d& p_Link_m);

/// What is wrong with the part's sections ("" when nothing): a section with z1 <= z0, r_inner
/// < 0, r_outer <= r_inner or a number that is not finite, or two sections that share material.
/// The message names the section by its index.
std::string RevolvedPartError(const RevolvedPart& part);

}  // namespace vmt::sim
