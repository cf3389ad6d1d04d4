#pragma once
// A study case's picture at its first contact: the machine posed where the refused move would
// first touch (the axes at the contact position, a chuck jaw turned to the contact), the workpiece
// as the tools had turned it, the two parts that meet drawn magenta and a cyan cross at the contact
// point, seen by the scene's camera turned to look at that point. PathGuard refuses a move before
// it starts, so the case's own pictures would show the parts apart; this one shows where they meet.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "render/image.hpp"
#include "sim/collision/collision_world.hpp"
#include "sim/scene/scene.hpp"
#include "sim/study/case_runner.hpp"

namespace vmt::sim::study {

/// What the case's run leaves for its picture: the joint positions the machine stood at when
/// the move was refused (it stays there) and the workpiece as turned then.
struct ContactStage {
  std::vector<double> joints;       ///< m | rad, one per model joint
  std::vector<CylinderPart> stock;  ///< the turned workpiece; empty: the scene's workpiece
};

/// `look`: the camera (a name of the scene's) and the picture's size. Throws
/// std::runtime_error when the scene has no such camera or the renderer fails.
render::Image ContactImage(const Scene& scene, const ContactStage& stage, const CaseResult& r,
                           const SnapshotSpec& look);

}  // namespace vmt::sim::study
