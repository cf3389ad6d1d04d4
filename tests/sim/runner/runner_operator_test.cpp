// The operator station's inputs to a run: a key taken between two PLC cycles is recorded with
// its tick, and a run given the recorded steps repeats the live one to the same trace digest
// and events; what a PLC or the operator may not set is refused and changes nothing.

#include <gtest/gtest.h>

#include <string>

#include "../sim_test_support.hpp"
#include "sim/runner/runner.hpp"

namespace vmt::sim {
namespace {

using testing::ReadBytes;
using testing::SourcePath;

constexpr int64_t kCycle = 16;  // drive ticks per PLC cycle of the lathe's panel PLC

TEST(RunnerOperatorTest, AKeyTakenLiveIsReplayedToTheSameDigest) {
  const Scene scene = LoadScene(SourcePath("scenes/machine-panel.yaml"));
  RunOptions options;
  options.until_s = 1.0;
  options.out_dir = testing::OutputDir("operator-live");
  SceneRun live(scene, options);
  ASSERT_EQ(live.ticks_per_plc_cycle(), kCycle);
  while (!live.done()) {
    if (live.tick() == 5 * kCycle) {
      EXPECT_EQ(live.Operate("mCOOLANT", 1), "");
    }
    if (live.tick() == 6 * kCycle) {
      EXPECT_EQ(live.Operate("mCOOLANT", 0), "");
    }
    live.Step();
  }
  const RunResult a = live.Finish();
  ASSERT_EQ(live.operated().size(), 2u);
  EXPECT_EQ(live.operated()[0].tick, 5 * kCycle);
  EXPECT_EQ(live.operated()[1].signal, "mCOOLANT");

  RunOptions replay = options;
  replay.out_dir = testing::OutputDir("operator-replay");
  replay.operator_steps = ReadOperatorSteps(options.out_dir + "/operator.yaml");
  const RunResult b = RunScene(scene, replay);
  EXPECT_EQ(a.trace_digest, b.trace_digest);
  EXPECT_EQ(ReadBytes(options.out_dir + "/events.jsonl"),
            ReadBytes(replay.out_dir + "/events.jsonl"));

  // The key did something: without it the run differs (the coolant pump's valve).
  RunOptions none = options;
  none.out_dir.clear();
  EXPECT_NE(RunScene(scene, none).trace_digest, a.trace_digest);
}

TEST(RunnerOperatorTest, RefusesWhatNeitherThePlcNorTheOperatorSets) {
  const Scene scene = LoadScene(SourcePath("scenes/machine-panel.yaml"));
  SceneRun run(scene, RunOptions{});
  EXPECT_EQ(run.Operate("P00S.RUN", 1), "the NC writes P00S.RUN: a PLC cannot set it");
  EXPECT_EQ(run.Operate("IDOOR_OPEN", 1),
            "IDOOR_OPEN is a sensor of the machine: a PLC cannot set it");
  EXPECT_EQ(run.Operate("nothing", 1), "no signal nothing");
  // The scene's own PLC program writes the NC's control signals.
  EXPECT_EQ(run.Operate("P00C.SBL", 1),
            "the scene's PLC program writes P00C.SBL: press the operator's keys instead");
  EXPECT_NE(run.Operate("mAUTO", 7), "");  // a key is BOOL
  EXPECT_TRUE(run.operated().empty());
  EXPECT_EQ(run.Operate("mAUTO", 1), "");
  EXPECT_EQ(run.operated().size(), 1u);
}

TEST(RunnerOperatorTest, AStepThatCannotBeTakenFailsTheReplay) {
  const Scene scene = LoadScene(SourcePath("scenes/machine-panel.yaml"));
  RunOptions options;
  options.until_s = 0.1;
  options.operator_steps = {{16, "P00S.RUN", 1, ""}};
  const RunResult r = RunScene(scene, options);
  ASSERT_FALSE(r.ok());
  bool told = false;
  for (const std::string& f : r.failures)
    told = told || f == "operator step at tick 16: the NC writes P00S.RUN: a PLC cannot set it";
  EXPECT_TRUE(told) << ::testing::PrintToString(r.failures);
}

}  // namespace
}  // namespace vmt::sim
