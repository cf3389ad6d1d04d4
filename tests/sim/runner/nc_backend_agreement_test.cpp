// The same NC program gives the same tool path on both backends, within the following error.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "sim/runner/runner.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

struct Row {
  double x_pos, z_pos, x_fe;
};

std::vector<Row> Trace(const std::string& dir) {
  std::ifstream in(dir + "/trace.csv");
  std::string line;
  std::getline(in, line);
  // Columns: t, Z.cmd, Z.pos, Z.vel, X.cmd, X.pos, X.vel, ...
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::vector<double> v;
    size_t start = 0;
    for (size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1)
      v.push_back(std::stod(line.substr(start, comma - start)));
    v.push_back(std::stod(line.substr(start)));
    rows.push_back({v[5], v[2], v[4] - v[5]});
  }
  return rows;
}

TEST(NcBackendAgreementTest, TurningProgramSamePathOnBothBackends) {
  const Scene scene = LoadScene(testing::SourcePath("scenes/turning.yaml"));
  RunOptions physics, kinematic;
  physics.snapshots = kinematic.snapshots = false;
  physics.backend = BackendKind::kPhysics;
  kinematic.backend = BackendKind::kKinematic;
  physics.out_dir = testing::OutputDir("nc_physics");
  kinematic.out_dir = testing::OutputDir("nc_kinematic");
  ASSERT_TRUE(RunScene(scene, physics).ok());
  ASSERT_TRUE(RunScene(scene, kinematic).ok());
  const std::vector<Row> p = Trace(physics.out_dir), k = Trace(kinematic.out_dir);
  ASSERT_EQ(p.size(), k.size());
  double worst_gap = 0, worst_fe = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    worst_gap =
        std::max({worst_gap, std::abs(p[i].x_pos - k[i].x_pos), std::abs(p[i].z_pos - k[i].z_pos)});
    worst_fe = std::max(worst_fe, std::abs(p[i].x_fe));
  }
  EXPECT_GT(worst_fe, 1.0);  // real motion with real following error
  EXPECT_LT(worst_gap, 0.1 * worst_fe) << "gap " << worst_gap << " vs following error " << worst_fe;
}

TEST(NcBackendAgreementTest, LowLagG06RemovesMostOfTheFollowingError) {
  // The same program on the physics lathe, with G05 and with G06 (velocity feed-forward).
  Scene scene = LoadScene(testing::SourcePath("scenes/turning.yaml"));
  RunOptions options;
  options.snapshots = false;
  options.until_s = 12;
  options.out_dir = testing::OutputDir("nc_g05");
  RunScene(scene, options);  // cut short at 12 s: the end-of-run expectations are not the point
  const std::vector<Row> g05 = Trace(options.out_dir);
  scene.nc.channel.initial.low_lag = true;
  options.out_dir = testing::OutputDir("nc_g06");
  RunScene(scene, options);
  const std::vector<Row> g06 = Trace(options.out_dir);
  ASSERT_EQ(g05.size(), g06.size());
  double fe05 = 0, fe06 = 0;
  for (size_t i = 0; i < g05.size(); ++i) {
    fe05 = std::max(fe05, std::abs(g05[i].x_fe));
    fe06 = std::max(fe06, std::abs(g06[i].x_fe));
  }
  EXPECT_GT(fe05, 1.0);
  EXPECT_LT(fe06, 0.1 * fe05) << "G06 " << fe06 << " mm vs G05 " << fe05 << " mm";
}

TEST(NcBackendAgreementTest, CAxisProgramsRunOnBothBackends) {
  // The changeover to rotary axis mode (clutch K, hunting) and the RX path velocity of the
  // C-axis manual's programs: every expectation of the scenes holds on either backend.
  for (const char* name : {"scenes/c-axis-switching.yaml", "scenes/c-axis-spiral-groove.yaml"}) {
    const Scene scene = LoadScene(testing::SourcePath(name));
    for (BackendKind backend : {BackendKind::kPhysics, BackendKind::kKinematic}) {
      RunOptions options;
      options.snapshots = false;
      options.backend = backend;
      const RunResult result = RunScene(scene, options);
      EXPECT_TRUE(result.ok()) << name
                               << (backend == BackendKind::kPhysics ? " physics" : " kinematic");
    }
  }
}

// When the changeover to rotary axis mode was asked for and when ROTMOD first went to the PLC.
struct RotmodTiming {
  double requested_s = -1, rotmod_s = -1;
};

RotmodTiming Rotmod(const std::string& dir) {
  std::ifstream in(dir + "/events.jsonl");
  RotmodTiming r;
  for (std::string line; std::getline(in, line);) {
    const nlohmann::json e = nlohmann::json::parse(line);
    if (e["event"] != "headstock") continue;
    if (r.requested_s < 0 && e.contains("target") && e["target"] == "rotary")
      r.requested_s = e["t"].get<double>();
    if (r.rotmod_s < 0 && e.contains("rotmod") && e["rotmod"].get<bool>())
      r.rotmod_s = e["t"].get<double>();
  }
  return r;
}

TEST(NcBackendAgreementTest, RotmodWaitsForTheSpindleToBrakeOnBothBackends) {
  // C-axis manual 4.2 / 4.3: the internal changeover decelerates the drives before ROTMOD goes
  // out. From 3000 rpm S1 brakes for about 2 s (9000 deg/s^2) on either backend: a drive let go
  // for a cycle coasts on the physics backend and stops dead on the kinematic one.
  const Scene scene = LoadScene(testing::SourcePath("scenes/c-axis-changeover-at-speed.yaml"));
  const double braking_s = 3000 * 6.0 / 9000;
  RotmodTiming timing[2];
  int k = 0;
  for (BackendKind backend : {BackendKind::kPhysics, BackendKind::kKinematic}) {
    RunOptions options;
    options.snapshots = false;
    options.backend = backend;
    options.out_dir = testing::OutputDir(k == 0 ? "rotmod_physics" : "rotmod_kinematic");
    const RunResult result = RunScene(scene, options);
    EXPECT_TRUE(result.ok()) << (k == 0 ? "physics" : "kinematic");
    timing[k] = Rotmod(options.out_dir);
    ASSERT_GE(timing[k].requested_s, 0);
    ASSERT_GE(timing[k].rotmod_s, 0);
    EXPECT_GT(timing[k].rotmod_s - timing[k].requested_s, 0.9 * braking_s)
        << (k == 0 ? "physics" : "kinematic");
    ++k;
  }
  EXPECT_NEAR(timing[0].rotmod_s, timing[1].rotmod_s, 0.1 * braking_s);
}

}  // namespace
}  // namespace vmt::sim
