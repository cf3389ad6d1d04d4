// Faults of the spindle <-> C changeover on lathe-c1 as the NC and the machine see them (C-axis
// manual 3.3 "Errors", 4.3, 4.4): a PLC that acknowledges rotary axis mode before clutch K has
// meshed (C lags on the spindle's encoder into its following error limit: message 504, not so
// with the manual's program), a spindle started with K in (the spindle drive overloads against
// the C servo: 503 and a drive trip), clutch clashes at speed, and the C servo's limits.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <sstream>
#include <string>
#include <vector>

#include "control/channel/channel_messages.hpp"
#include "sim/runner/make_backend.hpp"
#include "sim/runner/runner.hpp"
#include "sim/scene/scene.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using ::testing::HasSubstr;
using testing::OutputDir;
using testing::SourcePath;

struct Outcome {
  RunResult result;
  int64_t errnr = 0;   ///< P00S.ERRNR at the end
  std::string events;  ///< events.jsonl
};

Outcome RunToTheEnd(const Scene& scene, const std::string& name, double until_s = -1) {
  RunOptions options;
  options.out_dir = OutputDir(name);
  options.snapshots = false;
  if (until_s > 0) options.until_s = until_s;
  Outcome o;
  SceneRun run(scene, options);
  while (!run.done()) run.Step();
  o.errnr = run.image()->Int(run.image()->Find("P00S.ERRNR"));
  o.result = run.Finish();
  o.events = testing::ReadBytes(options.out_dir + "/events.jsonl");
  return o;
}

// Each line of events.jsonl that contains every one of `parts`.
std::vector<std::string> Lines(const std::string& events,
                               std::initializer_list<std::string> parts) {
  std::vector<std::string> out;
  std::istringstream in(events);
  for (std::string line; std::getline(in, line);)
    if (std::all_of(parts.begin(), parts.end(),
                    [&](const std::string& p) { return line.find(p) != std::string::npos; }))
      out.push_back(line);
  return out;
}

// A number after `"key":` in a JSON line.
double Number(const std::string& line, const std::string& key) {
  const size_t at = line.find("\"" + key + "\":");
  if (at == std::string::npos) return std::nan("");
  return std::stod(line.substr(at + key.size() + 3));
}

TEST(ChangeoverFaultTest, WrongPlcAcknowledgesEarlyAndCLagsIntoItsFollowingError) {
  const Scene scene = LoadScene(SourcePath("scenes/fault-changeover-wrong-plc.yaml"));
  ASSERT_EQ(scene.plc.program, "c_axis_changeover_wrong");
  const Outcome o = RunToTheEnd(scene, "changeover_wrong_plc");
  EXPECT_TRUE(o.result.ok()) << ::testing::PrintToString(o.result.failures);
  EXPECT_EQ(o.errnr, control::channel::kMsgFollowingError);
  EXPECT_EQ(Lines(o.events, {"\"event\":\"nc\"", "\"state\":\"error\"",
                             "axis C: following error beyond its limit"})
                .size(),
            1u);
  // The NC was in rotary axis mode, the clutch never meshed.
  EXPECT_EQ(
      Lines(o.events, {"\"event\":\"headstock\"", "\"mode\":\"rotary\"", "\"axis\":\"C\""}).size(),
      1u);
  EXPECT_TRUE(Lines(o.events, {"\"event\":\"clutch\"", "\"state\":\"engaged\""}).empty());
}

TEST(ChangeoverFaultTest, TheManualsProgramRunsTheSameBlocksWithoutAnError) {
  Scene scene = LoadScene(SourcePath("scenes/fault-changeover-wrong-plc.yaml"));
  scene.plc.program = "c_axis_changeover";
  scene.expectations.clear();
  scene.timeline.clear();
  scene.timeline.push_back({});
  scene.timeline.back().kind = TimelineStep::Kind::kNcStart;
  scene.timeline.back().text = "timeline[0]: NC start";
  const Outcome o = RunToTheEnd(scene, "changeover_right_plc", 4.0);
  EXPECT_EQ(o.errnr, 0);
  EXPECT_TRUE(Lines(o.events, {"\"event\":\"nc\"", "\"state\":\"error\""}).empty()) << o.events;
  // Rotary axis mode only once K has meshed, and C then turns the spindle along the spiral.
  const auto engaged = Lines(o.events, {"\"event\":\"clutch\"", "\"state\":\"engaged\""});
  const auto rotary =
      Lines(o.events, {"\"event\":\"headstock\"", "\"mode\":\"rotary\"", "\"axis\":\"C\""});
  ASSERT_EQ(engaged.size(), 1u);
  ASSERT_EQ(rotary.size(), 1u);
  EXPECT_LT(Number(engaged[0], "t"), Number(rotary[0], "t"));
  // Hunting is slow enough for the dogs: no clash.
  EXPECT_TRUE(Lines(o.events, {"\"state\":\"clash\""}).empty());
}

