// A run writes its trace, events and summary; a snapshot is the same bytes every time, and the
// default scene's picture matches its golden image. That a scene gives the same trace digest
// every time is checked against the digests pinned in tests/golden/<scene>/digest.

#include "sim/runner/runner.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <vector>

#include "render/image.hpp"
#include "render/image_compare.hpp"
#include "../sim_test_support.hpp"
#include "sim/runner/scene_renderer.hpp"

namespace vmt::sim {
namespace {

using ::testing::HasSubstr;
using testing::OutputDir;
using testing::SourcePath;

TEST(RunnerTest, DefaultScenePassesAndWritesItsOutputs) {
  const Scene scene = LoadScene(SourcePath("scenes/drive-timeline.yaml"));
  RunOptions options;
  options.out_dir = OutputDir("default");
  const RunResult r = RunScene(scene, options);
  EXPECT_TRUE(r.ok()) << ::testing::PrintToString(r.failures);
  EXPECT_EQ(r.snapshot_files.size(), scene.snapshots.size());
  const std::string summary = testing::ReadBytes(options.out_dir + "/summary.json");
  EXPECT_THAT(summary, HasSubstr("\"trace_digest\": \"" + r.trace_digest + "\""));
  EXPECT_THAT(summary, HasSubstr("\"real_time_factor\""));
  EXPECT_THAT(testing::ReadBytes(options.out_dir + "/trace.csv"), HasSubstr("t,Z.cmd,Z.pos,Z.vel"));
  EXPECT_THAT(testing::ReadBytes(options.out_dir + "/events.jsonl"),
              HasSubstr("\"event\":\"clutch\""));
}

TEST(RunnerTest, BackendsGiveDifferentTracesButTheSameEndState) {
  const Scene scene = LoadScene(SourcePath("scenes/drive-timeline.yaml"));
  RunOptions physics, kinematic;
  physics.snapshots = kinematic.snapshots = false;
  physics.backend = BackendKind::kPhysics;
  kinematic.backend = BackendKind::kKinematic;
  const RunResult p = RunScene(scene, physics), k = RunScene(scene, kinematic);
  EXPECT_NE(p.trace_digest, k.trace_digest);
  EXPECT_TRUE(p.ok());
  EXPECT_TRUE(k.ok()) << ::testing::PrintToString(k.failures);
}

TEST(RunnerTest, FailedExpectationAndTimeoutAreReported) {
  const std::string dir = OutputDir("failing");
  const std::string path = dir + "/failing.yaml";
  std::ofstream(path) << "scene: failing\nmodel: " << SourcePath("models/lathe-c1/machine.yaml")
                      << "\nbackend: kinematic\nduration: 1\n"
                         "timeline:\n  - move: {axis: Z, to: 100, feed: 6000}\n"
                         "  - wait_until: {input: IROTMODE, timeout: 0.2}\n"
                         "expect:\n  - {at: 0.5, axis: Z, position: 50, tol: 0.01}\n";
  const RunResult r = RunScene(LoadScene(path), {});
  ASSERT_EQ(r.failures.size(), 2u);
  EXPECT_THAT(r.failures[0], HasSubstr("expect[0]: Z position 50"));
  EXPECT_THAT(r.failures[1], HasSubstr("timeline[1]: wait until input=IROTMODE"));
  EXPECT_THAT(r.failures[1], HasSubstr("timed out"));
}

// An external PLC (vmt serve): the client_gone step reaches the callback once, and a PLC
// declared lost drops what it wrote and stops the NC with 505, as the embedded watchdog does.
TEST(RunnerTest, ExternalPlcLostDropsItsOutputsAndStopsTheNc) {
  const Scene scene = LoadScene(SourcePath("scenes/fault-plc-client-gone.yaml"));
  {
    std::vector<double> gone_at;
    const SceneRun* at = nullptr;
    RunOptions o;
    o.external_plc = true;
    o.on_plc_client_gone = [&] { gone_at.push_back(at->time_s()); };
    SceneRun run(scene, o);
    at = &run;
    while (!run.done()) run.Step();
    ASSERT_EQ(gone_at.size(), 1u);
    EXPECT_NEAR(gone_at[0], 1.0, 1e-9);
  }

  RunOptions options;
  options.external_plc = true;
  options.out_dir = OutputDir("external_plc_lost");
  SceneRun run(scene, options);
  control::gateway::SignalImage& image = *run.image();
  const int repos = image.Require("P00C.REPOS"), errnr = image.Require("P00S.ERRNR");
  const int run_signal = image.Require("P00S.RUN");
  while (run.time_s() < 0.2) run.Step();
  image.SetBool(repos, true);  // as the external PLC writes it
  run.PlcLost("Modbus: no request for 100 ms, the PLC link is lost");
  EXPECT_FALSE(image.Bool(repos));
  for (int i = 0; i < 8; ++i) run.Step();  // an NC cycle shows the error on the gateway
  EXPECT_EQ(image.Int(errnr), 505);
  EXPECT_FALSE(image.Bool(run_signal));
  run.PlcRunning();
  image.SetBool(repos, true);  // the PLC writes again; the NC stays in its error
  while (!run.done()) run.Step();
  run.Finish();
  const std::string events = testing::ReadBytes(options.out_dir + "/events.jsonl");
  EXPECT_THAT(events, HasSubstr("{\"t\":0.2,\"event\":\"plc\",\"state\":\"stopped\","
                                "\"reason\":\"Modbus: no request for 100 ms, the PLC link is "
                                "lost\"}"));
  EXPECT_THAT(events, HasSubstr("\"event\":\"plc\",\"state\":\"running\"}"));
  EXPECT_THAT(events, HasSubstr("\"state\":\"error\",\"error\":\"Modbus: no request for 100 ms"));
  EXPECT_THAT(events, HasSubstr("\"name\":\"P00S.ERRNR\",\"value\":505.0}"));
}

TEST(SnapshotTest, SameSnapshotSameBytes) {
  const Scene scene = LoadScene(SourcePath("scenes/drive-timeline.yaml"));
  const std::string a = OutputDir("snap_a"), b = OutputDir("snap_b");
  RunOptions options;
  options.until_s = 3.2;
  options.out_dir = a;
  RunScene(scene, options);
  options.out_dir = b;
  RunScene(scene, options);
  ASSERT_FALSE(scene.snapshots.empty());
  for (const SnapshotSpec& s : scene.snapshots) {
    const std::string bytes = testing::ReadBytes(a + "/" + s.file);
    EXPECT_GT(bytes.size(), 1000u);
    EXPECT_EQ(bytes, testing::ReadBytes(b + "/" + s.file)) << s.file;
  }
}

// The golden picture was rendered on this project's machines (llvmpipe); a small tolerance
// absorbs rounding differences between CPU instruction sets, not changes of the scene.
TEST(SnapshotTest, DefaultSceneMatchesGolden) {
  const Scene scene = LoadScene(SourcePath("scenes/drive-timeline.yaml"));
  const std::string dir = OutputDir("golden");
  RunOptions options;
  options.until_s = 3.2;
  options.out_dir = dir;
  RunScene(scene, options);
  for (const char* name : {"iso_3.2s.png", "work_3.2s.png"}) {
    const std::string golden = SourcePath(std::string("tests/golden/drive-timeline/") + name);
    const render::Image expected = render::ReadPng(golden);
    const render::Image actual = render::ReadPng(dir + "/" + name);
    // The project's tolerance (render::kGoldenChannelTolerance, kGoldenAllowedFraction).
    const render::CompareResult c = render::CompareImages(expected, actual);
    if (!c.equal && !c.size_mismatch) render::WritePng(dir + "/diff_" + std::string(name), c.diff);
    EXPECT_TRUE(c.equal) << name << ": " << c.differing_pixels << " pixels differ, max delta "
                         << c.max_channel_delta << "; see " << dir;
  }
}

}  // namespace
}  // namespace vmt::sim
