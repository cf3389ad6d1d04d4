#pragma once
// The FCL mirror of a machine's collision geometry (DESIGN.md, PathGuard): one FCL object per
// URDF <collision> mesh, plus the parts a scene adds (the workpiece), posed from joint
// positions. Internal unit SI (m, rad) like the model; PathGuard converts at its boundary.
//
// Which pairs may touch: parts of one link, of links joined by one joint (saddle on its rail,
// turret in its housing) and parts that touch in the model's zero pose and only turn against
// each other (a pinion in its gear) are the machine's own contacts, never reported. A probe's
// measuring sphere (machine.yaml probe: sphere_parts) touching a part the scene adds is the
// measurement, not a collision: the stylus (sim/backend/stylus) reports its over-travel.

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "sim/model/machine_model.hpp"

namespace vmt::sim {

/// A cylinder a scene adds to the machine: along its link's z axis from z_m to z_m + length_m;
/// with inner_radius_m > 0 a tube (a bored section, the ring outside a face groove).
struct CylinderPart {
  std::string name;
  std::string link;
  double radius_m = 0, length_m = 0, z_m = 0;
  double inner_radius_m = 0;
};

struct CollisionPart {
  std::string name;  ///< the <collision name=""> (or its link's name and index)
  int link = -1;
  Eigen::Isometry3d X_LinkPart = Eigen::Isometry3d::Identity();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< bounding sphere, part frame, m
  double radius = 0;                                 ///< bounding sphere, m
  bool measures = false;  ///< a probe's measuring sphere: may touch the parts the scene adds
};

class CollisionWorld {
 public:
  /// Throws ModelError if an added part names a link the model lacks.
  CollisionWorld(const MachineModel& model, const std::vector<CylinderPart>& added = {});
  ~CollisionWorld();
  CollisionWorld(const CollisionWorld&) = delete;
  CollisionWorld& operator=(const CollisionWorld&) = delete;

  const MachineModel& model() const { return *model_; }
  int size() const { return static_cast<int>(parts_.size()); }
  const CollisionPart& part(int i) const { return parts_[i]; }
  /// Whether the pair's contact is the machine's own (see above), or one of them is set aside:
  /// never checked.
  bool MayTouch(int a, int b) const {
    return may_touch_[a * size() + b] || (a < machine_parts_ && aside_[a]) ||
           (b < machine_parts_ && aside_[b]) || (measuring_ && Measures(a, b));
  }
  /// A probe's measuring sphere and a part the scene added (the workpiece): their touching is
  /// the measurement on a measuring path (SetMeasuring), a collision on every other move.
  bool Measures(int a, int b) const {
    return (parts_[a].measures && b >= machine_parts_) ||
           (parts_[b].measures && a >= machine_parts_);
  }
  /// While on, the measuring spheres may touch the added parts (a probe's measuring path).
  void SetMeasuring(bool on) { measuring_ = on; }
  /// Sets a machine part aside (a chuck jaw while the spindle turns: an added part stands for
  /// the ring it sweeps) or back.
  void SetAside(int part, bool aside) { aside_[part] = aside; }
  bool aside(int part) const { return part < machine_parts_ && aside_[part]; }
  /// Whether the part is one the scene added (SetAdded), not the machine's.
  bool added(int part) const { return part >= machine_parts_; }

  /// Replaces the parts the scene added (the workpiece, as it is turned): the machine's parts
  /// stay, an added part the same as one before stays with its pairs, the others are built with
  /// their own-contact rule. The world must be posed again afterwards.
  void SetAdded(const std::vector<CylinderPart>& added);

  /// Poses every part for the joint positions (SI, one per model joint).
  void Pose(const std::vector<double>& q);
  /// Poses only parts a and b (and the links) for q, to the same bits as Pose; the other parts
  /// keep their poses. A pair's queries along a path need no more.
  void PosePair(const std::vector<double>& q, int a, int b);
  const Eigen::Isometry3d& X_WorldLink(int link) const { return X_WorldLink_[link]; }
  /// Clearance between two parts at the current poses, m; 0 when they touch or overlap. The
  /// nearest points (world, m) when wanted.
  double Distance(int a, int b, Eigen::Vector3d* point_a = nullptr,
                  Eigen::Vector3d* point_b = nullptr) const;
  /// A lower bound of Distance from the parts' world-aligned bounding boxes: cheap.
  double BoxDistance(int a, int b) const;
  /// The part's world-aligned bounding box at its current pose (the one BoxDistance uses), m.
  Eigen::AlignedBox3d Box(int i) const;
  /// Whether the two parts touch or overlap at the current poses; a contact point (world, m).
  bool Collide(int a, int b, Eigen::Vector3d* point = nullptr) const;
  int64_t queries() const { return queries_; }

  /// What checking changes: the added parts, the parts set aside, the measuring switch, the
  /// links' poses (a clearance proof reads them before it poses anything) and the count of
  /// queries. Kept to go back to (a run's in-memory snapshot); the solids are rebuilt from it.
  struct Saved {
    std::vector<CylinderPart> added;
    std::vector<char> aside;
    bool measuring = false;
    std::vector<Eigen::Isometry3d> X_WorldLink;
    int64_t queries = 0;
  };
  Saved Save() const { return {added_, aside_, measuring_, X_WorldLink_, queries_}; }
  void Restore(const Saved& saved);

 private:
  struct Fcl;
  const MachineModel* model_;
  std::vector<CollisionPart> parts_;
  std::unique_ptr<Fcl> fcl_;
  std::vector<char> may_touch_;
  std::vector<CylinderPart> added_;  ///< as SetAdded got them (parts_ after the machine's)
  int machine_parts_ = 0;            ///< the model's parts come first, the added ones after them
  std::vector<char> aside_;          ///< per machine part
  bool measuring_ = false;
  std::vector<Eigen::Isometry3d> X_WorldLink_;
  void PosePart(int i);
  mutable int64_t queries_ = 0;
};

}  // namespace vmt::sim