TEST(ChangeoverFaultTest, SpindleStartedWithTheClutchInOverloadsTheSpindleDrive) {
  const Scene scene = LoadScene(SourcePath("scenes/fault-spindle-against-clutch.yaml"));
  const Outcome o = RunToTheEnd(scene, "spindle_against_clutch");
  EXPECT_TRUE(o.result.ok()) << ::testing::PrintToString(o.result.failures);
  EXPECT_EQ(o.errnr, control::channel::kMsgDriveFault);
  const auto trips =
      Lines(o.events, {"\"event\":\"drive\"", "\"name\":\"S1\"", "\"overload\":true"});
  ASSERT_EQ(trips.size(), 1u) << o.events;
  // At its torque limit from the start (the spindle does not turn) until overload_time.
  const MachineModel& m = testing::Lathe();
  EXPECT_NEAR(Number(trips[0], "t"), m.drives[m.DriveIndex("S1")].overload_time_s, 0.1);
  const auto error = Lines(o.events, {"\"event\":\"nc\"", "\"state\":\"error\""});
  ASSERT_EQ(error.size(), 1u);
  EXPECT_THAT(error[0], HasSubstr("spindle: drive error: overload"));
  // The C servo held the spindle within its own limit: no trip of C.
  EXPECT_TRUE(Lines(o.events, {"\"event\":\"drive\"", "\"name\":\"C\""}).empty());
}

// Engaging at speed: K refuses, the dogs ratchet, and the run records one clash with the
// relative speed (the spindle's 300 rpm against a C gear at rest: 1800 deg/s).
TEST(ChangeoverFaultTest, ClutchEngagedAtSpeedIsRecordedAsAClash) {
  const Scene scene = LoadScene(SourcePath("scenes/clutch-refuses-at-speed.yaml"));
  RunOptions options;
  options.out_dir = OutputDir("clutch_clash");
  options.snapshots = false;
  const RunResult r = RunScene(scene, options);
  EXPECT_TRUE(r.ok()) << ::testing::PrintToString(r.failures);
  const std::string events = testing::ReadBytes(options.out_dir + "/events.jsonl");
  const auto clashes =
      Lines(events, {"\"event\":\"clutch\"", "\"name\":\"K\"", "\"state\":\"clash\""});
  ASSERT_EQ(clashes.size(), 1u) << events;
  EXPECT_NEAR(Number(clashes[0], "relative_speed"), 1800, 20);
  EXPECT_NEAR(Number(clashes[0], "max_relative_speed"), 12, 1e-9);
}

// The C servo's limits hold in a physics run (C-axis manual 3.1: the power train tolerates less
// than 200 rpm): the NC's rapid for C is within the drive's velocity limit, and a C command far
// faster than that is clamped by the drive, at no more torque than its limit.
TEST(ChangeoverFaultTest, CServoStaysWithinItsSpeedAndTorqueLimits) {
  const MachineModel& m = testing::Lathe();
  const DriveParams& c = m.drives[m.DriveIndex("C")];
  EXPECT_LE(c.velocity_limit * kDegPerRad, 1200 + 1e-9);  // 200 rpm at the spindle
  const Scene scene = LoadScene(SourcePath("scenes/c-axis-switching.yaml"));
  const auto& axes = scene.nc.data.axes;
  const auto it =
      std::find_if(axes.begin(), axes.end(), [](const auto& a) { return a.name == "C"; });
  ASSERT_NE(it, axes.end());
  EXPECT_LE(it->rapid_per_s, c.velocity_limit * kDegPerRad + 1e-9);

  InitialState init;
  init.clutch_engaged["K"] = true;
  auto backend = MakeBackend(BackendKind::kPhysics, m, init);
  testing::Bench bench(*backend);
  bench.Command("S1", control::DriveMode::kOff, 0);
  // A command that runs away at 20 turns per second: the drive follows at its limit.
  double command = 0, fastest = 0, strongest = 0;
  bench.Run(1.0, [&] {
    command += 7200 * kDriveTickS;
    bench.Command("C", control::DriveMode::kPosition, command);
    fastest = std::max(fastest, std::abs(bench.Feedback("C").velocity));
    strongest = std::max(strongest, std::abs(bench.Feedback("C").torque));
  });
  // The servo accelerates the spindle at its torque limit and no harder, and never runs
  // faster than its velocity limit (the spindle's bearings and belt drag take part of the
  // torque, so it may not quite reach it in the second).
  EXPECT_LE(fastest, 1200 * 1.02);  // velocity loop overshoot only
  EXPECT_GT(fastest, 1200 * 0.8);
  EXPECT_LE(strongest, c.torque_limit + 1e-9);
  EXPECT_GT(strongest, c.torque_limit * 0.99) << "the command asks for more than the servo has";
  EXPECT_TRUE(bench.Feedback("C").status & control::drive_status::kReady) << "no trip";
}

}  // namespace
}  // namespace vmt::sim
