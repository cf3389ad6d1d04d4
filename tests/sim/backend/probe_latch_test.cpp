// The drive's probe evaluation (fast-measurement manual 7.3), tick by tick: activation by
// S-0-0170 = 3, arming by the enable's 0-1 transition, the first positive and the first negative
// edge only, S-0-0169's edge selection, flags and values cleared with the enable.

#include "sim/backend/probe_latch.hpp"

#include <gtest/gtest.h>

namespace vmt::sim {
namespace {

namespace pc = control::probe_control;

// A drive's latch on a bench: the master's probe parameters, the two pins and the actual
// position value the drive reports, one tick per call.
struct LatchBench {
  ProbeLatch latch;
  control::ProbeControl control{
      pc::kProbeCycleActive,
      pc::kProbe1Positive | pc::kProbe1Negative | pc::kProbe2Positive | pc::kProbe2Negative, false,
      false};
  std::array<ProbeInputSample, 2> pins{};
  double position = 0;

  // One tick with PIN4 / PIN5 at these levels; a pin that changed was at `position - 0.25`
  // exactly when it did (any value distinct from the sampled one will do).
  void Tick(bool pin4, bool pin5) {
    position += 1;
    pins[0] = {pin4, position - 0.25, std::nullopt};
    pins[1] = {pin5, position - 0.5, std::nullopt};
    latch.Step(control, pins, position);
  }
  void Tick() { Tick(pins[0].level, pins[1].level); }
  const control::ProbeInputStatus& p1() const { return latch.status().probe1; }
  const control::ProbeInputStatus& p2() const { return latch.status().probe2; }
};

TEST(ProbeLatchTest, InactiveUntilTheCycleCommandIsThree) {
  LatchBench b;
  for (uint8_t command : {0, 1, 2, 7}) {
    b.control.probe_cycle_command = command;
    b.control.probe1_enable = false;
    b.Tick(false, false);
    b.control.probe1_enable = true;
    b.Tick(true, true);  // enable 0-1 and a positive edge, but the function is off
    EXPECT_FALSE(b.p1().level) << int(command);
    EXPECT_FALSE(b.p2().level) << int(command);
    EXPECT_FALSE(b.p1().positive.latched) << int(command);
    b.Tick(false, false);
    EXPECT_FALSE(b.p1().negative.latched) << int(command);
  }
  // 3: the states show from this tick on.
  b.control.probe_cycle_command = pc::kProbeCycleActive;
  b.Tick(true, false);
  EXPECT_TRUE(b.p1().level);
  EXPECT_FALSE(b.p2().level);
}

TEST(ProbeLatchTest, StatesShowTheInputLevels) {
  LatchBench b;
  b.Tick(false, true);
  EXPECT_FALSE(b.p1().level);
  EXPECT_TRUE(b.p2().level);
  b.Tick(true, false);
  EXPECT_TRUE(b.p1().level);
  EXPECT_FALSE(b.p2().level);
  // Switched off again: S-0-0401/0402 read 0 whatever the inputs.
  b.control.probe_cycle_command = 0;
  b.Tick(true, true);
  EXPECT_FALSE(b.p1().level);
  EXPECT_FALSE(b.p2().level);
}

TEST(ProbeLatchTest, TheEnablesRisingEdgeArms) {
  LatchBench b;
  b.Tick(false, false);
  b.Tick(true, false);  // an edge while not enabled is not latched ...
  EXPECT_FALSE(b.p1().positive.latched);
  b.control.probe1_enable = true;
  b.Tick(true, false);  // ... nor remembered when the enable comes
  EXPECT_FALSE(b.p1().positive.latched);
  EXPECT_FALSE(b.p1().negative.latched);
  b.Tick(false, false);  // armed: the negative edge latches
  EXPECT_TRUE(b.p1().negative.latched);
  EXPECT_EQ(b.p1().negative.measured_value, b.position);
  EXPECT_EQ(b.p1().negative.exact_position, b.position - 0.25);
  b.Tick(true, false);  // and the positive one
  EXPECT_TRUE(b.p1().positive.latched);
  EXPECT_EQ(b.p1().positive.measured_value, b.position);
}

TEST(ProbeLatchTest, AnEdgeInTheTickThatArmsIsLatched) {
  // The setpoint's enable is valid from the start of its tick, the edge happened within it.
  LatchBench b;
  b.Tick(false, false);
  b.control.probe1_enable = true;
  b.Tick(true, false);
  EXPECT_TRUE(b.p1().positive.latched);
  EXPECT_EQ(b.p1().positive.measured_value, b.position);
}

TEST(ProbeLatchTest, OnlyTheFirstPositiveEdgeIsLatched) {
  LatchBench b;
  b.control.probe_control_parameter = pc::kProbe1Positive;
  b.Tick(false, false);
  b.control.probe1_enable = true;
  b.Tick();
  b.Tick(true, false);
  const double first = b.position;
  b.Tick(false, false);
  EXPECT_FALSE(b.p1().negative.latched);  // not selected
  b.Tick(true, false);                    // a second positive edge
  b.Tick(false, false);
  b.Tick(true, false);
  EXPECT_TRUE(b.p1().positive.latched);
  EXPECT_EQ(b.p1().positive.measured_value, first);
  EXPECT_EQ(b.p1().positive.exact_position, first - 0.25);
  EXPECT_FALSE(b.p1().negative.latched);
}

TEST(ProbeLatchTest, OnlyTheFirstNegativeEdgeIsLatched) {
  LatchBench b;
  b.control.probe_control_parameter = pc::kProbe1Negative;
  b.Tick(true, false);
  b.control.probe1_enable = true;
  b.Tick();
  b.Tick(false, false);
  const double first = b.position;
  b.Tick(true, false);
  EXPECT_FALSE(b.p1().positive.latched);  // not selected
  b.Tick(false, false);
  b.Tick(true, false);
  b.Tick(false, false);
  EXPECT_TRUE(b.p1().negative.latched);
  EXPECT_EQ(b.p1().negative.measured_value, first);
  EXPECT_FALSE(b.p1().positive.latched);
}

TEST(ProbeLatchTest, BothEdgesLatchOnceEachAndLaterEdgesAreIgnored) {
  LatchBench b;
  b.Tick(false, false);
  b.control.probe1_enable = true;
  b.Tick();
  b.Tick(true, false);
  const double rise = b.position;
  b.Tick(false, false);
  const double fall = b.position;
  for (int i = 0; i < 5; ++i) b.Tick(i % 2 == 0, false);
  EXPECT_EQ(b.p1().positive.measured_value, rise);
  EXPECT_EQ(b.p1().negative.measured_value, fall);
  EXPECT_TRUE(b.p1().positive.latched);
  EXPECT_TRUE(b.p1().negative.latched);
}

TEST(ProbeLatchTest, ClearingTheEnableClearsFlagsAndValues) {
  LatchBench b;
  b.Tick(false, false);
  b.control.probe1_enable = true;
  b.Tick(true, false);
  b.Tick(false, false);
  ASSERT_TRUE(b.p1().positive.latched);
  ASSERT_TRUE(b.p1().negative.latched);
  b.control.probe1_enable = false;
  b.Tick(true, false);
  const control::ProbeInputStatus& p = b.p1();
  EXPECT_FALSE(p.positive.latched);
  EXPECT_FALSE(p.negative.latched);
  EXPECT_EQ(p.positive.measured_value, 0);
  EXPECT_EQ(p.negative.measured_value, 0);
  EXPECT_EQ(p.positive.exact_position, 0);
  EXPECT_EQ(p.negative.exact_position, 0);
  EXPECT_TRUE(p.level);  // the state still shows
}

TEST(ProbeLatchTest, ANewMeasurementNeedsTheEnableZeroThenOne) {
  LatchBench b;
  b.control.probe_control_parameter = pc::kProbe1Positive;
  b.Tick(false, false);
  b.control.probe1_enable = true;
  b.Tick(true, false);
  const double first = b.position;
  // Held enabled: no new measurement, however many edges.
  b.Tick(false, false);
  b.Tick(true, false);
  EXPECT_EQ(b.p1().positive.measured_value, first);
  // 0 ...
  b.control.probe1_enable = false;
  b.Tick(false, false);
  b.Tick(true, false);  // not enabled: not latched
  EXPECT_FALSE(b.p1().positive.latched);
  b.Tick(false, false);
  // ... then 1: armed again.
  b.control.probe1_enable = true;
  b.Tick();
  EXPECT_FALSE(b.p1().positive.latched);
  b.Tick(true, false);
  EXPECT_TRUE(b.p1().positive.latched);
  EXPECT_EQ(b.p1().positive.measured_value, b.position);
}

TEST(ProbeLatchTest, AnEnableSetBeforeActivationNeedsZeroThenOne) {
  LatchBench b;
  b.control.probe_cycle_command = 0;
  b.control.probe1_enable = true;
  b.Tick(false, false);
  b.control.probe_cycle_command = pc::kProbeCycleActive;
  b.Tick();
  b.Tick(true, false);
  EXPECT_FALSE(b.p1().positive.latched);
  b.control.probe1_enable = false;
  b.Tick(false, false);
  b.control.probe1_enable = true;
  b.Tick(true, false);
  EXPECT_TRUE(b.p1().positive.latched);
  // Deactivating the function ends the measurement as clearing the enable does.
  b.control.probe_cycle_command = 0;
  b.Tick(false, false);
  EXPECT_FALSE(b.p1().positive.latched);
  EXPECT_EQ(b.p1().positive.measured_value, 0);
}

TEST(ProbeLatchTest, TheControlParameterSelectsEdgesPerProbe) {
  // Each S-0-0169 bit alone: the edge it names latches, the other three do not.
  struct Case {
    uint16_t bits;
    bool p1_pos, p1_neg, p2_pos, p2_neg;
  };
  for (const Case& c : {Case{pc::kProbe1Positive, true, false, false, false},
                        Case{pc::kProbe1Negative, false, true, false, false},
                        Case{pc::kProbe2Positive, false, false, true, false},
                        Case{pc::kProbe2Negative, false, false, false, true},
                        Case{0, false, false, false, false}}) {
    LatchBench b;
    b.control.probe_control_parameter = c.bits;
    b.Tick(false, false);
    b.control.probe1_enable = b.control.probe2_enable = true;
    b.Tick();
    b.Tick(true, true);
    b.Tick(false, false);
    EXPECT_EQ(b.p1().positive.latched, c.p1_pos) << c.bits;
    EXPECT_EQ(b.p1().negative.latched, c.p1_neg) << c.bits;
    EXPECT_EQ(b.p2().positive.latched, c.p2_pos) << c.bits;
    EXPECT_EQ(b.p2().negative.latched, c.p2_neg) << c.bits;
  }
}

TEST(ProbeLatchTest, Pin4AndPin5AreIndependent) {
  LatchBench b;
  b.Tick(false, false);
  b.control.probe2_enable = true;  // probe 2 only
  b.Tick();
  b.Tick(true, false);  // PIN4 edge: probe 1 is not enabled
  EXPECT_FALSE(b.p1().positive.latched);
  EXPECT_FALSE(b.p2().positive.latched);
  b.Tick(true, true);  // PIN5 edge
  const double pin5_rise = b.position;
  EXPECT_TRUE(b.p2().positive.latched);
  EXPECT_EQ(b.p2().positive.measured_value, pin5_rise);
  EXPECT_EQ(b.p2().positive.exact_position, pin5_rise - 0.5);
  // Probe 1 armed now; clearing probe 2's enable leaves probe 1 alone and vice versa.
  b.control.probe1_enable = true;
  b.Tick(false, true);
  EXPECT_TRUE(b.p1().negative.latched);
  b.control.probe2_enable = false;
  b.Tick();
  EXPECT_TRUE(b.p1().negative.latched);
  EXPECT_FALSE(b.p2().positive.latched);
  b.control.probe2_enable = true;
  b.control.probe1_enable = false;
  b.Tick(false, false);
  EXPECT_FALSE(b.p1().negative.latched);
  EXPECT_TRUE(b.p2().negative.latched);
}

}  // namespace
}  // namespace vmt::sim
