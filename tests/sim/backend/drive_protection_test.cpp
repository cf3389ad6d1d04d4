// The amplifier's protections (control/drive_bus.hpp drive_status): overload after the
// overload time at the torque limit, overspeed above 1.2 x the velocity limit. Both trip the
// drive (power stage off, not ready) until the master removes the controller enable with the
// cause gone.

#include <gtest/gtest.h>

#include <cmath>

#include "sim/runner/make_backend.hpp"
#include "sim/runner/runner.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using control::DriveMode;
using namespace control::drive_status;
using testing::Bench;
using testing::Lathe;

constexpr uint32_t kTripped = kOverload | kOverspeed | kParameterSetError;

// The turret clamped, T commanded 30 degrees on (inside its 45 degree following-error limit):
// T pushes at its torque limit against the clamp's 4000 N m until the overload trips it.
double TimeToOverload(const MachineModel& m, BackendKind kind, double timeout) {
  InitialState init;
  init.drive_positions = {{"T", 0}};
  auto backend = MakeBackend(kind, m, init);
  Bench bench(*backend);
  bench.Command("T", DriveMode::kPosition, 30);
  return bench.RunUntil([&] { return bench.Feedback("T").status & kOverload; }, timeout);
}

TEST(DriveProtectionTest, OverloadTripsAfterTheOverloadTime) {
  const MachineModel& m = Lathe();
  InitialState init;
  init.drive_positions = {{"T", 0}};
  PhysicsBackend backend(m, init);
  Bench bench(backend);
  bench.Command("T", DriveMode::kPosition, 30);
  bench.Run(0.9);
  EXPECT_TRUE(bench.Feedback("T").status & kTorqueLimit);
  EXPECT_TRUE(bench.Feedback("T").status & kReady) << "not yet: 0.9 s of the default 1 s";
  const double t = bench.RunUntil([&] { return bench.Feedback("T").status & kOverload; }, 0.5);
  ASSERT_GT(t, 0) << "never tripped";
  EXPECT_NEAR(0.9 + t, 1.0, 0.01);
  // Tripped: power stage off -- no torque, not ready, not enabled, and it stays so while the
  // master keeps its position command.
  bench.Run(0.1);
  const control::DriveFeedback& fb = bench.Feedback("T");
  EXPECT_EQ(fb.status & (kReady | kEnabled | kTripped), kOverload);
  EXPECT_EQ(fb.torque, 0);
  // The fault reset: controller enable off.
  bench.Command("T", DriveMode::kOff, 0);
  bench.Run(0.001);
  EXPECT_EQ(bench.Feedback("T").status & (kReady | kTripped), kReady);
  // Enabled again it pushes again, and the overload time counts from 0.
  bench.Command("T", DriveMode::kPosition, 30);
  EXPECT_NEAR(bench.RunUntil([&] { return bench.Feedback("T").status & kOverload; }, 2), 1.0, 0.01);
}

TEST(DriveProtectionTest, OverloadTimeFromTheModel) {
  const MachineModel m = testing::EditedLathe("t_overload", [](std::string s) {
    return testing::ReplaceOnce(s, "    following_error_limit: 45\n",
                                "    following_error_limit: 45\n    overload_time: 0.25\n");
  });
  EXPECT_NEAR(TimeToOverload(m, BackendKind::kPhysics, 1), 0.25, 0.01);
}

// The ideal machine has no torque: a drive there never overloads (the clamp simply holds).
TEST(DriveProtectionTest, KinematicNeverOverloads) {
  EXPECT_LT(TimeToOverload(Lathe(), BackendKind::kKinematic, 1.5), 0);
}

class OverspeedTest : public ::testing::TestWithParam<BackendKind> {};

