#include "sim/collision/collision_world.hpp"

#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "render/mesh_primitives.hpp"
#include "sim/collision/collision_shape.hpp"
#include "sim/model/model_error.hpp"

namespace vmt::sim {

struct CollisionWorld::Fcl {
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> geometry;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
};

namespace {

/// The part's solid `shape` of a mesh placed at `X_LinkMesh` (FCL's box sits at its centre).
std::shared_ptr<fcl::CollisionGeometryd> MeshGeometry(const CollisionShape& shape,
                                                      const Eigen::Isometry3d& X_LinkMesh,
                                                      CollisionPart& p) {
  p.X_LinkPart = X_LinkMesh * shape.X_MeshShape;
  p.centre = shape.X_MeshShape.inverse() * shape.centre;
  p.radius = shape.radius;
  return shape.geometry;
}

// The measuring sphere whose ball the sphere part `p` (bounding sphere from its mesh) is: the
// stylus' sphere nearest the mesh's centre, if that centre lies inside it.
const MeasuringSphere* BallOf(const ProbeStylus& stylus, const CollisionPart& p) {
  const Eigen::Vector3d centre = p.X_LinkPart * p.centre;
  const MeasuringSphere* best = nullptr;
  for (const MeasuringSphere& ball : stylus.spheres)
    if ((ball.centre_m - centre).norm() < ball.radius_m &&
        (!best || (ball.centre_m - centre).norm() < (best->centre_m - centre).norm()))
      best = &ball;
  return best;
}

// Bit for bit: a part whose numbers differ only in the sign of a zero is built anew.
bool SameCylinder(const CylinderPart& a, const CylinderPart& b) {
  const auto same = [](double x, double y) {
    return std::bit_cast<uint64_t>(x) == std::bit_cast<uint64_t>(y);
  };
  return a.name == b.name && a.link == b.link && same(a.radius_m, b.radius_m) &&
         same(a.length_m, b.length_m) && same(a.z_m, b.z_m) &&
         same(a.inner_radius_m, b.inner_radius_m);
}

}  // namespace

CollisionWorld::CollisionWorld(const MachineModel& model, const std::vector<CylinderPart>& added)
    : model_(&model), fcl_(std::make_unique<Fcl>()) {
  for (size_t l = 0; l < model.links.size(); ++l) {
    const Link& link = model.links[l];
    for (size_t c = 0; c < link.collisions.size(); ++c) {
      const Visual& v = link.collisions[c];
      if (!v.mesh || v.mesh->indices.empty()) continue;
      CollisionPart p;
      p.name = v.name.empty() ? link.name + "#" + std::to_string(c) : v.name;
      p.link = static_cast<int>(l);
      const ProbeStylus* stylus = nullptr;
      for (const ProbeStylus& s : model.probes)
        if (s.link == static_cast<int>(l))
          for (const std::string& sphere : s.sphere_parts)
            if (sphere == v.name) stylus = &s;
      p.measures = stylus != nullptr;
      std::shared_ptr<fcl::CollisionGeometryd> geometry;
      if (v.primitive.kind != Primitive::Kind::kNone) {
        const CollisionShape shape = ShapeOfPrimitive(v.primitive);
        p.X_LinkPart = v.X_LinkVisual;
        p.radius = shape.radius;
        geometry = shape.geometry;
      } else {
        geometry = MeshGeometry(SharedShapeOfMesh(v.mesh), v.X_LinkVisual, p);
      }
      if (const MeasuringSphere* ball = stylus ? BallOf(*stylus, p) : nullptr) {
        // A ruby's mesh has its vertices on the sphere and its faces inside it: a sharp edge
        // (a bore's rim) would come up to the sagitta (tens of um) closer than PathGuard saw,
        // and the stylus switch trips on 5 um. The ball itself, as FCL's sphere, is exact.
        p.X_LinkPart = Eigen::Isometry3d::Identity();
        p.X_LinkPart.translation() = ball->centre_m;
        p.centre = Eigen::Vector3d::Zero();
        p.radius = ball->radius_m;
        geometry = std::make_shared<fcl::Sphered>(ball->radius_m);
      }
      fcl_->geometry.push_back(geometry);
      parts_.push_back(p);
    }
  }
  machine_parts_ = size();
  for (auto& g : fcl_->geometry) fcl_->objects.push_back(ObjectOf(g));
  aside_.assign(machine_parts_, 0);
  SetAdded(added);
  queries_ = 0;
}

CollisionWorld::~CollisionWorld() = default;

void CollisionWorld::SetAdded(const std::vector<CylinderPart>& added) {
  const MachineModel& model = *model_;
  const int old_size = size();
  // A part added again unchanged keeps its solid, its object and its pairs: the stock as it is
  // turned changes a few of its cylinders at a time, the spindle's sweep none, and building a
  // tube's mesh and testing the new part against every machine part in the zero pose is most
  // of the cost. The same solid gives every query the same bits.
  const std::vector<CylinderPart> old_added = std::move(added_);
  std::vector<CollisionPart> old_parts(parts_.begin() + machine_parts_, parts_.end());
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> old_geometry(
      fcl_->geometry.begin() + machine_parts_, fcl_->geometry.end());
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> old_objects;
  for (size_t i = machine_parts_; i < fcl_->objects.size(); ++i)
    old_objects.push_back(std::move(fcl_->objects[i]));
  parts_.resize(machine_parts_);
  fcl_->geometry.resize(machine_parts_);
  fcl_->objects.resize(machine_parts_);
  added_ = added;
  std::vector<int> was(added.size(), -1);  // per added part, its index among the old ones
  std::vector<char> taken(old_added.size(), 0);
  for (size_t k = 0; k < added.size(); ++k) {
    const CylinderPart& c = added[k];
    for (size_t j = 0; j < old_added.size() && was[k] < 0; ++j)
      if (!taken[j] && SameCylinder(old_added[j], c)) was[k] = static_cast<int>(j), taken[j] = 1;
    if (was[k] >= 0) {
      parts_.push_back(old_parts[was[k]]);
      fcl_->geometry.push_back(old_geometry[was[k]]);
      fcl_->objects.push_back(std::move(old_objects[was[k]]));
      continue;
    }
    CollisionPart p;
    p.name = c.name;
    p.link = model.LinkIndex(c.link);
    if (p.link < 0) throw ModelError(model.yaml_path, c.name, "no link '" + c.link + "'");
    if (c.inner_radius_m > 0) {
      // FCL has no tube: a mesh whose outer wall circumscribes the circle and whose bore's
      // corners lie on it, so the polygon never misses material.
      constexpr int kSegments = 64;
      const double outer = c.radius_m / std::cos(std::numbers::pi / kSegments);
      fcl_->geometry.push_back(MeshGeometry(
          ShapeOfMesh(render::MakeTube(c.inner_radius_m, outer, c.length_m, kSegments)),
          Eigen::Isometry3d(Eigen::Translation3d(0, 0, c.z_m)), p));
    } else {
      // FCL's cylinder is centred on its origin.
      p.X_LinkPart.translation() = Eigen::Vector3d(0, 0, c.z_m + c.length_m / 2);
      p.radius = std::hypot(c.radius_m, c.length_m / 2);
      fcl_->geometry.push_back(std::make_shared<fcl::Cylinderd>(c.radius_m, c.length_m));
    }
    parts_.push_back(p);
    fcl_->objects.push_back(ObjectOf(fcl_->geometry.back()));
  }

  // The machine's own contacts: same link, links joined by a joint, and parts that touch in the
  // zero pose and only turn against each other (a pinion in its gear). A slide between them
  // makes a zero-pose contact chance (a tool that stands in the workpiece at X0 Z0).
  auto slides_between = [&](int la, int lb) {
    std::vector<int> up_a, up_b;
    for (int l = la; model.links[l].parent_joint >= 0;
         l = model.joints[model.links[l].parent_joint].parent_link)
      up_a.push_back(model.links[l].parent_joint);
    for (int l = lb; model.links[l].parent_joint >= 0;
         l = model.joints[model.links[l].parent_joint].parent_link)
      up_b.push_back(model.links[l].parent_joint);
    auto prismatic_not_in = [&](const std::vector<int>& mine, const std::vector<int>& other) {
      for (int j : mine)
        if (model.joints[j].type == JointType::kPrismatic &&
            std::find(other.begin(), other.end(), j) == other.end())
          return true;
      return false;
    };
    return prismatic_not_in(up_a, up_b) || prismatic_not_in(up_b, up_a);
  };
  // The machine's pairs keep what they were; the added parts' are worked out anew.
  const int n = size();
  std::vector<char> before = std::move(may_touch_);
  may_touch_.assign(static_cast<size_t>(n) * n, 0);
  for (int a = 0; a < std::min(n, machine_parts_); ++a)
    for (int b = 0; b < machine_parts_ && !before.empty(); ++b)
      may_touch_[a * n + b] = before[a * old_size + b];
  Pose(std::vector<double>(model.joints.size(), 0.0));
  // A pair of a machine part or a kept part with a kept part: as it was.
  const auto old_index = [&](int i) {
    return i < machine_parts_            ? i
           : was[i - machine_parts_] < 0 ? -1
                                         : machine_parts_ + was[i - machine_parts_];
  };
  for (int a = 0; a < n; ++a)
    for (int b = std::max(a, before.empty() ? 0 : machine_parts_); b < n; ++b) {
      if (const int oa = old_index(a), ob = old_index(b); oa >= 0 && ob >= machine_parts_) {
        may_touch_[a * n + b] = may_touch_[b * n + a] = before[oa * old_size + ob];
        continue;
      }
      const int la = parts_[a].link, lb = parts_[b].link;
      bool own = la == lb;
      for (const Joint& j : model.joints)
        own = own || (j.parent_link == la && j.child_link == lb) ||
              (j.parent_link == lb && j.child_link == la);
      own = own || (!slides_between(la, lb) && Collide(a, b));
      may_touch_[a * n + b] = may_touch_[b * n + a] = own;
    }
}

void CollisionWorld::Restore(const Saved& saved) {
  SetAdded(saved.added);
  aside_ = saved.aside;
  measuring_ = saved.measuring;
  X_WorldLink_ = saved.X_WorldLink;
  for (int i = 0; i < size(); ++i) PosePart(i);
  queries_ = saved.queries;
}

void CollisionWorld::Pose(const std::vector<double>& q) {
  X_WorldLink_ = LinkPoses(*model_, q);
  for (int i = 0; i < size(); ++i) PosePart(i);
}

void CollisionWorld::PosePair(const std::vector<double>& q, int a, int b) {
  X_WorldLink_ = LinkPoses(*model_, q);
  PosePart(a);
  PosePart(b);
}

void CollisionWorld::PosePart(int i) {
  const Eigen::Isometry3d X = X_WorldLink_[parts_[i].link] * parts_[i].X_LinkPart;
  fcl_->objects[i]->setTransform(X);
  fcl_->objects[i]->computeAABB();
}

double CollisionWorld::Distance(int a, int b, Eigen::Vector3d* point_a,
                                Eigen::Vector3d* point_b) const {
  ++queries_;
  fcl::DistanceRequestd request(point_a != nullptr || point_b != nullptr);
  // GJK stops once an iteration gains less than this, not on a proven gap: at FCL's 1e-6 m a
  // convex part's distance came out up to 8 % long (a 48-sided cylinder at 2.5 mm), and
  // PathGuard steps on it. At 1e-10 m GJK runs to the polytope's exact answer.
  request.distance_tolerance = 1e-10;
  fcl::DistanceResultd result;
  fcl::distance(fcl_->objects[a].get(), fcl_->objects[b].get(), request, result);
  if (point_a) *point_a = result.nearest_points[0];
  if (point_b) *point_b = result.nearest_points[1];
  return std::max(0.0, result.min_distance);
}

double CollisionWorld::BoxDistance(int a, int b) const {
  return fcl_->objects[a]->getAABB().distance(fcl_->objects[b]->getAABB());
}

Eigen::AlignedBox3d CollisionWorld::Box(int i) const {
  const fcl::AABBd& box = fcl_->objects[i]->getAABB();
  return Eigen::AlignedBox3d(box.min_, box.max_);
}

bool CollisionWorld::Collide(int a, int b, Eigen::Vector3d* point) const {
  ++queries_;
  fcl::CollisionRequestd request(1, point != nullptr);
  fcl::CollisionResultd result;
  fcl::collide(fcl_->objects[a].get(), fcl_->objects[b].get(), request, result);
  if (!result.isCollision()) return false;
  if (point && result.numContacts() > 0) *point = result.getContact(0).pos;
  return true;
}

}  // namespace vmt::sim
