// The rotary axis' position across changeovers, on both headstocks: lathe-c1 (C servo through
// clutch K, its drive modulo 360 on the spindle's encoder) and lathe-c2 (C is S1's rotary axis
// designation; S1 modulo 360). A main spindle with rotary axis capability is an unlimited rotary
// axis (C-axis manual 2.2): rotary axis mode starts where the spindle stopped, within one turn,
// and the program's C counts from there. The NC interpolates an absolute C target from that
// start as programmed (no shortest-way choice; C-270 turns a whole turn back); the position
// indication shows 0..360.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "../scene_trace_support.hpp"
#include "sim/runner/runner.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

struct Machine {
  const char* name;   ///< lathe-c1 | lathe-c2
  const char* drive;  ///< the drive that carries C: C on c1, S1 on c2
};

constexpr Machine kC1{"lathe-c1", "C"}, kC2{"lathe-c2", "S1"};

struct ProgramRun {
  RunResult result;
  testing::Trace trace;
  std::vector<testing::Changeover> changeovers;
};

/// `program` (MTC200, one block per line, line 1 first) on `machine`'s physics backend, with the
/// machine's own changeover PLC (c1) or the runner's immediate acknowledgement (c2).
ProgramRun RunProgram(const Machine& machine, const std::string& name, const std::string& program,
                      double duration_s) {
  const std::string dir = testing::OutputDir(std::string("positions_") + machine.name + "_" + name);
  std::ofstream(dir + "/program.mtc") << program;
  std::ofstream(dir + "/scene.yaml")
      << "scene: " << name << "\n"
      << "model: " << testing::SourcePath(std::string("models/") + machine.name + "/machine.yaml")
      << "\nbackend: physics\nduration: " << duration_s
      << "\ninitial: {Z: 300, X: 150, T: 0, W: 200}\n"
      << "nc: {program: program.mtc}\n"
      << "timeline:\n  - nc: start\n  - wait_until: {nc: ended, timeout: " << duration_s - 0.5
      << "}\nexpect:\n  - {nc: ended}\n";
  const Scene scene = LoadScene(dir + "/scene.yaml");
  RunOptions options;
  options.snapshots = false;
  options.out_dir = dir + "/out";
  ProgramRun run;
  run.result = RunScene(scene, options);
  run.trace = testing::ReadTrace(options.out_dir);
  run.changeovers = testing::Changeovers(options.out_dir);
  return run;
}

double Mod360(double a) { return a - 360 * std::floor(a / 360); }

/// The run's one changeover to rotary axis mode, completed; null if there is none.
const testing::Changeover* RotaryChangeover(const ProgramRun& run) {
  const testing::Changeover* found = nullptr;
  for (const testing::Changeover& c : run.changeovers)
    if (c.target == "rotary") {
      if (found || c.end_s < 0) return nullptr;
      found = &c;
    }
  return found;
}

class HeadstockPositionsTest : public ::testing::TestWithParam<Machine> {};

// 50 turns in spindle mode, then G90 C90: the rotary axis starts within one turn (the drive's
// modulo 360) and travels less than a turn to 90, instead of unwinding the 50 turns.
TEST_P(HeadstockPositionsTest, AbsoluteTargetAfterManyTurnsTravelsLessThanATurn) {
  const Machine& m = GetParam();
  const ProgramRun run = RunProgram(m, "endless",
                                    "N0010 M19 S0\n"
                                    "N0020 M03 S600\n"
                                    "N0030 G04 F5\n"
                                    "N0040 M05\n"
                                    "N0050 G01 G90 C90 F7200\n"
                                    "N0060 RET\n",
                                    20);
  ASSERT_TRUE(run.result.ok()) << ::testing::PrintToString(run.result.failures);
  const testing::Trace& t = run.trace;
  const std::string cmd = std::string(m.drive) + ".cmd", pos = std::string(m.drive) + ".pos";
  // The spindle ran about 50 turns (600 rpm for 5 s).
  double turns = 0;
  for (size_t i = 1; i < t.size(); ++i)
    if (t["nc.line"][i] <= 4) turns += std::abs(t["S1.vel"][i]) * (t["t"][i] - t["t"][i - 1]) / 360;
  EXPECT_GT(turns, 45);
  const testing::Changeover* rotary = RotaryChangeover(run);
  ASSERT_NE(rotary, nullptr);
  const size_t from = t.RowAt(rotary->end_s);
  const size_t last = t.size() - 1;
  const double start = t[cmd][from];
  EXPECT_GE(start, 0);
  EXPECT_LT(start, 360) << "rotary axis mode starts within one turn";
  EXPECT_LT(std::abs(t[cmd][last] - start), 360) << "C unwound the spindle's turns";
  EXPECT_NEAR(t[cmd][last], 90, 1e-6);
  EXPECT_NEAR(Mod360(t[pos][last]), 90, 0.01);
}

// M3 S100, dwell, M5, G91 C10: C ends 10 deg from where the spindle stopped, not 10 deg from
// where the program last put C; the blocks after it count on from there, G90 sets it again.
TEST_P(HeadstockPositionsTest, IncrementRightAfterAChangeoverCountsFromWhereTheSpindleStopped) {
  const Machine& m = GetParam();
  const ProgramRun run = RunProgram(m, "incremental",
                                    "N0010 M19 S0\n"
                                    "N0020 M03 S100\n"
                                    "N0030 G04 F1.37\n"
                                    "N0040 M05\n"
                                    "N0050 G01 G91 C10 F3600\n"
                                    "N0060 C10\n"
                                    "N0070 G90 C45\n"
                                    "N0080 G91 C-20\n"
                                    "N0090 RET\n",
                                    20);
  ASSERT_TRUE(run.result.ok()) << ::testing::PrintToString(run.result.failures);
  const testing::Trace& t = run.trace;
  const std::string cmd = std::string(m.drive) + ".cmd", pos = std::string(m.drive) + ".pos";
  const testing::Changeover* rotary = RotaryChangeover(run);
  ASSERT_NE(rotary, nullptr);
  // Where rotary axis mode took the spindle over.
  const double stopped = t[cmd][t.RowAt(rotary->end_s)];
  ASSERT_GT(std::abs(std::remainder(stopped, 360.0)), 1)
      << "the spindle stopped near 0: the test would not tell the stale position from the actual";
  EXPECT_NEAR(Mod360(t[pos][t.RowAt(rotary->end_s)]), Mod360(stopped), 0.05);
  // The drive's setpoint in the last trace row of a block: the fine interpolation between NC
  // cycle points (a block ends inside a cycle, the next runs on from there), within a cycle's
  // travel at 60 deg/s of the block's end; the takeover row, within one of the changeover's end.
  // Counted from where the program last put C (0), N0050 would end about 100 deg away.
  const auto end_of = [&](int line) { return t[cmd][t.RowsOfLine(line).back()]; };
  EXPECT_NEAR(end_of(5), stopped + 10, 0.15);
  EXPECT_NEAR(end_of(6), stopped + 20, 0.15);
  EXPECT_NEAR(end_of(7), 45, 0.15);
  const size_t last = t.size() - 1;
  EXPECT_NEAR(t[cmd][last], 25, 1e-6);
  EXPECT_NEAR(Mod360(t[pos][last]), 25, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Machines, HeadstockPositionsTest, ::testing::Values(kC1, kC2),
                         [](const auto& info) {
                           return std::string(info.param.name[7] == '1' ? "c1" : "c2");
                         });

}  // namespace
}  // namespace vmt::sim
