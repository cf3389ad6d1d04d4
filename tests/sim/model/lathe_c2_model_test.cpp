// lathe-c2: a main spindle with rotary axis capability (C-axis manual 2). One drive, S1, on the
// spindle itself: speed control and M19 with parameter set 0, position control as the C axis
// with set 1.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "sim/backend/drive_controller.hpp"
#include "sim/model/gateway_layout.hpp"
#include "sim/model/model_error.hpp"
#include "sim/runner/make_backend.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using control::DriveMode;
using namespace control::drive_status;
using testing::Bench;

const MachineModel& LatheC2() {
  static const MachineModel model =
      LoadMachineModel(testing::SourcePath("models/lathe-c2/machine.yaml"));
  return model;
}

TEST(LatheC2ModelTest, Loads) {
  const MachineModel& m = LatheC2();
  EXPECT_EQ(m.name, "lathe-c2");
  EXPECT_EQ(m.drives.size(), 6u);  // Z X T W S1 S2: no C servo
  EXPECT_TRUE(m.clutches.empty());
  EXPECT_TRUE(m.gears.empty());
  EXPECT_LT(m.JointIndex("s1_motor"), 0);
  EXPECT_LT(m.JointIndex("c_motor"), 0);
  EXPECT_LT(control::IndexOf(m.io, "QROTMODE"), 0);
  EXPECT_GE(control::IndexOf(m.io, "QTURRET_UNCLAMP"), 0);
  const DriveParams& s1 = m.drives[m.DriveIndex("S1")];
  EXPECT_EQ(s1.motor_joint, m.JointIndex("spindle"));
  EXPECT_EQ(s1.ratio, 1);
  ASSERT_EQ(s1.parameter_sets.size(), 2u);
  EXPECT_TRUE(s1.parameter_sets[0].spindle);
  EXPECT_FALSE(s1.parameter_sets[1].spindle);
  EXPECT_EQ(s1.parameter_sets[1].kv_per_s, 30);
  EXPECT_EQ(m.nc.spindle_drive, m.DriveIndex("S1"));
  for (const Link& l : m.links)
    for (const Visual& v : l.visuals) EXPECT_FALSE(v.mesh->indices.empty()) << v.mesh_file;
}

