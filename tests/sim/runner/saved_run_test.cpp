// A run kept in memory (SceneRun::Save) and gone back to (Restore) runs on as it did: for every
// scene pinned on the kinematic backend, the run saved half-way, finished, restored and
// finished again gives the pinned trace digest both times, and the same expectations.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "../sim_test_support.hpp"
#include "sim/runner/runner.hpp"

namespace vmt::sim {
namespace {

using testing::SourcePath;

// The kinematic digest pinned for `scene` (tests/golden/<scene>/digest), "" if none.
std::string PinnedKinematic(const std::string& scene) {
  std::ifstream in(SourcePath("tests/golden/" + scene + "/digest"));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string backend, digest, more;
    if (fields >> backend >> digest && !(fields >> more) && backend == "kinematic") return digest;
  }
  return "";
}

std::vector<std::string> KinematicScenes() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(SourcePath("tests/golden"))) {
    const std::string name = entry.path().filename().string();
    if (!PinnedKinematic(name).empty() &&
        std::filesystem::exists(SourcePath("scenes/" + name + ".yaml")))
      names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

RunOptions Kinematic() {
  RunOptions o;
  o.backend = BackendKind::kKinematic;
  o.snapshots = false;
  return o;
}

std::vector<std::string> Outcomes(const RunResult& r) {
  std::vector<std::string> out = r.failures;
  for (const ExpectationResult& e : r.expectations)
    out.push_back(e.text + (e.passed ? " passed" : " failed"));
  return out;
}

class SavedRunTest : public ::testing::TestWithParam<std::string> {};

TEST_P(SavedRunTest, RestoredRunEndsAsPinned) {
  const std::string pinned = PinnedKinematic(GetParam());
  const Scene scene = LoadScene(SourcePath("scenes/" + GetParam() + ".yaml"));
  SceneRun run(scene, Kinematic());
  while (!run.done() && run.time_s() < run.end_s() / 2) run.Step();
  const auto saved = run.Save();
  while (!run.done()) run.Step();
  const RunResult first = run.Finish();
  EXPECT_EQ(first.trace_digest, pinned);

  run.Restore(*saved);
  EXPECT_FALSE(run.done());
  while (!run.done()) run.Step();
  const RunResult again = run.Finish();
  EXPECT_EQ(again.trace_digest, pinned);
  EXPECT_EQ(Outcomes(again), Outcomes(first));
  EXPECT_EQ(again.final_joint_positions, first.final_joint_positions);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SavedRunTest, ::testing::ValuesIn(KinematicScenes()),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// One saved state serves any number of returns, from any later point, also from a run that was
// itself restored: a study's cases each go back to the same interruption.
TEST(SavedRunTest, OneSaveServesManyReturns) {
  const Scene scene = LoadScene(SourcePath("scenes/repos-automatic.yaml"));
  SceneRun run(scene, Kinematic());
  while (run.time_s() < run.end_s() * 0.3) run.Step();
  const auto saved = run.Save();
  const double saved_at = run.time_s();
  for (const double until : {0.9, 0.5, 0.31}) {
    while (!run.done() && run.time_s() < run.end_s() * until) run.Step();
    run.Restore(*saved);
    EXPECT_EQ(run.time_s(), saved_at);
  }
  while (!run.done()) run.Step();
  EXPECT_EQ(run.Finish().trace_digest, PinnedKinematic("repos-automatic"));
}

// What Save() refuses with, "" if it saved the run.
std::string SaveRefusal(SceneRun& run) {
  try {
    (void)run.Save();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(SavedRunTest, PhysicsRunHasNoCopy) {
  const Scene scene = LoadScene(SourcePath("scenes/turning.yaml"));
  RunOptions o;
  o.backend = BackendKind::kPhysics;
  o.snapshots = false;
  SceneRun run(scene, o);
  run.Step();
  EXPECT_THAT(SaveRefusal(run), ::testing::HasSubstr("physics backend"));
}

TEST(SavedRunTest, RunWritingItsFilesHasNoCopy) {
  const Scene scene = LoadScene(SourcePath("scenes/repos-automatic.yaml"));
  RunOptions o = Kinematic();
  o.out_dir = testing::OutputDir("saved_run_writing");
  SceneRun run(scene, o);
  run.Step();
  EXPECT_THAT(SaveRefusal(run), ::testing::HasSubstr("writes its files"));
  (void)run.Finish();
}

}  // namespace
}  // namespace vmt::sim
