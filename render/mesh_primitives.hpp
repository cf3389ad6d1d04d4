#pragma once

#include <Eigen/Core>

#include "render/mesh.hpp"

namespace vmt::render {

/// A closed cylinder along +z from z = 0 to z = length_m: smooth side normals, flat caps,
/// 4 * segments triangles. Throws std::runtime_error unless radius_m > 0, length_m > 0 and
/// segments >= 3.
Mesh MakeCylinder(double radius_m, double length_m, int segments);

/// An axis-aligned box between the corners `min` and `max` (metres), flat normals, 12 triangles.
/// Throws std::runtime_error if max < min in any coordinate.
Mesh MakeBox(const Eigen::Vector3d& min, const Eigen::Vector3d& max);

}  // namespace vmt::render
