// A drive's amplifier tripping (overload, overspeed, a missing parameter set) fails a scene
// unless the scene expects it (`expect: {drive:, trip:}`): the failure names the drive, the
// cause and the time. And the trip the turning scenes had: the C servo, held on the spindle's
// encoder with clutch K released, chased the turning spindle until it overloaded.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "../sim_test_support.hpp"
#include "control/drive_bus.hpp"
#include "sim/runner/runner.hpp"
#include "sim/scene/scene.hpp"

namespace vmt::sim {
namespace {

using ::testing::HasSubstr;
using testing::OutputDir;
using testing::SourcePath;

RunResult RunTo(const Scene& scene, const std::string& name, double until_s = -1) {
  RunOptions options;
  options.out_dir = OutputDir("drive_trip/" + name);
  options.snapshots = false;
  if (until_s > 0) options.until_s = until_s;
  return RunScene(scene, options);
}

bool IsTripExpectation(const Expectation& e) {
  return e.quantity == Expectation::Quantity::kDriveTrip;
}

TEST(DriveTrip, AnExpectedTripPasses) {
  const Scene scene = LoadScene(SourcePath("scenes/fault-spindle-against-clutch.yaml"));
  ASSERT_TRUE(std::any_of(scene.expectations.begin(), scene.expectations.end(), IsTripExpectation));
  const RunResult r = RunTo(scene, "expected");
  EXPECT_TRUE(r.ok()) << ::testing::PrintToString(r.failures);
  const auto e =
      std::find_if(r.expectations.begin(), r.expectations.end(), [](const ExpectationResult& x) {
        return x.text.find("drive S1 trips") != std::string::npos;
      });
  ASSERT_NE(e, r.expectations.end());
  EXPECT_TRUE(e->passed);
  EXPECT_THAT(e->detail, HasSubstr("tripped: overload at 1.026 s"));
}

TEST(DriveTrip, AnUnexpectedTripFailsTheSceneNamingDriveCauseAndTime) {
  Scene scene = LoadScene(SourcePath("scenes/fault-spindle-against-clutch.yaml"));
  std::erase_if(scene.expectations, IsTripExpectation);
  const RunResult r = RunTo(scene, "unexpected");
  EXPECT_FALSE(r.ok());
  ASSERT_EQ(r.failures.size(), 1u) << ::testing::PrintToString(r.failures);
  EXPECT_THAT(r.failures[0], HasSubstr("drive S1 tripped on overload at 1.026 s"));
  EXPECT_THAT(r.failures[0], HasSubstr("expect: {drive: S1, trip: overload}"));
  // Every expectation of the scene passes: only the trip fails it.
  for (const ExpectationResult& e : r.expectations) EXPECT_TRUE(e.passed) << e.text;
}

TEST(DriveTrip, ATripForAnotherCauseOrDriveIsStillUnexpected) {
  Scene scene = LoadScene(SourcePath("scenes/fault-spindle-against-clutch.yaml"));
  for (Expectation& e : scene.expectations)
    if (IsTripExpectation(e)) e.trip = control::drive_status::kOverspeed;
  RunResult r = RunTo(scene, "other_cause");
  EXPECT_THAT(::testing::PrintToString(r.failures),
              HasSubstr("drive S1 tripped on overload at 1.026 s"));
  for (Expectation& e : scene.expectations)
    if (IsTripExpectation(e)) e.trip = control::drive_status::kOverload, e.index = 0;
  r = RunTo(scene, "other_drive");
  EXPECT_THAT(::testing::PrintToString(r.failures), HasSubstr("drive S1 tripped on overload"));
}

TEST(DriveTrip, AnExpectedTripThatDoesNotComeFails) {
  Scene scene = LoadScene(SourcePath("scenes/fault-spindle-against-clutch.yaml"));
  for (Expectation& e : scene.expectations)
    if (IsTripExpectation(e)) e.at_s = 0.5;  // before the trip at 1.026 s
  const RunResult r = RunTo(scene, "not_yet");
  EXPECT_THAT(::testing::PrintToString(r.failures), HasSubstr("drive S1 has not tripped"));
}

TEST(DriveTrip, AnInjectedDriveFaultIsTheScenesOwnAndPasses) {
  // fault-drive takes X's power stage off with a timeline step: no amplifier protection trips.
  const RunResult r = RunTo(LoadScene(SourcePath("scenes/fault-drive.yaml")), "fault_drive");
  EXPECT_TRUE(r.ok()) << ::testing::PrintToString(r.failures);
}

TEST(DriveTrip, TheCServoNoLongerChasesTheTurningSpindleWithTheClutchReleased) {
  // turning's NC owns X and Z only: C, on the spindle's encoder with K released, stays in
  // follow-up while S1 turns at 1500 rpm, instead of overloading at 2.5 s.
  const Scene scene = LoadScene(SourcePath("scenes/turning.yaml"));
  ASSERT_EQ(scene.backend, BackendKind::kPhysics);
  const RunResult r = RunTo(scene, "turning");
  EXPECT_TRUE(r.ok()) << ::testing::PrintToString(r.failures);
  const std::string events = testing::ReadBytes(OutputDir("drive_trip/turning") + "/events.jsonl");
  EXPECT_EQ(events.find("\"overload\":true"), std::string::npos);
}

TEST(DriveTrip, TheExpectationIsReadWithItsCause) {
  const std::string body = "duration: 1\nexpect:\n  - {drive: C, trip: overspeed, at: 0.5}\n";
  const Scene s = LoadScene(testing::WriteLatheScene("drive_trip", "read", body));
  ASSERT_EQ(s.expectations.size(), 1u);
  EXPECT_EQ(s.expectations[0].quantity, Expectation::Quantity::kDriveTrip);
  EXPECT_EQ(s.expectations[0].trip, control::drive_status::kOverspeed);
  EXPECT_EQ(s.expectations[0].text, "expect[0]: drive C trips (overspeed) at 0.5 s");
  const std::string bad = testing::SceneLoadError(testing::WriteLatheScene(
      "drive_trip", "bad", "duration: 1\nexpect:\n  - {drive: C, trip: hot}\n"));
  EXPECT_THAT(bad, HasSubstr("expect[0].trip"));
  EXPECT_THAT(bad, HasSubstr("expected overload, overspeed, parameter_set_error or any"));
  EXPECT_THAT(testing::SceneLoadError(testing::WriteLatheScene(
                  "drive_trip", "no_drive", "duration: 1\nexpect:\n  - {drive: Q, trip: any}\n")),
              HasSubstr("expect[0].drive"));
}

}  // namespace
}  // namespace vmt::sim
