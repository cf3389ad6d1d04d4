// The C-axis manual's program "Spindle/C Axis Switching" (1.2) on both headstocks: lathe-c1 (a
// separate C servo through dog clutch K, manual 3) and lathe-c2 (a main spindle drive with
// rotary axis capability, manual 2). For the program the two are the same machine (1.1: "It is
// irrelevant whether or not a separate servo drive exists"): the machining block N0077 follows
// the same path, and the program ends in the same place. Only the changeover differs: c1 brings
// the clutch in mechanically, with hunting; c2 only switches its drive's parameter set.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../scene_trace_support.hpp"
#include "sim/runner/runner.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using testing::Changeover;
using testing::Trace;

constexpr const char* kProgram = "tests/control/nc/seed_programs/caxis_spindle_switching.mtc";
constexpr const char* kSpiralGroove = "scenes/nc/caxis_spiral_groove.mtc";

/// The source line of the block numbered `block` ("N0077") in `program`.
int LineOf(const std::string& block, const char* program = kProgram) {
  std::ifstream in(testing::SourcePath(program));
  std::string line;
  for (int n = 1; std::getline(in, line); ++n)
    if (line.rfind(block, 0) == 0) return n;
  return -1;
}

struct SwitchingRun {
  RunResult result;
  Trace trace;
  std::vector<Changeover> changeovers;
};

SwitchingRun RunSwitching(const std::string& scene_file, BackendKind backend,
                          const std::string& out) {
  const Scene scene = LoadScene(testing::SourcePath(scene_file));
  RunOptions options;
  options.backend = backend;
  options.snapshots = false;
  options.out_dir = testing::OutputDir(out);
  SwitchingRun run;
  run.result = RunScene(scene, options);
  run.trace = testing::ReadTrace(options.out_dir);
  run.changeovers = testing::Changeovers(options.out_dir);
  return run;
}

// On the physics backend, the scenes' own: lathe-c1's clutch meshes there with its tooth
// dynamics (the kinematic backend's ideal clutch snaps into mesh, which is not what this compares).
TEST(HeadstockMachinesTest, SameProgramSamePathDifferentChangeover) {
  const SwitchingRun c1 =
      RunSwitching("scenes/c-axis-switching.yaml", BackendKind::kPhysics, "switching_c1");
  const SwitchingRun c2 =
      RunSwitching("scenes/c-axis-switching-c2.yaml", BackendKind::kPhysics, "switching_c2");
  ASSERT_TRUE(c1.result.ok()) << ::testing::PrintToString(c1.result.failures);
  ASSERT_TRUE(c2.result.ok()) << ::testing::PrintToString(c2.result.failures);

  // The following error bound: the lag v / Kv of the slower position loop (G06's feed-forward
  // takes most of it away, what stays is within it). C: 22.6 deg/s, Kv 30 (c2's set 1) or the
  // c1 servo's; X: 3.35 mm/s at Kv 40.
  const Scene c1_scene = LoadScene(testing::SourcePath("scenes/c-axis-switching.yaml"));
  const MachineModel& m1 = *c1_scene.model;
  const double kv_c = std::min(30.0, m1.drives[m1.DriveIndex("C")].kv_per_s);
  const double c_bound = 22.6 / kv_c, x_bound = 3.35 / 40;

  // N0077 G01 G91 X40 C-270 RX50 F1200: the same interpolated path, block time for block time.
  // C is drive C on c1 and drive S1 (C its rotary axis designation) on c2.
  const int n0077 = LineOf("N0077");
  ASSERT_GT(n0077, 0);
  const std::vector<size_t> r1 = c1.trace.RowsOfLine(n0077), r2 = c2.trace.RowsOfLine(n0077);
  ASSERT_GT(r1.size(), 1000u);
  ASSERT_NEAR(static_cast<double>(r1.size()), static_cast<double>(r2.size()), 2);
  const size_t n = std::min(r1.size(), r2.size());
  const double c1_0 = c1.trace["C.cmd"][r1[0]], c2_0 = c2.trace["S1.cmd"][r2[0]];
  const double x1_0 = c1.trace["X.cmd"][r1[0]], x2_0 = c2.trace["X.cmd"][r2[0]];
  double worst_cmd_c = 0, worst_cmd_x = 0, worst_pos_c = 0, worst_pos_x = 0;
  for (size_t k = 0; k < n; ++k) {
    const size_t i = r1[k], j = r2[k];
    worst_cmd_c = std::max(
        worst_cmd_c, std::abs((c1.trace["C.cmd"][i] - c1_0) - (c2.trace["S1.cmd"][j] - c2_0)));
    worst_cmd_x = std::max(worst_cmd_x,
                           std::abs((c1.trace["X.cmd"][i] - x1_0) - (c2.trace["X.cmd"][j] - x2_0)));
    // c1's C reads the spindle's encoder modulo 360 (its position within one turn).
    worst_pos_c = std::max(
        worst_pos_c, std::abs(std::remainder(
                         (c1.trace["C.pos"][i] - c1_0) - (c2.trace["S1.pos"][j] - c2_0), 360.0)));
    worst_pos_x = std::max(worst_pos_x,
                           std::abs((c1.trace["X.pos"][i] - x1_0) - (c2.trace["X.pos"][j] - x2_0)));
  }
  // The block covers X40 C-270 on both.
  EXPECT_NEAR(c1.trace["C.cmd"][r1[n - 1]] - c1_0, -270, 0.5);
  EXPECT_NEAR(c2.trace["S1.cmd"][r2[n - 1]] - c2_0, -270, 0.5);
  EXPECT_LT(worst_cmd_c, 0.01) << "interpolated C paths differ";
  EXPECT_LT(worst_cmd_x, 0.001) << "interpolated X paths differ";
  EXPECT_LT(worst_pos_c, c_bound) << "actual C paths differ by more than the following error bound";
  EXPECT_LT(worst_pos_x, x_bound) << "actual X paths differ by more than the following error bound";

  // The program ends in the same place: X120 Z200, the spindle at 1200 rpm.
  const size_t e1 = c1.trace.size() - 1, e2 = c2.trace.size() - 1;
  EXPECT_NEAR(c1.trace["X.pos"][e1], c2.trace["X.pos"][e2], 0.01);
  EXPECT_NEAR(c1.trace["Z.pos"][e1], c2.trace["Z.pos"][e2], 0.01);
  EXPECT_NEAR(c1.trace["S1.rpm"][e1], c2.trace["S1.rpm"][e2], 2);

  // Two changeovers each, to rotary axis mode (N0070) and back (N0100). c1's to rotary axis
  // mode brakes the spindle, hunts and brings clutch K in; c2's only brakes and switches the
  // drive's parameter set: several times faster.
  ASSERT_EQ(c1.changeovers.size(), 2u);
  ASSERT_EQ(c2.changeovers.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(c1.changeovers[k].target, k == 0 ? "rotary" : "spindle");
    EXPECT_EQ(c2.changeovers[k].target, c1.changeovers[k].target);
    EXPECT_GT(c1.changeovers[k].end_s, 0);
    EXPECT_GT(c2.changeovers[k].end_s, 0);
    EXPECT_LT(c2.changeovers[k].duration_s(), c1.changeovers[k].duration_s())
        << "changeover " << k << ": c2 " << c2.changeovers[k].duration_s() << " s, c1 "
        << c1.changeovers[k].duration_s() << " s";
  }
  EXPECT_LT(3 * c2.changeovers[0].duration_s(), c1.changeovers[0].duration_s())
      << "to rotary axis mode: c2 " << c2.changeovers[0].duration_s() << " s, c1 "
      << c1.changeovers[0].duration_s() << " s";
}

