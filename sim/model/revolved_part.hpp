#pragma once
// A part of a lathe as its true dimensions: a solid of revolution about its link's z axis (the
// spindle axis), given as annular sections along z; the part is their union. A stepped shaft is
// sections with r_inner 0 one after another; a face groove is two sections over the groove's
// depth, the core inside the groove and the ring outside it. The probe measures against this
// shape exactly, so the scene knows every dimension the NC measures.
//
// Plain data in the link frame, SI (m).

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

}  // namespace vmt::sim
