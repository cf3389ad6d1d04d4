// Snapshots on events: which recorded events are collisions, probe latches and NC errors, the
// files their pictures get, and a run that pictures them, lists them in summary.json and
// events.jsonl like time snapshots, and writes the same bytes twice (once rendering them after
// the run, as vmt serve --realtime does).

#include "sim/runner/event_snapshots.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../sim_test_support.hpp"
#include "sim/runner/runner.hpp"

namespace vmt::sim {
namespace {

TEST(EventSnapshotsTest, WhichEventsCount) {
  EXPECT_EQ(SnapshotEventOf({{"event", "path_guard"}, {"clear", false}}),
            SnapshotEvent::kCollision);
  EXPECT_EQ(SnapshotEventOf({{"event", "path_guard"}, {"clear", true}}), SnapshotEvent::kNone);
  EXPECT_EQ(SnapshotEventOf({{"event", "stylus"}, {"state", "over_travel"}}),
            SnapshotEvent::kCollision);
  EXPECT_EQ(SnapshotEventOf({{"event", "probe_latch"}, {"drive", "X"}}),
            SnapshotEvent::kProbeLatch);
  EXPECT_EQ(SnapshotEventOf({{"event", "nc"}, {"state", "error"}}), SnapshotEvent::kError);
  EXPECT_EQ(SnapshotEventOf({{"event", "nc"}, {"state", "hold"}}), SnapshotEvent::kNone);
  EXPECT_EQ(SnapshotEventOf({{"event", "snapshot"}, {"on", "error"}}), SnapshotEvent::kNone);
}

TEST(EventSnapshotsTest, FileNames) {
  SnapshotSpec s;
  s.on = SnapshotEvent::kProbeLatch;
  s.camera = "work";
  EXPECT_EQ(EventSnapshotFile(s, 2, 4.01225), "probe_latch_2_4.0123s_work.png");
  s.on = SnapshotEvent::kCollision;
  EXPECT_EQ(EventSnapshotFile(s, 1, 0.5 - 1e-12), "collision_1_0.5000s_work.png");
}

// measure-move-collision: PathGuard finds the MOVE into the part (a collision) and the NC stops
// with 507 (an error) in the same NC cycle; no probe ever latches.
TEST(EventSnapshotsTest, ARunPicturesItsEvents) {
  Scene scene = LoadScene(testing::SourcePath("scenes/measure-move-collision.yaml"));
  scene.snapshots.clear();
  for (SnapshotEvent on :
       {SnapshotEvent::kCollision, SnapshotEvent::kError, SnapshotEvent::kProbeLatch}) {
    SnapshotSpec s;
    s.on = on;
    s.limit = 3;
    s.camera = "work";
    s.width = 96;
    s.height = 72;
    scene.snapshots.push_back(s);
  }
  RunOptions options;
  options.until_s = 1.0;
  std::vector<std::string> runs;
  for (const char* name : {"event_snapshots_a", "event_snapshots_b"}) {
    options.out_dir = testing::OutputDir(name);
    // The second run renders its pictures after the run (vmt serve --realtime): the same.
    options.snapshots_after_run = runs.size() == 1;
    const RunResult r = RunScene(scene, options);
    ASSERT_EQ(r.snapshot_files.size(), 2u);  // one collision, one error, within the limits
    runs.push_back(options.out_dir);
  }
  // Each pictured at the tick its event was recorded in.
  std::vector<std::string> files;
  std::vector<double> shot_t;
  double collision_t = -1, error_t = -1;
  std::ifstream events(runs[0] + "/events.jsonl");
  std::string line;
  while (std::getline(events, line)) {
    const auto e = nlohmann::json::parse(line);
    if (e["event"] == "path_guard" && !e["clear"].get<bool>() && collision_t < 0)
      collision_t = e["t"].get<double>();
    if (e["event"] == "nc" && e["state"] == "error" && error_t < 0) error_t = e["t"].get<double>();
    if (e["event"] != "snapshot") continue;
    EXPECT_EQ(e["n"], 1) << line;
    EXPECT_EQ(e["camera"], "work") << line;
    files.push_back(e["file"].get<std::string>());
    shot_t.push_back(e["t"].get<double>());
  }
  ASSERT_EQ(files.size(), 2u);
  EXPECT_TRUE(files[0].starts_with("collision_1_0.")) << files[0];
  EXPECT_TRUE(files[1].starts_with("error_1_0.")) << files[1];
  EXPECT_DOUBLE_EQ(shot_t[0], collision_t);
  EXPECT_DOUBLE_EQ(shot_t[1], error_t);
  EXPECT_EQ(testing::ReadBytes(runs[0] + "/events.jsonl"),
            testing::ReadBytes(runs[1] + "/events.jsonl"));
  const std::string summary = testing::ReadBytes(runs[0] + "/summary.json");
  for (const std::string& f : files) {
    EXPECT_NE(summary.find(runs[0] + "/" + f), std::string::npos) << summary;
    const std::string bytes = testing::ReadBytes(runs[0] + "/" + f);
    EXPECT_GT(bytes.size(), 100u) << f;
    EXPECT_EQ(bytes, testing::ReadBytes(runs[1] + "/" + f)) << f;  // deterministic
  }
}

// measure-shaft latches on X and Z at every contact: a limit pictures the first ones only.
TEST(EventSnapshotsTest, ALimitPicturesTheFirstOccurrences) {
  Scene scene = LoadScene(testing::SourcePath("scenes/measure-shaft.yaml"));
  scene.snapshots.clear();
  SnapshotSpec s;
  s.on = SnapshotEvent::kProbeLatch;
  s.limit = 3;
  s.camera = "work";
  s.width = 64;
  s.height = 48;
  scene.snapshots.push_back(s);
  RunOptions options;
  options.out_dir = testing::OutputDir("event_snapshots_limit");
  const RunResult r = RunScene(scene, options);
  ASSERT_EQ(r.snapshot_files.size(), 3u);
  for (int n = 1; n <= 3; ++n)
    EXPECT_NE(r.snapshot_files[n - 1].find("/probe_latch_" + std::to_string(n) + "_"),
              std::string::npos)
        << r.snapshot_files[n - 1];
}

}  // namespace
}  // namespace vmt::sim
