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

#include "sim/runner/runner.hpp"
#include "sim_test_support.hpp"

namespace vmt::sim {
namespace {

constexpr const char* kProgram = "tests/control/nc/seed_programs/caxis_spindle_switching.mtc";

/// trace.csv as columns by header name.
struct Trace {
  std::map<std::string, std::vector<double>> columns;
  const std::vector<double>& operator[](const std::string& name) const {
    const auto it = columns.find(name);
    if (it == columns.end()) throw std::runtime_error("no trace column " + name);
    return it->second;
  }
  size_t size() const { return columns.empty() ? 0 : columns.begin()->second.size(); }
};

Trace ReadTrace(const std::string& dir) {
  std::ifstream in(dir + "/trace.csv");
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  for (size_t start = 0;;) {
    const size_t comma = line.find(',', start);
    names.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  Trace t;
  while (std::getline(in, line)) {
    size_t start = 0;
    for (const std::string& name : names) {
      const size_t comma = line.find(',', start);
      t.columns[name].push_back(std::stod(line.substr(start, comma - start)));
      start = comma + 1;
    }
  }
  return t;
}

/// The source line of the block numbered `block` ("N0077") in the seed program.
int LineOf(const std::string& block) {
  std::ifstream in(testing::SourcePath(kProgram));
  std::string line;
  for (int n = 1; std::getline(in, line); ++n)
    if (line.rfind(block, 0) == 0) return n;
  return -1;
}

/// A headstock changeover as events.jsonl records it: from the request to the new mode.
struct Changeover {
  std::string target;
  double start_s = 0, end_s = -1;
  double duration_s() const { return end_s - start_s; }
};

std::vector<Changeover> Changeovers(const std::string& dir) {
  std::ifstream in(dir + "/events.jsonl");
  std::vector<Changeover> result;
  for (std::string line; std::getline(in, line);) {
    const nlohmann::json e = nlohmann::json::parse(line);
    if (e["event"] != "headstock") continue;
    if (e.contains("target") && e["mode"] == "none")
      result.push_back({e["target"].get<std::string>(), e["t"].get<double>()});
    else if (e.contains("axis") && !result.empty() && result.back().end_s < 0 &&
             e["mode"] == result.back().target)
      result.back().end_s = e["t"].get<double>();
  }
  return result;
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
  run.trace = ReadTrace(options.out_dir);
  run.changeovers = Changeovers(options.out_dir);
  return run;
}

/// The rows of the trace while N0077 runs.
std::vector<size_t> RowsOfBlock(const Trace& t, int line) {
  std::vector<size_t> rows;
  for (size_t i = 0; i < t.size(); ++i)
    if (t["nc.line"][i] == line) rows.push_back(i);
  return rows;
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
  const std::vector<size_t> r1 = RowsOfBlock(c1.trace, n0077), r2 = RowsOfBlock(c2.trace, n0077);
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
    worst_pos_c =
        std::max(worst_pos_c, std::abs(std::remainder(
                                  (c1.trace["C.pos"][i] - c1_0) - (c2.trace["S1.pos"][j] - c2_0),
                                  360.0)));
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

class LatheC2ParameterSetTest : public ::testing::TestWithParam<BackendKind> {};

// lathe-c2's one drive changes its parameter set with the mode (manual 2.2, "Parameter set in
// drive used for rotary mode"): set 0 (spindle, speed control) at the start and at the end, set 1
// (servo, position control) through the C axis blocks, and only at standstill.
TEST_P(LatheC2ParameterSetTest, SwitchesTheDriveParameterSetWithTheMode) {
  const SwitchingRun c2 = RunSwitching("scenes/c-axis-switching-c2.yaml", GetParam(),
                                       std::string("set_c2_") + ToString(GetParam()));
  ASSERT_TRUE(c2.result.ok()) << ::testing::PrintToString(c2.result.failures);
  const Trace& t = c2.trace;
  const std::vector<size_t> n0077 = RowsOfBlock(t, LineOf("N0077"));
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
