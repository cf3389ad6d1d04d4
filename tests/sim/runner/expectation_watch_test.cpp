// The scene's expectations on their own: each checked once when its time comes (untimed ones at
// the last tick), recorded as an event, "not reached" when the run ends first; a drive trip or
// an NC error the scene does not expect fails the run, one it expects does not.
#include "sim/runner/expectation_watch.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

Expectation Position(int drive, double value, double at_s, std::string text) {
  Expectation e{};
  e.quantity = Expectation::Quantity::kPosition;
  e.index = drive;
  e.value = value;
  e.tolerance = 0.01;
  e.at_s = at_s;
  e.text = std::move(text);
  return e;
}

Expectation Trip(int drive, uint32_t causes, std::string text) {
  Expectation e{};
  e.quantity = Expectation::Quantity::kDriveTrip;
  e.index = drive;
  e.trip = causes;
  e.text = std::move(text);
  return e;
}

struct Machine {
  const MachineModel& m = testing::Lathe();
  control::AmplifierTelegram at;
  std::vector<ClutchState> clutches;
  std::vector<DriveTrip> trips;
  Machine() { at.feedback.resize(m.drives.size()); }
  ExpectationInputs Inputs() const { return {at, clutches, nullptr, nullptr, trips}; }
};

TEST(ExpectationWatch, EachIsCheckedOnceWhenItsTimeComes) {
  Machine machine;
  const std::vector<Expectation> list = {Position(0, 5, 1.0, "at 1 s"),
                                         Position(0, 7, -1, "at the end"),
                                         Position(0, 9, 3.0, "at 3 s")};
  ExpectationWatch watch(list, machine.m);
  RunRecorder recorder;
  std::vector<nlohmann::ordered_json> events;
  recorder.AddObserver([&events](const nlohmann::ordered_json& e) { events.push_back(e); });

  EXPECT_TRUE(watch.Due(0, false));  // nothing known yet: the first tick looks
  watch.Check(0, false, machine.Inputs(), recorder);
  EXPECT_TRUE(events.empty());
  EXPECT_FALSE(watch.Due(0.5, false));  // the next one is due at 1 s
  machine.at.feedback[0].position = 5.004;
  ASSERT_TRUE(watch.Due(1.0, false));
  watch.Check(1.0, false, machine.Inputs(), recorder);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0]["text"], "at 1 s");
  EXPECT_EQ(events[0]["passed"], true);
  EXPECT_EQ(events[0]["detail"], "got 5.004000");
  machine.at.feedback[0].position = 7.5;
  watch.Check(1.25, false, machine.Inputs(), recorder);  // not due: nothing again
  EXPECT_EQ(events.size(), 1u);
  // The run ends at 2 s: the untimed one is checked, the one at 3 s is never reached.
  watch.Check(2.0, true, machine.Inputs(), recorder);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[1]["text"], "at the end");
  EXPECT_EQ(events[1]["passed"], false);
  const std::vector<ExpectationResult>& results = watch.Close();
  ASSERT_EQ(results.size(), 3u);
  EXPECT_TRUE(results[0].passed);
  EXPECT_FALSE(results[1].passed);
  EXPECT_EQ(results[2].detail, "not reached: the run ended first");
  const std::vector<std::string> failures = watch.NotHeld();
  ASSERT_EQ(failures.size(), 2u);
  EXPECT_EQ(failures[0], "at the end (got 7.500000)");
  EXPECT_EQ(failures[1], "at 3 s (not reached: the run ended first)");
}

TEST(ExpectationWatch, ATripTheSceneExpectsHoldsAndAnyOtherFailsTheRun) {
  Machine machine;
  const std::string name = machine.m.drives[1].info.name;
  const std::vector<Expectation> list = {Trip(1, control::drive_status::kOverload, "trips")};
  ExpectationWatch watch(list, machine.m);
  RunRecorder recorder;
  machine.trips = {{0.5, 1, control::drive_status::kOverload | control::drive_status::kOverspeed},
                   {0.75, 0, control::drive_status::kOverspeed}};
  watch.Check(1.0, true, machine.Inputs(), recorder);
  const std::vector<ExpectationResult>& results = watch.Close();
  EXPECT_TRUE(results[0].passed);
  EXPECT_NE(results[0].detail.find("at 0.5 s"), std::string::npos);
  EXPECT_TRUE(watch.NotHeld().empty());
  // Drive 1's overspeed and all of drive 0's trip are not expected; neither is the NC error.
  const std::vector<std::string> unexpected = watch.Unexpected(machine.trips, "P-ERR: stop");
  ASSERT_EQ(unexpected.size(), 3u);
  EXPECT_EQ(unexpected[0], "NC error: P-ERR: stop");
  EXPECT_NE(unexpected[1].find("drive " + name + " tripped on"), std::string::npos);
  EXPECT_NE(unexpected[1].find("which the scene does not expect"), std::string::npos);
  EXPECT_NE(unexpected[2].find("drive " + machine.m.drives[0].info.name), std::string::npos);
}

TEST(ExpectationWatch, AnExpectedNcErrorIsNoFailure) {
  Machine machine;
  Expectation error{};
  error.quantity = Expectation::Quantity::kNc;
  error.nc = control::channel::ChannelState::kError;
  error.text = "the NC stops";
  const std::vector<Expectation> list = {error};
  ExpectationWatch watch(list, machine.m);
  RunRecorder recorder;
  watch.Check(1.0, true, machine.Inputs(), recorder);
  watch.Close();
  EXPECT_EQ(watch.NotHeld().size(), 1u);  // without a channel it did not hold
  EXPECT_TRUE(watch.Unexpected({}, "P-ERR: stop").empty());
}

}  // namespace
}  // namespace vmt::sim
