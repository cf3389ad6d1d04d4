#include "render/mesh_primitives.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vmt::render {
namespace {

uint32_t AddVertex(Mesh& mesh, const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  const auto index = uint32_t(mesh.positions.size() / 3);
  mesh.positions.insert(mesh.positions.end(), {float(p.x()), float(p.y()), float(p.z())});
  mesh.normals.insert(mesh.normals.end(), {float(n.x()), float(n.y()), float(n.z())});
  return index;
}

void AddTriangle(Mesh& mesh, uint32_t a, uint32_t b, uint32_t c) {
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

}  // namespace

Mesh MakeCylinder(double radius_m, double length_m, int segments) {
  if (!(radius_m > 0) || !(length_m > 0) || segments < 3) {
    throw std::runtime_error("MakeCylinder: need radius > 0, length > 0 and segments >= 3, got " +
                             std::to_string(radius_m) + ", " + std::to_string(length_m) + ", " +
                             std::to_string(segments));
  }
  Mesh mesh;
  const auto n = uint32_t(segments);
  mesh.positions.reserve(size_t(n) * 4 * 3 + 6);
  mesh.normals.reserve(size_t(n) * 4 * 3 + 6);
  mesh.indices.reserve(size_t(n) * 4 * 3);
  auto ring = [&](uint32_t i) {
    const double angle = 2 * std::numbers::pi * double(i) / double(n);
    return Eigen::Vector3d(std::cos(angle), std::sin(angle), 0);
  };
  const Eigen::Vector3d top(0, 0, length_m);

  // Side: one bottom and one top vertex per segment sharing the radial normal.
  const uint32_t side = uint32_t(mesh.positions.size() / 3);
  for (uint32_t i = 0; i < n; ++i) {
    const Eigen::Vector3d dir = ring(i);
    AddVertex(mesh, radius_m * dir, dir);
    AddVertex(mesh, radius_m * dir + top, dir);
  }
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t j = (i + 1) % n;
    const uint32_t b0 = side + 2 * i, t0 = b0 + 1, b1 = side + 2 * j, t1 = b1 + 1;
    AddTriangle(mesh, b0, b1, t1);
    AddTriangle(mesh, b0, t1, t0);
  }

  // Caps: own vertices so their normals stay flat; fans wound to face outwards.
  for (const bool is_top : {false, true}) {
    const Eigen::Vector3d normal(0, 0, is_top ? 1 : -1);
    const Eigen::Vector3d offset = is_top ? top : Eigen::Vector3d::Zero();
    const uint32_t centre = AddVertex(mesh, offset, normal);
    for (uint32_t i = 0; i < n; ++i) AddVertex(mesh, radius_m * ring(i) + offset, normal);
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t a = centre + 1 + i, b = centre + 1 + (i + 1) % n;
      if (is_top) {
        AddTriangle(mesh, centre, a, b);
      } else {
        AddTriangle(mesh, centre, b, a);
      }
    }
  }
  return mesh;
}

Mesh MakeTube(double inner_radius_m, double outer_radius_m, double length_m, int segments) {
  if (!(inner_radius_m > 0) || !(outer_radius_m > inner_radius_m) || !(length_m > 0) ||
      segments < 3) {
    throw std::runtime_error(
        "MakeTube: need 0 < inner radius < outer radius, length > 0 and segments >= 3, got " +
        std::to_string(inner_radius_m) + ", " + std::to_string(outer_radius_m) + ", " +
        std::to_string(length_m) + ", " + std::to_string(segments));
  }
  Mesh mesh;
  const auto n = uint32_t(segments);
  auto ring = [&](uint32_t i) {
    const double angle = 2 * std::numbers::pi * double(i) / double(n);
    return Eigen::Vector3d(std::cos(angle), std::sin(angle), 0);
  };
  const Eigen::Vector3d top(0, 0, length_m);
  // Walls: the outer one faces away from the axis, the bore's towards it.
  for (const bool outer : {true, false}) {
    const double r = outer ? outer_radius_m : inner_radius_m;
    const uint32_t first = uint32_t(mesh.positions.size() / 3);
    for (uint32_t i = 0; i < n; ++i) {
      const Eigen::Vector3d dir = ring(i);
      AddVertex(mesh, r * dir, outer ? dir : Eigen::Vector3d(-dir));
      AddVertex(mesh, r * dir + top, outer ? dir : Eigen::Vector3d(-dir));
    }
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t j = (i + 1) % n;
      const uint32_t b0 = first + 2 * i, t0 = b0 + 1, b1 = first + 2 * j, t1 = b1 + 1;
      if (outer) {
        AddTriangle(mesh, b0, b1, t1);
        AddTriangle(mesh, b0, t1, t0);
      } else {
        AddTriangle(mesh, b0, t1, b1);
        AddTriangle(mesh, b0, t0, t1);
      }
    }
  }
  // Annular faces: own vertices so their normals stay flat.
  for (const bool is_top : {false, true}) {
    const Eigen::Vector3d normal(0, 0, is_top ? 1 : -1);
    const Eigen::Vector3d offset = is_top ? top : Eigen::Vector3d::Zero();
    const uint32_t first = uint32_t(mesh.positions.size() / 3);
    for (uint32_t i = 0; i < n; ++i) {
      AddVertex(mesh, inner_radius_m * ring(i) + offset, normal);
      AddVertex(mesh, outer_radius_m * ring(i) + offset, normal);
    }
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t j = (i + 1) % n;
      const uint32_t in0 = first + 2 * i, out0 = in0 + 1, in1 = first + 2 * j, out1 = in1 + 1;
      if (is_top) {
        AddTriangle(mesh, in0, out0, out1);
        AddTriangle(mesh, in0, out1, in1);
      } else {
        AddTriangle(mesh, in0, out1, out0);
        AddTriangle(mesh, in0, in1, out1);
      }
    }
  }
  return mesh;
}