// lathe-c2 with `edit` applied to its machine.yaml; the message of the ModelError it throws, or
// "" if it loads.
std::string LoadEditedLatheC2(const std::string& name,
                              const std::function<std::string(std::string)>& edit) {
  std::string yaml = testing::ReadBytes(testing::SourcePath("models/lathe-c2/machine.yaml"));
  yaml = testing::ReplaceOnce(yaml, "urdf: machine.urdf",
                              "urdf: " + testing::SourcePath("models/lathe-c2/machine.urdf"));
  const std::string path = testing::OutputDir("edited_models") + "/" + name + ".yaml";
  std::ofstream(path) << edit(yaml);
  try {
    LoadMachineModel(path);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

// C-axis manual 2.2: one axis (number 3) with two designations, S1 and C, on the one drive; C's
// limits are those of the drive's parameter set 1.
TEST(LatheC2ModelTest, CIsTheRotaryAxisDesignationOfTheSpindle) {
  const MachineModel& m = LatheC2();
  const int s1 = m.DriveIndex("S1");
  ASSERT_GE(m.nc.rotary_axis, 0);
  const control::axes::AxisParameters& c = m.nc.axes[m.nc.rotary_axis];
  EXPECT_EQ(c.name, "C");
  EXPECT_EQ(c.drive, s1);
  EXPECT_EQ(c.number, 3);
  EXPECT_EQ(m.nc.spindle_number, 3);
  EXPECT_EQ(m.nc.rotary_parameter_set, 1);
  EXPECT_DOUBLE_EQ(c.rapid_per_s, 1200);
  EXPECT_DOUBLE_EQ(c.acceleration, 6000);
  EXPECT_DOUBLE_EQ(c.in_position_window, 0.005);
  EXPECT_TRUE(c.rotary);
  EXPECT_EQ(c.travel_min, c.travel_max);  // endless (2.2: "unlimited rotary axes")
  // One axis interface (4.2) for both modes: A03, spindle-capable, with the name C.
  const control::gateway::GatewayLayout layout = GatewayLayoutOf(m);
  ASSERT_EQ(layout.axes.size(), 3u);
  EXPECT_EQ(layout.axes[2].number, 3);
  EXPECT_EQ(layout.axes[2].name, "C");
  EXPECT_TRUE(layout.axes[2].spindle_capable);
}

TEST(LatheC2ModelTest, RotaryAxisOnTheSpindleDriveErrors) {
  using ::testing::HasSubstr;
  // A second axis number for the same axis.
  EXPECT_THAT(LoadEditedLatheC2("c2_c_number",
                                [](std::string s) {
                                  return testing::ReplaceOnce(s, "      number: 3\n      drive: S1",
                                                              "      number: 4\n      drive: S1");
                                }),
              HasSubstr("nc.axes[2].number: must be the spindle's number 3"));
  // Faster than set 1 allows (set 0's 4000 rpm would pass).
  EXPECT_THAT(LoadEditedLatheC2("c2_c_rapid",
                                [](std::string s) {
                                  return testing::ReplaceOnce(s, "rapid: 72000 ", "rapid: 90000 ");
                                }),
              HasSubstr("nc.axes[2].rapid: faster than the velocity_limit of drive S1's "
                        "parameter set 1"));
  EXPECT_THAT(LoadEditedLatheC2("c2_c_set",
                                [](std::string s) {
                                  return testing::ReplaceOnce(s, "rotary_parameter_set: 1",
                                                              "rotary_parameter_set: 2");
                                }),
              HasSubstr("nc.spindle.rotary_parameter_set: drive S1 has no parameter set 2"));
  // Without rapid and acceleration the axis takes set 1's.
  EXPECT_EQ(LoadEditedLatheC2("c2_c_defaults",
                              [](std::string s) {
                                s = testing::ReplaceOnce(s, "      rapid: 72000 ", "      # ");
                                return testing::ReplaceOnce(
                                    s, "      acceleration: 6000    # deg/s^2 (set 1)", "");
                              }),
            "");
}

// REPOS manual 6.1: Cxx.086 is 0 (the axis is not repositioned) or a window of 0.1 .. 200000;
// a value outside is refused with the file and the YAML path.
TEST(LatheC2ModelTest, ReposWindowOutsideItsValueRangeErrors) {
  using ::testing::HasSubstr;
  auto with_x_window = [](const std::string& value) {
    return LoadEditedLatheC2("c2_cxx086_" + value, [&](std::string s) {
      return testing::ReplaceOnce(s, "Cxx.086: 0.2          #", "Cxx.086: " + value + " #");
    });
  };
  for (const char* bad : {"0.05", "200001", "-1"}) {
    const std::string error = with_x_window(bad);
    // file:line:column: yaml.path: message
    EXPECT_THAT(error, ::testing::ContainsRegex(std::string("c2_cxx086_") + bad +
                                                "\\.yaml:[0-9]+:[0-9]+: "))
        << bad;
    EXPECT_THAT(error, HasSubstr(": nc.axes[0].Cxx.086: must be 0 (the axis is not "
                                 "repositioned) or in 0.1..200000"))
        << bad;
  }
  for (const char* good : {"0", "0.1", "200000"}) EXPECT_EQ(with_x_window(good), "") << good;
}

// 2.3 Homing: one drive, one encoder, one reference: the spindle's encoder (a high-resolution
// incremental encoder on the 100 kHz main spindle interface) is C's, and given twice is an error.
TEST(LatheC2ModelTest, SpindleAndCShareTheOneEncoder) {
  const MachineModel& m = LatheC2();
  const control::axes::AxisParameters& c = m.nc.axes[m.nc.rotary_axis];
  EXPECT_DOUBLE_EQ(m.nc.spindle.encoder_periods_per_rev, 1024);
  EXPECT_DOUBLE_EQ(m.nc.spindle.encoder_limit_hz, 100000);
  EXPECT_DOUBLE_EQ(c.encoder_periods_per_rev, 1024);
  EXPECT_DOUBLE_EQ(c.encoder_limit_hz, 100000);
  EXPECT_GT(c.encoder_limit_hz / c.encoder_periods_per_rev * 60, 4000);  // 5859 rpm > S1's max
  EXPECT_DOUBLE_EQ(m.nc.spindle.jog_per_s, 600);
  EXPECT_DOUBLE_EQ(m.nc.spindle.jog_spindle_position, 45);
  EXPECT_THAT(LoadEditedLatheC2("c2_encoder_twice",
                                [](std::string s) {
                                  return testing::ReplaceOnce(
                                      s, "      drive: S1\n",
                                      "      drive: S1\n      encoder_periods_per_rev: 2048\n"
                                      "      encoder_limit_hz: 100000\n");
                                }),
              ::testing::HasSubstr("nc.axes[2].encoder_periods_per_rev: the spindle's encoder is "
                                   "given already"));
}

// The drive works with the gains of the set the setpoint selects and reports it (S-0-0254):
// set 1's position loop Kv 30 and velocity loop P 1.5 N m per deg/s in rotary axis mode, set 0's
// velocity loop P 0.8 N m per deg/s in spindle mode (speed control).
TEST(LatheC2ModelTest, S1WorksWithTheGainsOfTheSelectedSet) {
  const MachineModel& m = LatheC2();
  const DriveParams& p = m.drives[m.DriveIndex("S1")];
  DriveController drive(p);
  const double dt = kDriveTickS, one_deg = 1 / kDegPerRad;
  // Position control, set 1: 1 deg of following error asks for Kv x 1 deg/s.
  const control::DriveSetpoint rotary{DriveMode::kPosition, 1, 1};
  const double v_ref = drive.VelocityReference(ToSi(p, rotary), 0, 0, dt);
  EXPECT_NEAR(v_ref, 30 * one_deg, 1e-9);
  EXPECT_NEAR(drive.Torque(v_ref, 0, dt), 1.5 * 30 * (1 + dt / 0.02), 1e-6);
  control::DriveFeedback fb;
  drive.Feedback(0, 0, 0, fb);
  EXPECT_EQ(fb.parameter_set, 1);
  // Speed control, set 0 (at standstill: bumpless), 1 deg/s of speed error.
  DriveController spindle(p);
  const control::DriveSetpoint speed{DriveMode::kVelocity, 1, 0};
  const double s_ref = spindle.VelocityReference(ToSi(p, speed), 0, 0, dt);
  EXPECT_NEAR(spindle.Torque(s_ref, s_ref - one_deg, dt), 0.8 * (1 + dt / 0.03), 1e-6);
  spindle.Feedback(0, 0, 0, fb);
  EXPECT_EQ(fb.parameter_set, 0);
}

class LatheC2SpindleTest : public ::testing::TestWithParam<BackendKind> {};

// Spindle mode, then at standstill rotary axis mode: the same drive follows an interpolated
// position with the C axis' lag (v / Kv of set 1), then orients again as a spindle.
TEST_P(LatheC2SpindleTest, SpeedControlThenPositionControlThenM19) {
  auto backend = MakeBackend(GetParam(), LatheC2(), {});
  Bench bench(*backend);
  const int s1 = bench.Drive("S1");
  bench.Command("S1", DriveMode::kVelocity, 1000 * 6);
  ASSERT_GT(bench.RunUntil([&] { return bench.Feedback("S1").status & kAtSpeed; }, 2), 0);
  bench.Command("S1", DriveMode::kVelocity, 0);
  ASSERT_GT(bench.RunUntil([&] { return bench.Feedback("S1").status & kStandstill; }, 2), 0);
  bench.Run(0.2);

  // Rotary axis mode: set 1, position control from where the spindle stands.
  const double start = bench.Feedback("S1").position;
  bench.Command("S1", DriveMode::kPosition, start, 1);
  const double v = 300;  // deg/s
  bench.Run(0.3, [&] { bench.mdt().setpoints[s1].value += v * kDriveTickS; });
  EXPECT_NEAR(bench.Feedback("S1").following_error, v / 30, 0.05 * v / 30);
  EXPECT_TRUE(bench.Feedback("S1").status & kReady);
  bench.Run(0.5);
  EXPECT_NEAR(bench.Feedback("S1").position, start + 90, 0.005);
  EXPECT_TRUE(bench.Feedback("S1").status & kInPosition);

  // Spindle mode again: M19 with set 0 orients modulo one turn.
  bench.Command("S1", DriveMode::kPosition, 45, 0);
  ASSERT_GT(bench.RunUntil(
                [&] {
                  return (bench.Feedback("S1").status & kInPosition) &&
                         (bench.Feedback("S1").status & kStandstill);
                },
                3),
            0);
  const double angle = std::fmod(bench.Feedback("S1").position, 360.0);
  EXPECT_NEAR(angle < 0 ? angle + 360 : angle, 45, 0.05);
}

// Rotary axis mode at spindle speed: 1000 rpm is far above 1.2 x the C axis' 200 rpm, so the
// switch trips the drive (the NC must stop the spindle first).
TEST_P(LatheC2SpindleTest, SwitchToTheRotaryAxisSetAtSpeedTrips) {
  auto backend = MakeBackend(GetParam(), LatheC2(), {});
  Bench bench(*backend);
  bench.Command("S1", DriveMode::kVelocity, 1000 * 6);
  ASSERT_GT(bench.RunUntil([&] { return bench.Feedback("S1").status & kAtSpeed; }, 2), 0);
  bench.Command("S1", DriveMode::kPosition, bench.Feedback("S1").position, 1);
  bench.Run(kDriveTickS);
  EXPECT_TRUE(bench.Feedback("S1").status & kOverspeed);
  EXPECT_FALSE(bench.Feedback("S1").status & kReady);
}

INSTANTIATE_TEST_SUITE_P(Backends, LatheC2SpindleTest,
                         ::testing::Values(BackendKind::kPhysics, BackendKind::kKinematic),
                         [](const auto& info) { return std::string(ToString(info.param)); });

}  // namespace
}  // namespace vmt::sim
