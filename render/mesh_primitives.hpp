#pragma once

#include <Eigen/Core>

#include "render/mesh.hpp"

namespace vmt::render {

/// A closed cylinder along +z from z = 0 to z = length_m: smooth side normals, flat caps,
/// 4 * segments triangles. Throws std::runtime_error unless radius_m > 0, length_m > 0 and
/// segments >= 3.
Mesh MakeCylinder(double radius_m, double length_m, int segments);

/// A tube along +z from z = 0 to z = length_m (a bored section, the ring outside a face groove):
/// outer wall, bore, annular end faces, 8 * segments triangles. Throws std::runtime_error unless
/// 0 < inner_radius_m < outer_radius_m, length_m > 0 and segments >= 3.
Mesh MakeTube(double inner_radius_m, double outer_radius_m, double length_m, int segments);

/// An axis-aligned box between the corners `min` and `max` (metres), flat normals, 12 triangles.
/// Throws std::runtime_error if max < min in any coordinate.
Mesh MakeBox(const Eigen::Vector3d& min, const Eigen::Vector3d& max);

/// A sphere about the origin: `rings` bands of latitude by `segments` of longitude, smooth
/// normals, vertices on the sphere. Throws std::runtime_error unless radius_m > 0, rings >= 2
/// and segments >= 3.
Mesh MakeSphere(double radius_m, int rings, int segments);

}  // namespace vmt::render
