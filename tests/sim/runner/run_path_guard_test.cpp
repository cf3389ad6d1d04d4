// PathGuard of a run on its own: without a workpiece it guards the machine alone; with one the
// stock's cylinders are parts of its world, its sweep follows the workpiece's link, and a
// machine standing still neither cuts nor turns the spindle.
#include "sim/runner/run_path_guard.hpp"

#include <gtest/gtest.h>

#include "../sim_test_support.hpp"
#include "sim/runner/make_backend.hpp"

namespace vmt::sim {
namespace {

int AddedParts(CollisionWorld& world) {
  int added = 0;
  for (int i = 0; i < world.size(); ++i) added += world.added(i) ? 1 : 0;
  return added;
}

TEST(RunPathGuard, WithoutAWorkpieceItGuardsTheMachineAlone) {
  const Scene scene = LoadScene(testing::SourcePath("scenes/jog.yaml"));
  Workpiece none;
  const auto backend = MakeBackend(BackendKind::kKinematic, *scene.model, scene.initial);
  RunPathGuard guard(*scene.model, none, *backend);
  EXPECT_EQ(guard.cutter(), nullptr);
  EXPECT_EQ(AddedParts(guard.guard().world()), 0);
  guard.FollowSpindle(0.001, 0.001);
  EXPECT_EQ(guard.stock_cuts(), 0);
}

TEST(RunPathGuard, TheWorkpieceIsPartOfItsWorldAndStandingStillCutsNothing) {
  const Scene scene = LoadScene(testing::SourcePath("scenes/block-search-backward.yaml"));
  ASSERT_TRUE(scene.workpiece.present);
  const auto backend = MakeBackend(BackendKind::kKinematic, *scene.model, scene.initial);
  RunPathGuard guard(*scene.model, scene.workpiece, *backend);
  ASSERT_NE(guard.cutter(), nullptr);
  EXPECT_GT(AddedParts(guard.guard().world()), 0);
  EXPECT_GE(guard.guard().sweep().joint, 0);  // the workpiece turns with the spindle
  for (int cycle = 1; cycle <= 3; ++cycle) guard.FollowSpindle(cycle * 0.001, 0.001);
  EXPECT_EQ(guard.stock_cuts(), 0);
}

}  // namespace
}  // namespace vmt::sim
