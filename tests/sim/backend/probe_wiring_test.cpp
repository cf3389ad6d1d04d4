// The probe switch wired to the drives' probe inputs (machine.yaml `probe_inputs:`) on both
// backends: the PLC sees the switch, each wired drive latches its actual position value of the
// sampling tick, and beside it the exact position at the sub-tick instant of the change, so that
// the sampling error (up to the feed x 250 us) is visible.

#include "sim/backend/probe_wiring.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "../sim_test_support.hpp"
#include "control/plc/programs/probe_drive_parameters.hpp"
#include "sim/model/model_error.hpp"

namespace vmt::sim {
namespace {

namespace pc = control::probe_control;
using testing::Bench;
using ::testing::HasSubstr;
using testing::Lathe;

constexpr double kFeedMmPerS = 50;  // 3000 mm/min
constexpr double kX0Mm = 100;
constexpr double kZ0Mm = 300;

// X and Z armed on PIN4 for both edges; X runs at kFeedMmPerS in velocity mode.
void ArmAndRun(Bench& bench) {
  bench.Command("X", control::DriveMode::kVelocity, kFeedMmPerS);
  for (const char* axis : {"X", "Z"})
    bench.mdt().setpoints[bench.Drive(axis)].probe = {
        pc::kProbeCycleActive, pc::kProbe1Positive | pc::kProbe1Negative, true, false};
}

// PIN4 (probe 1) is the radial stylus' contact on both lathes; lathe-c1's PIN5 (probe 2) its
// axial stylus'.
TEST(ProbeWiringTest, LatheWiresXAndZToTheStylusContact) {
  for (const char* path : {"models/lathe-c1/machine.yaml", "models/lathe-c2/machine.yaml"}) {
    const MachineModel m = LoadMachineModel(testing::SourcePath(path));
    const int contact = control::IndexOf(m.io, std::string("IPROBE_CONTACT"));
    ASSERT_GE(contact, 0) << path;
    const bool c1 = std::string(path).find("lathe-c1") != std::string::npos;
    const int contact2 = control::IndexOf(m.io, std::string("IPROBE2_CONTACT"));
    ASSERT_EQ(contact2 >= 0, c1) << path;
    for (const DriveParams& d : m.drives) {
      const bool wired = d.info.name == "X" || d.info.name == "Z";
      EXPECT_EQ(d.probe_inputs[0], wired ? contact : -1) << path << " " << d.info.name;
      EXPECT_EQ(d.probe_inputs[1], wired && c1 ? contact2 : -1) << path << " " << d.info.name;
    }
  }
}

TEST(ProbeWiringTest, KinematicExactPositionIsTheAnalyticOneAndTheSamplingErrorShows) {
  KinematicBackend backend(Lathe(), {{{"X", kX0Mm}, {"Z", kZ0Mm}}, {}});
  Bench bench(backend);
  ArmAndRun(bench);
  // The ramp: 4000 mm/s^2 adds 1 mm/s per tick, so X reaches 50 mm/s after 50 ticks, having
  // moved (1 + 2 + ... + 50) x 1 mm/s x 250 us = 0.31875 mm; from then on 12.5 um per tick.
  constexpr int kTicks = 200;
  bench.Run(kTicks * kDriveTickS);
  ASSERT_FALSE(bench.Feedback("X").probe.probe1.positive.latched);
  ASSERT_FALSE(bench.Input("IPROBE_CONTACT"));

  constexpr double kFraction = 0.3;  // the contact at 30 % of the next tick
  backend.SetProbeSwitch(bench.Io("IPROBE_CONTACT"), true, kFraction);
  bench.Run(kDriveTickS);
  const double dt_feed = kFeedMmPerS * kDriveTickS;
  const double analytic = kX0Mm + 0.31875 + dt_feed * (kTicks - 50 + kFraction);

  EXPECT_TRUE(bench.Input("IPROBE_CONTACT"));  // the PLC sees the same switch
  const control::ProbeInputStatus& x = bench.Feedback("X").probe.probe1;
  EXPECT_TRUE(x.level);
  ASSERT_TRUE(x.positive.latched);
  EXPECT_FALSE(x.negative.latched);
  EXPECT_NEAR(x.positive.exact_position, analytic, 1e-4);
  // 7.3: the drive latched the actual position value it acquired 80 us before the sample that
  // saw the edge at the tick's end: 70 % of a tick after the contact, less 80 us.
  const double lead = kLatchPositionLeadS / kProbeSamplePeriodS;
  const double error = x.positive.measured_value - x.positive.exact_position;
  EXPECT_GT(error, 0);
  EXPECT_LE(error, kFeedMmPerS * kLatchMaxDelayS + 0.5e-4);
  EXPECT_NEAR(error, (1 - kFraction - lead) * dt_feed, 0.5e-4 + 1e-9);  // + half an increment

  // Z, wired to the same switch, stands: its exact and latched values agree.
  const control::ProbeInputStatus& z = bench.Feedback("Z").probe.probe1;
  ASSERT_TRUE(z.positive.latched);
  EXPECT_NEAR(z.positive.exact_position, kZ0Mm, 1e-9);
  EXPECT_NEAR(z.positive.measured_value, kZ0Mm, 1e-9);

  // The switch opens again at 80 % of a tick ten ticks later: the negative edge.
  bench.Run(9 * kDriveTickS);
  backend.SetProbeSwitch(bench.Io("IPROBE_CONTACT"), false, 0.8);
  bench.Run(kDriveTickS);
  const control::ProbeInputStatus& x2 = bench.Feedback("X").probe.probe1;
  ASSERT_TRUE(x2.negative.latched);
  EXPECT_NEAR(x2.negative.exact_position, analytic + dt_feed * (10 - kFraction + 0.8), 1e-4);
  // At 80 % the position was acquired before the edge: 20 % of a tick less 80 us.
  EXPECT_NEAR(x2.negative.measured_value - x2.negative.exact_position, (0.2 - lead) * dt_feed,
              0.5e-4 + 1e-9);
  EXPECT_NEAR(x2.positive.exact_position, analytic, 1e-4);  // the first edge stays
  EXPECT_FALSE(bench.Input("IPROBE_CONTACT"));
}

// 7.3: "the maximum time offset between probe edge and actual position value measurement is
// approximately 170 us". Wherever in the 250 us sampling period the contact falls, the latched
// value lies between 170 us of travel after it and 80 us before it; a contact just after a
// sample is latched 170 us late.
TEST(ProbeWiringTest, TheLatchIsAtMost170usFromTheEdge) {
  EXPECT_LE(kLatchMaxDelayS, 170e-6);
  for (const double fraction : {0.0, 0.01, 0.2, 0.5, 0.68, 0.9, 1.0}) {
    KinematicBackend backend(Lathe(), {{{"X", kX0Mm}, {"Z", kZ0Mm}}, {}});
    Bench bench(backend);
    ArmAndRun(bench);
    bench.Run(200 * kDriveTickS);  // past the ramp: 12.5 um a tick
    backend.SetProbeSwitch(bench.Io("IPROBE_CONTACT"), true, fraction);
    bench.Run(kDriveTickS);
    const control::ProbeEdgeLatch& latch = bench.Feedback("X").probe.probe1.positive;
    ASSERT_TRUE(latch.latched) << fraction;
    const double delay_s = (latch.measured_value - latch.exact_position) / kFeedMmPerS;
    const double half_increment_s = 0.5e-4 / kFeedMmPerS;
    EXPECT_LE(delay_s, kLatchMaxDelayS + half_increment_s) << fraction;
    EXPECT_GE(delay_s, -kLatchPositionLeadS - half_increment_s) << fraction;
    EXPECT_NEAR(delay_s, (1 - fraction) * kDriveTickS - kLatchPositionLeadS, half_increment_s)
        << fraction;
  }
}

// The seeded sampling phase: each contact falls at a random point of the drive's period, so
// the same contact instant is latched with different errors, all within -80..+170 us of travel;
// the same seed gives the same errors, another seed others.
TEST(ProbeWiringTest, ASeededSamplingPhaseScattersTheLatchWithinThePeriod) {
  const auto errors = [](uint64_t seed) {
    KinematicBackend backend(Lathe(), {{{"X", kX0Mm}, {"Z", kZ0Mm}}, {}});
    backend.SetProbeSamplingPhase({true, seed});
    Bench bench(backend);
    ArmAndRun(bench);
    bench.Run(200 * kDriveTickS);
    std::vector<double> e;
    for (int i = 0; i < 16; ++i) {
      // A new measurement: the enable 0 and back to 1 (7.3), the contact at 30 % of a tick.
      const auto enable = [&bench](bool on) {
        for (const char* axis : {"X", "Z"})
          bench.mdt().setpoints[bench.Drive(axis)].probe.probe1_enable = on;
      };
      enable(false);
      backend.SetProbeSwitch(bench.Io("IPROBE_CONTACT"), false, 0.5);
      bench.Run(kDriveTickS);
      enable(true);
      bench.Run(kDriveTickS);
      backend.SetProbeSwitch(bench.Io("IPROBE_CONTACT"), true, 0.3);
      bench.Run(kDriveTickS);
      const control::ProbeEdgeLatch& latch = bench.Feedback("X").probe.probe1.positive;
      EXPECT_TRUE(latch.latched);
      e.push_back(latch.measured_value - latch.exact_position);
    }
    return e;
  };
  const std::vector<double> a = errors(7), b = errors(7), c = errors(8);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  const double lo = *std::min_element(a.begin(), a.end());
  const double hi = *std::max_element(a.begin(), a.end());
  EXPECT_GE(lo, -kFeedMmPerS * kLatchPositionLeadS - 0.5e-4);
  EXPECT_LE(hi, kFeedMmPerS * kLatchMaxDelayS + 0.5e-4);
  // Spread over the period: 16 draws cover well over half of it.
  EXPECT_GT(hi - lo, 0.5 * kFeedMmPerS * kDriveTickS);
}

TEST(ProbeWiringTest, PhysicsExactPositionLiesOnTheTicksPath) {
  PhysicsBackend backend(Lathe(), {{{"X", kX0Mm}, {"Z", kZ0Mm}}, {}});
  Bench bench(backend);
  ArmAndRun(bench);
  bench.Run(0.1);  // well past the ramp: X runs at its feed
  const int x_joint = Lathe().drives[bench.Drive("X")].motor_joint;
  const double before = backend.JointPositions()[x_joint] * kMmPerM;
  constexpr double kFraction = 0.6;
  backend.SetProbeSwitch(bench.Io("IPROBE_CONTACT"), true, kFraction);
  bench.Run(kDriveTickS);
  const double after = backend.JointPositions()[x_joint] * kMmPerM;
  EXPECT_NEAR(after - before, kFeedMmPerS * kDriveTickS, 0.02 * kFeedMmPerS * kDriveTickS);

  const control::ProbeInputStatus& x = bench.Feedback("X").probe.probe1;
  ASSERT_TRUE(x.positive.latched);
  EXPECT_NEAR(x.positive.exact_position, before + kFraction * (after - before), 1e-4);
  const double error = x.positive.measured_value - x.positive.exact_position;
  const double lead = kLatchPositionLeadS / kProbeSamplePeriodS;
  EXPECT_NEAR(error, (1 - kFraction - lead) * (after - before), 0.5e-4 + 1e-6);
  EXPECT_GT(error, 0);
  EXPECT_LE(error, kFeedMmPerS * kLatchMaxDelayS);
  EXPECT_TRUE(bench.Input("IPROBE_CONTACT"));
  EXPECT_TRUE(bench.Feedback("Z").probe.probe1.positive.latched);
}

TEST(ProbeWiringTest, WithoutTheProbeFunctionTheFeedbackIsUnchanged) {
  // Default setpoints (S-0-0170 = 0): the switch reaches the PLC, the drives show nothing.
  KinematicBackend backend(Lathe(), {{{"X", kX0Mm}}, {}});
  Bench bench(backend);
  bench.Run(kDriveTickS);
  backend.SetProbeSwitch(bench.Io("IPROBE_CONTACT"), true, 0.5);
  bench.Run(kDriveTickS);
  EXPECT_TRUE(bench.Input("IPROBE_CONTACT"));
  const control::ProbeStatus& p = bench.Feedback("X").probe;
  EXPECT_FALSE(p.probe1.level);
  EXPECT_FALSE(p.probe1.positive.latched);
  EXPECT_EQ(p.probe1.positive.measured_value, 0);
}

TEST(ProbeWiringTest, PinFiveIsProbeTwo) {
  const MachineModel m = testing::EditedLathe("probe_pin5", [](std::string y) {
    return testing::ReplaceOnce(y, "probe_inputs: {PIN4: IPROBE_CONTACT, PIN5: IPROBE2_CONTACT}",
                                "probe_inputs: {PIN5: IPROBE_CONTACT}");
  });
  KinematicBackend backend(m, {{{"Z", kZ0Mm}}, {}});
  Bench bench(backend);
  const int z = bench.Drive("Z");
  bench.mdt().setpoints[z].probe = {pc::kProbeCycleActive, pc::kProbe2Positive, false, true};
  bench.Run(kDriveTickS);
  backend.SetProbeSwitch(bench.Io("IPROBE_CONTACT"), true, 0.5);
  bench.Run(kDriveTickS);
  EXPECT_FALSE(bench.Feedback("Z").probe.probe1.level);
  EXPECT_TRUE(bench.Feedback("Z").probe.probe2.level);
  EXPECT_TRUE(bench.Feedback("Z").probe.probe2.positive.latched);
}

TEST(ProbeWiringTest, TheProbeBlocksParametersArmWithQddsAndShowTheContactInIdds) {
  // lathe-c1's page stand-in (ProbeBlockProgram::basis_page): pin 4, normally open contact.
  const control::plc::ProbeDriveParameters p = control::plc::AxdWrProbeParameters(
      control::plc::BasisMessPage{false, false, true, true, false});
  KinematicBackend backend(Lathe(), {{{"X", kX0Mm}}, {}});
  Bench bench(backend);
  const int x = bench.Drive("X");
  bench.Command("X", control::DriveMode::kVelocity, -kFeedMmPerS);
  bench.mdt().setpoints[x].probe = control::plc::ProbeControlOf(p, false);
  bench.Run(0.01);
  bench.mdt().setpoints[x].probe = control::plc::ProbeControlOf(p, true);  // QDDS_1 on
  bench.Run(0.01);
  EXPECT_FALSE(control::plc::RealTimeStatusBit2(p, bench.Feedback("X").probe));
  backend.SetProbeSwitch(bench.Io("IPROBE_CONTACT"), true, 0.25);
  bench.Run(kDriveTickS);
  EXPECT_TRUE(control::plc::RealTimeStatusBit2(p, bench.Feedback("X").probe));  // IDDS_1
  // The stylus returns: the 1-0 edge is not selected, the measured value stays.
  const double measured = bench.Feedback("X").probe.probe1.positive.measured_value;
  backend.SetProbeSwitch(bench.Io("IPROBE_CONTACT"), false, 0.5);
  bench.Run(0.01);
  EXPECT_TRUE(control::plc::RealTimeStatusBit2(p, bench.Feedback("X").probe));
  EXPECT_FALSE(bench.Feedback("X").probe.probe1.negative.latched);
  EXPECT_EQ(bench.Feedback("X").probe.probe1.positive.measured_value, measured);
  // QDDS off at the end of the measuring path: IDDS clears.
  bench.mdt().setpoints[x].probe = control::plc::ProbeControlOf(p, false);
  bench.Run(kDriveTickS);
  EXPECT_FALSE(control::plc::RealTimeStatusBit2(p, bench.Feedback("X").probe));
}

TEST(ProbeWiringTest, OnlyAFreeMachineInputIsAProbeSwitch) {
  KinematicBackend backend(Lathe(), {});
  const auto io = [](const char* name) { return control::IndexOf(Lathe().io, std::string(name)); };
  EXPECT_NO_THROW(backend.SetProbeSwitch(io("IPROBE_CONTACT"), true, 0));
  for (const char* name : {"QPROBE_ON", "mREPOS", "IROTMODE", "ITAILSTOCK_FWD", "ITURRET_INPOS"}) {
    try {
      backend.SetProbeSwitch(io(name), true, 0.5);
      ADD_FAILURE() << name << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(name));
    }
  }
  EXPECT_THROW(backend.SetProbeSwitch(-1, true, 0.5), std::invalid_argument);
  EXPECT_THROW(backend.SetProbeSwitch(static_cast<int>(Lathe().io.size()), true, 0.5),
               std::invalid_argument);
}

TEST(ProbeWiringTest, BadProbeInputsNameTheirPath) {
  struct Case {
    const char* replacement;
    const char* path;
    const char* message;
  };
  const Case cases[] = {
      {"probe_inputs: {PIN6: IPROBE_CONTACT}", "drives[0].probe_inputs.PIN6",
       "unknown key 'PIN6' (expected one of: PIN4, PIN5)"},
      {"probe_inputs: {PIN4: IPROBE_CONTAKT}", "drives[0].probe_inputs.PIN4",
       "no I/O point 'IPROBE_CONTAKT'"},
      {"probe_inputs: {PIN4: QPROBE_ON}", "drives[0].probe_inputs.PIN4", "must be an input"},
      {"probe_inputs: {PIN4: mREPOS}", "drives[0].probe_inputs.PIN4", "operator's key"},
      {"probe_inputs: [IPROBE_CONTACT]", "drives[0].probe_inputs",
       "expected a map {PIN4: <input>, PIN5: <input>}"},
  };
  for (const Case& c : cases) {
    std::string message;
    try {
      testing::EditedLathe("bad_probe_inputs", [&c](std::string y) {
        return testing::ReplaceOnce(
            y, "probe_inputs: {PIN4: IPROBE_CONTACT, PIN5: IPROBE2_CONTACT}", c.replacement);
      });
    } catch (const ModelError& e) {
      message = e.what();
    }
    EXPECT_THAT(message, HasSubstr("bad_probe_inputs.yaml:")) << c.replacement;
    EXPECT_THAT(message, HasSubstr(c.path)) << c.replacement;
    EXPECT_THAT(message, HasSubstr(c.message)) << c.replacement;
  }
}

}  // namespace
}  // namespace vmt::sim