Mesh MakeBox(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  if (!(min.array() <= max.array()).all()) {
    throw std::runtime_error("MakeBox: max must not be below min in any coordinate");
  }
  Mesh mesh;
  // Per face: outward axis, and two in-plane axes u, v with u x v = normal so the quad
  // (0,0) (1,0) (1,1) (0,1) in (u, v) is counter-clockwise from outside.
  for (int axis = 0; axis < 3; ++axis) {
    for (const int sign : {-1, 1}) {
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      normal[axis] = sign;
      const int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;
      const uint32_t first = uint32_t(mesh.positions.size() / 3);
      for (const auto& [su, sv] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
        Eigen::Vector3d p;
        p[axis] = sign > 0 ? max[axis] : min[axis];
        // On the negative face, swap the roles of u and v to keep the winding outward.
        const int along_u = sign > 0 ? su : sv, along_v = sign > 0 ? sv : su;
        p[u_axis] = along_u ? max[u_axis] : min[u_axis];
        p[v_axis] = along_v ? max[v_axis] : min[v_axis];
        AddVertex(mesh, p, normal);
      }
      AddTriangle(mesh, first, first + 1, first + 2);
      AddTriangle(mesh, first, first + 2, first + 3);
    }
  }
  return mesh;
}

Mesh MakeSphere(double radius_m, int rings, int segments) {
  if (!(radius_m > 0) || rings < 2 || segments < 3) {
    throw std::runtime_error("MakeSphere: need radius > 0, rings >= 2 and segments >= 3, got " +
                             std::to_string(radius_m) + ", " + std::to_string(rings) + ", " +
                             std::to_string(segments));
  }
  Mesh mesh;
  const auto n = uint32_t(segments), r = uint32_t(rings);
  // Rows of latitude from the south pole (row 0) to the north pole (row r); a pole is one
  // vertex, every other row n.
  auto row_start = [&](uint32_t row) { return row == 0 ? 0u : 1 + (row - 1) * n; };
  for (uint32_t row = 0; row <= r; ++row) {
    const double polar = std::numbers::pi * double(row) / double(r);
    const double z = -std::cos(polar), ring_radius = std::sin(polar);
    const uint32_t count = (row == 0 || row == r) ? 1 : n;
    for (uint32_t i = 0; i < count; ++i) {
      const double angle = 2 * std::numbers::pi * double(i) / double(n);
      const Eigen::Vector3d dir = count == 1 ? Eigen::Vector3d(0, 0, z)
                                             : Eigen::Vector3d(ring_radius * std::cos(angle),
                                                               ring_radius * std::sin(angle), z);
      AddVertex(mesh, radius_m * dir, dir);
    }
  }
  const uint32_t north = row_start(r);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t j = (i + 1) % n;
    AddTriangle(mesh, 0, row_start(1) + j, row_start(1) + i);
    AddTriangle(mesh, north, row_start(r - 1) + i, row_start(r - 1) + j);
    for (uint32_t row = 1; row + 1 < r; ++row) {
      const uint32_t a = row_start(row) + i, b = row_start(row) + j;
      const uint32_t c = row_start(row + 1) + j, d = row_start(row + 1) + i;
      AddTriangle(mesh, a, b, c);
      AddTriangle(mesh, a, c, d);
    }
  }
  return mesh;
}

}  // namespace vmt::render