// The C servo's controller enable is off, but clutch K is engaged: the spindle drags it. Above
// 1.2 x its velocity limit (1440 deg/s at the spindle, 240 rpm) it trips; once the spindle has
// slowed down, its enable being off resets it.
TEST_P(OverspeedTest, ServoDraggedThroughTheClutchTrips) {
  InitialState init;
  init.clutch_engaged = {{"K", true}};
  auto backend = MakeBackend(GetParam(), Lathe(), init);
  Bench bench(*backend);
  bench.Command("C", DriveMode::kOff, 0);
  bench.Command("S1", DriveMode::kVelocity, 300 * 6);
  double tripped_at_rpm = 0;
  const double t = bench.RunUntil(
      [&] {
        tripped_at_rpm = bench.Feedback("S1").velocity / 6;
        return bench.Feedback("C").status & kOverspeed;
      },
      1);
  ASSERT_GT(t, 0) << "never tripped";
  EXPECT_NEAR(tripped_at_rpm, 240, 2);
  EXPECT_FALSE(bench.Feedback("C").status & kReady);
  EXPECT_TRUE(bench.Feedback("S1").status & kReady);
  bench.Run(0.5);
  EXPECT_TRUE(bench.Feedback("C").status & kOverspeed) << "still dragged too fast";
  bench.Command("S1", DriveMode::kVelocity, 0);
  bench.Run(0.5);
  EXPECT_EQ(bench.Feedback("C").status & (kReady | kTripped), kReady);
}

// Switched while moving to a set whose velocity limit the axis exceeds by more than the factor,
// the drive trips; the trip latches until the enable goes off.
TEST_P(OverspeedTest, SwitchToASlowerSetWhileFastTrips) {
  const MachineModel m = testing::EditedLathe("slow_z", [](std::string s) {
    return testing::ReplaceOnce(s, "    spec: {settle_time: 0.2, overshoot: 0.005}   # 10 mm step",
                                "    parameter_sets: [{velocity_limit: 100}]\n"
                                "    spec: {settle_time: 0.2, overshoot: 0.005}   # 10 mm step");
  });
  InitialState init;
  init.drive_positions = {{"Z", 100}};
  auto backend = MakeBackend(GetParam(), m, init);
  Bench bench(*backend);
  const int z = bench.Drive("Z");
  bench.Run(0.3, [&] { bench.mdt().setpoints[z].value += 200 * kDriveTickS; });
  EXPECT_TRUE(bench.Feedback("Z").status & kReady);
  bench.mdt().setpoints[z].parameter_set = 1;
  bench.Run(kDriveTickS);
  EXPECT_TRUE(bench.Feedback("Z").status & kOverspeed);
  EXPECT_FALSE(bench.Feedback("Z").status & kReady);
  // Latched while the enable stays on, however slow the axis gets.
  bench.Run(1.0);
  EXPECT_TRUE(bench.Feedback("Z").status & kOverspeed);
  bench.Command("Z", DriveMode::kOff, 0, 1);
  bench.RunUntil([&] { return bench.Feedback("Z").status & kReady; }, 10);
  EXPECT_EQ(bench.Feedback("Z").status & (kReady | kTripped), kReady);
}

INSTANTIATE_TEST_SUITE_P(Backends, OverspeedTest,
                         ::testing::Values(BackendKind::kPhysics, BackendKind::kKinematic),
                         [](const auto& info) { return std::string(ToString(info.param)); });

// A scene names a set the spindle does not have: events.jsonl says which drive tripped and why,
// and when the fault is reset.
TEST(DriveProtectionTest, TripsAreEvents) {
  const std::string dir = testing::OutputDir("trip_events");
  const std::string path = dir + "/scene.yaml";
  std::ofstream(path) << "scene: trip-events\nmodel: "
                      << testing::SourcePath("models/lathe-c1/machine.yaml")
                      << "\nbackend: kinematic\nduration: 0.2\ntimeline:\n"
                         "  - speed: {axis: S1, rpm: 100, parameter_set: 2}\n"
                         "  - wait: 0.1\n"
                         "  - off: {axis: S1}\n";
  RunOptions options;
  options.out_dir = dir;
  options.snapshots = false;
  RunScene(LoadScene(path), options);
  const std::string events = testing::ReadBytes(dir + "/events.jsonl");
  EXPECT_NE(events.find("\"event\":\"drive\",\"name\":\"S1\",\"overload\":false,"
                        "\"overspeed\":false,\"parameter_set_error\":true}"),
            std::string::npos)
      << events;
  EXPECT_NE(events.find("\"event\":\"drive\",\"name\":\"S1\",\"overload\":false,"
                        "\"overspeed\":false,\"parameter_set_error\":false}"),
            std::string::npos);
}

}  // namespace
}  // namespace vmt::sim