// The manual's spiral groove (1.2, Fig. 1-3) on both headstocks. For the program they are the same
// machine (1.1): the blocks after the changeover -- lowering the cutter, the groove with RX50,
// lifting it -- take the same time and follow the same X/Z/C path, and the program ends in the
// same place; only the changeover in N0144 (c1: clutch K with hunting, c2: the drive's
// parameter set) differs, and with it when the blocks after it start.
TEST(HeadstockMachinesTest, SpiralGrooveSamePathsAndBlockTimes) {
  const SwitchingRun c1 =
      RunSwitching("scenes/c-axis-spiral-groove.yaml", BackendKind::kPhysics, "spiral_c1");
  const SwitchingRun c2 =
      RunSwitching("scenes/c-axis-spiral-groove-c2.yaml", BackendKind::kPhysics, "spiral_c2");
  ASSERT_TRUE(c1.result.ok()) << ::testing::PrintToString(c1.result.failures);
  ASSERT_TRUE(c2.result.ok()) << ::testing::PrintToString(c2.result.failures);
  const Scene c1_scene = LoadScene(testing::SourcePath("scenes/c-axis-spiral-groove.yaml"));
  const MachineModel& m1 = *c1_scene.model;
  // Following error bounds v / Kv of the slower loop (G06 takes most of the lag away): C at
  // 22.7 deg/s, X at 2.53 mm/s and Z at the feed of N0145, 500 mm/min.
  const double kv_c = std::min(30.0, m1.drives[m1.DriveIndex("C")].kv_per_s);
  const double bound[3] = {22.8 / kv_c, 2.53 / 40, 8.34 / 40};
  const char* c1_axes[3] = {"C", "X", "Z"};
  const char* c2_axes[3] = {"S1", "X", "Z"};

  for (const char* block : {"N0145", "N0146", "N0147"}) {
    const int line = LineOf(block, kSpiralGroove);
    ASSERT_GT(line, 0) << block;
    const std::vector<size_t> r1 = c1.trace.RowsOfLine(line), r2 = c2.trace.RowsOfLine(line);
    ASSERT_GT(r1.size(), 100u) << block;
    // The block time: the same within two NC cycles (8 trace rows of 250 us).
    EXPECT_NEAR(static_cast<double>(r1.size()), static_cast<double>(r2.size()), 8) << block;
    const size_t n = std::min(r1.size(), r2.size());
    for (int a = 0; a < 3; ++a) {
      const std::string cmd1 = std::string(c1_axes[a]) + ".cmd",
                        cmd2 = std::string(c2_axes[a]) + ".cmd";
      const std::string pos1 = std::string(c1_axes[a]) + ".pos",
                        pos2 = std::string(c2_axes[a]) + ".pos";
      double worst_cmd = 0, worst_pos = 0;
      for (size_t k = 0; k < n; ++k) {
        const size_t i = r1[k], j = r2[k];
        worst_cmd = std::max(worst_cmd, std::abs(c1.trace[cmd1][i] - c2.trace[cmd2][j]));
        // Both C drives report modulo 360.
        const double d = c1.trace[pos1][i] - c2.trace[pos2][j];
        worst_pos = std::max(worst_pos, std::abs(a == 0 ? std::remainder(d, 360.0) : d));
      }
      EXPECT_LT(worst_cmd, a == 0 ? 0.01 : 0.001) << block << ": interpolated " << c1_axes[a];
      EXPECT_LT(worst_pos, bound[a]) << block << ": actual " << c1_axes[a];
    }
  }
  // The groove turns C from 90 to -270 on both.
  const std::vector<size_t> g1 = c1.trace.RowsOfLine(LineOf("N0146", kSpiralGroove));
  const std::vector<size_t> g2 = c2.trace.RowsOfLine(LineOf("N0146", kSpiralGroove));
  EXPECT_NEAR(c1.trace["C.cmd"][g1.back()], -270, 0.5);
  EXPECT_NEAR(c2.trace["S1.cmd"][g2.back()], -270, 0.5);

  // The program ends in the same place.
  const size_t e1 = c1.trace.size() - 1, e2 = c2.trace.size() - 1;
  EXPECT_NEAR(c1.trace["X.pos"][e1], c2.trace["X.pos"][e2], 0.01);
  EXPECT_NEAR(c1.trace["Z.pos"][e1], c2.trace["Z.pos"][e2], 0.01);
  EXPECT_NEAR(std::remainder(c1.trace["C.pos"][e1] - c2.trace["S1.pos"][e2], 360.0), 0, 0.01);

  // One changeover each, to rotary axis mode; c2's is the faster.
  ASSERT_EQ(c1.changeovers.size(), 1u);
  ASSERT_EQ(c2.changeovers.size(), 1u);
  EXPECT_EQ(c1.changeovers[0].target, "rotary");
  EXPECT_EQ(c2.changeovers[0].target, "rotary");
  EXPECT_LT(c2.changeovers[0].duration_s(), c1.changeovers[0].duration_s());
}

class LatheC2ParameterSetTest : public ::testing::TestWithParam<BackendKind> {};

// lathe-c2's one drive changes its parameter set with the mode (manual 2.2, "Parameter set in
// drive used for rotary mode"): set 0 (spindle, speed control) at the start and at the end, set 1
// (servo, position control) through the C axis blocks, and only at standstill.
TEST_P(LatheC2ParameterSetTest, SwitchesTheDriveParameterSetWithTheMode) {
  const SwitchingRun c2 = RunSwitching("scenes/c-axis-switching-c2.yaml", GetParam(),
                                       std::string("set_c2_") + ToString(GetParam()));
  ASSERT_TRUE(c2.result.ok()) << ::testing::PrintToString(c2.result.failures);
  const Trace& t = c2.trace;
  const std::vector<size_t> n0077 = t.RowsOfLine(LineOf("N0077"));
  ASSERT_FALSE(n0077.empty());
  for (size_t i : n0077) ASSERT_EQ(t["S1.set"][i], 1) << "t " << t["t"][i];
  EXPECT_EQ(t["S1.set"][0], 0);
  EXPECT_EQ(t["S1.set"][t.size() - 1], 0);
  // Exactly two switches, each at standstill (set 1's velocity limit is 200 rpm; the spindle
  // turns at 1000 rpm before N0070).
  int switches = 0;
  for (size_t i = 1; i < t.size(); ++i) {
    if (t["S1.set"][i] == t["S1.set"][i - 1]) continue;
    ++switches;
    EXPECT_LT(std::abs(t["S1.rpm"][i]), 1.0) << "switch at t " << t["t"][i];
  }
  EXPECT_EQ(switches, 2);
}

INSTANTIATE_TEST_SUITE_P(Backends, LatheC2ParameterSetTest,
                         ::testing::Values(BackendKind::kPhysics, BackendKind::kKinematic),
                         [](const auto& info) { return std::string(ToString(info.param)); });

}  // namespace
}  // namespace vmt::sim
