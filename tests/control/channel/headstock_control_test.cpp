// The channel's headstock on its own (C-axis manual 2.3, 3.3, 4.2): the mode a block needs,
// power-on from the PLC's acknowledgement, a block waiting for its changeover, immediate stop
// and the manual keys, the PLC removing its acknowledgement, and a channel without a headstock.

#include "control/channel/headstock_control.hpp"

#include <gtest/gtest.h>

#include "tests/control/axes/headstock_rig.hpp"

namespace vmt::control::channel {
namespace {

using axes::HeadstockMode;
using axes::headstock_rig::ConfigOf;
using axes::headstock_rig::Kind;

constexpr int kRotaryAxis = 2;  // X, Z, C

nc::PreparedBlock Block(nc::Motion motion, uint64_t programmed) {
  nc::PreparedBlock b;
  b.motion = motion;
  b.programmed = programmed;
  return b;
}

TEST(HeadstockControlModeNeeded, RotaryAxisWordsSelectRotaryModeSpindleFunctionsSpindleMode) {
  const uint64_t c = uint64_t{1} << kRotaryAxis, x = 1;
  EXPECT_EQ(HeadstockControl::ModeNeeded(Block(nc::Motion::kRapid, c), kRotaryAxis),
            HeadstockMode::kRotary);
  EXPECT_EQ(HeadstockControl::ModeNeeded(Block(nc::Motion::kArcCw, c | x), kRotaryAxis),
            HeadstockMode::kRotary);
  EXPECT_EQ(HeadstockControl::ModeNeeded(Block(nc::Motion::kLinear, x), kRotaryAxis),
            HeadstockMode::kNone);
  nc::PreparedBlock homing = Block(nc::Motion::kNone, c);
  homing.homing = true;  // G74 C0: homed in position control
  EXPECT_EQ(HeadstockControl::ModeNeeded(homing, kRotaryAxis), HeadstockMode::kRotary);
  for (const int m : {3, 4, 5, 19}) {
    nc::PreparedBlock b = Block(nc::Motion::kLinear, c);
    b.aux.push_back({'M', 0, static_cast<double>(m)});
    EXPECT_EQ(HeadstockControl::ModeNeeded(b, kRotaryAxis), HeadstockMode::kSpindle) << "M" << m;
  }
  nc::PreparedBlock second_spindle = Block(nc::Motion::kNone, 0);
  second_spindle.aux.push_back({'M', 2, 3});  // M2=3 turns spindle 2, not the headstock
  EXPECT_EQ(HeadstockControl::ModeNeeded(second_spindle, kRotaryAxis), HeadstockMode::kNone);
  EXPECT_EQ(HeadstockControl::ModeNeeded(Block(nc::Motion::kThread, x), kRotaryAxis),
            HeadstockMode::kSpindle);
  nc::PreparedBlock fictive = Block(nc::Motion::kLinear, c | x);
  fictive.fictive = true;  // X1/Y1 need rotary axis mode but do not select it
  EXPECT_EQ(HeadstockControl::ModeNeeded(fictive, kRotaryAxis), HeadstockMode::kNone);
  nc::PreparedBlock restore = Block(nc::Motion::kNone, 0);
  restore.repos = true;  // G77 S1=0: the spindle restored in spindle mode
  restore.aux.push_back({'S', 1, 0});
  EXPECT_EQ(HeadstockControl::ModeNeeded(restore, kRotaryAxis), HeadstockMode::kSpindle);
}

TEST(HeadstockControl, WithoutAHeadstockEveryQueryAnswersAsForAPlainSpindle) {
  HeadstockControl none(std::nullopt);
  EXPECT_FALSE(none);
  EXPECT_EQ(none.changeover(), nullptr);
  EXPECT_FALSE(none.In(HeadstockMode::kSpindle));
  EXPECT_FALSE(none.RotaryAxisOff());
  EXPECT_FALSE(none.RotaryOffsetsActive());
  EXPECT_FALSE(none.waiting());
  none.PowerOn();
  none.Abandon();
  none.TakeModeFromPlc();
  EXPECT_FALSE(none.waiting());
}

// The headstock with ideal drives, as the channel drives it each NC cycle.
struct Headstock : test_support::IdealDriveBus {
  explicit Headstock(Kind kind)
      : IdealDriveBus(kind == Kind::kServo ? 2 : 1, drive_status::kReady, axes::headstock_rig::kDt),
        control(ConfigOf(kind)) {
    for (test_support::IdealDrive& d : drives) d = test_support::IdealDrive::Servo(3600);
  }
  std::optional<std::string> Cycle(const HeadstockCycleInput& in) {
    const std::optional<std::string> error = control.Cycle(in, at, axes::headstock_rig::kDt);
    control.WriteSetpoints({DriveMode::kVelocity, 0, 0}, {DriveMode::kPosition, 0, 0}, mdt);
    Answer();
    return error;
  }
  // The PLC acknowledges `mode` at once, as a PLC without a mechanism does.
  void Acknowledge(HeadstockMode mode) {
    plc.rotmod_q = mode == HeadstockMode::kRotary;
    plc.spmod_q = mode == HeadstockMode::kSpindle;
    control.SetPlc(plc);
  }
  // Cycles of a running program until the changeover is over (at most `limit`).
  int RunChangeover(int limit = 20000) {
    HeadstockCycleInput running;
    running.running = true;
    int n = 0;
    for (; n < limit && control->busy(); ++n) {
      if (control->rotmod()) Acknowledge(HeadstockMode::kRotary);
      if (control->spmod()) Acknowledge(HeadstockMode::kSpindle);
      EXPECT_FALSE(Cycle(running));
    }
    return n;
  }
  axes::HeadstockPlc plc;
  HeadstockControl control;
};

class HeadstockControlKinds : public ::testing::TestWithParam<Kind> {};
INSTANTIATE_TEST_SUITE_P(Machine, HeadstockControlKinds,
                         ::testing::Values(Kind::kServo, Kind::kFrameless),
                         axes::headstock_rig::KindName);

TEST_P(HeadstockControlKinds, PowerOnTakesThePlcsModeOnceAndShowsIt) {
  Headstock h(GetParam());
  h.Acknowledge(HeadstockMode::kRotary);
  h.control.PowerOn();
  EXPECT_TRUE(h.control.In(HeadstockMode::kRotary));
  EXPECT_EQ(h.control.shown_mode(), HeadstockMode::kRotary);
  EXPECT_TRUE(h.control.RotaryOffsetsActive());
  EXPECT_TRUE(h.control.RotaryFollowsFeedback());  // the command taken from the actual position
  h.Acknowledge(HeadstockMode::kSpindle);
  h.control.PowerOn();  // only at the first NC cycle
  EXPECT_TRUE(h.control.In(HeadstockMode::kRotary));
}

TEST_P(HeadstockControlKinds, ABlockWaitsForItsModeAndTheShownModeSwitchesWhenItIsThere) {
  Headstock h(GetParam());
  h.Acknowledge(HeadstockMode::kSpindle);
  h.control.PowerOn();
  h.control.set_rotary_translation(12.5);
  h.control.RequestForBlock(HeadstockMode::kRotary);
  EXPECT_TRUE(h.control.waiting());
  EXPECT_EQ(h.control.waiting_for(), HeadstockMode::kRotary);
  EXPECT_TRUE(h.control->busy());
  EXPECT_EQ(h.control.shown_mode(), HeadstockMode::kSpindle);  // until the changeover is done
  EXPECT_GT(h.RunChangeover(), 0);
  EXPECT_TRUE(h.control.In(HeadstockMode::kRotary));
  EXPECT_EQ(h.control.shown_mode(), HeadstockMode::kRotary);
  EXPECT_TRUE(h.control.RotaryOffsetsActive());
  EXPECT_EQ(h.control.rotary_translation(), 12.5);
  EXPECT_EQ(h.control.EndWait(), HeadstockMode::kRotary);
  EXPECT_FALSE(h.control.waiting());
}

TEST_P(HeadstockControlKinds, ImmediateStopHoldsTheBlocksChangeoverButNotAKeys) {
  Headstock h(GetParam());
  h.Acknowledge(HeadstockMode::kSpindle);
  h.control.PowerOn();
  h.control.RequestForBlock(HeadstockMode::kRotary);
  HeadstockCycleInput held;
  held.hold = true;
  for (int i = 0; i < 2000; ++i) EXPECT_FALSE(h.Cycle(held));
  EXPECT_TRUE(h.control->busy());  // the program's changeover stays pending while interrupted
  // A key aborts the changeover the stop interrupted and commands its own, which runs.
  h.control.ManualChangeover(HeadstockMode::kSpindle, /*program_stopped=*/true);
  for (int i = 0; i < 20000 && h.control->busy(); ++i) {
    if (h.control->spmod()) h.Acknowledge(HeadstockMode::kSpindle);
    EXPECT_FALSE(h.Cycle(held));
  }
  EXPECT_FALSE(h.control->busy());
  EXPECT_TRUE(h.control.In(HeadstockMode::kSpindle));
}

TEST_P(HeadstockControlKinds, ThePlcRemovingItsAcknowledgementIsAnErrorUnlessOneIsPending) {
  Headstock h(GetParam());
  h.Acknowledge(HeadstockMode::kSpindle);
  h.control.PowerOn();
  HeadstockCycleInput running;
  running.running = true;
  EXPECT_FALSE(h.Cycle(running));
  h.Acknowledge(HeadstockMode::kNone);  // SPMOD_Q removed in spindle mode
  const std::optional<std::string> error = h.Cycle(running);
  ASSERT_TRUE(error);
  EXPECT_NE(error->find("SPMOD_Q"), std::string::npos) << *error;
  HeadstockCycleInput failed;
  failed.failed = true;
  EXPECT_FALSE(h.Cycle(failed));  // the channel has its error already
  // Control-Reset: the mode is again the one the PLC acknowledges (none here).
  h.control.TakeModeFromPlc();
  EXPECT_FALSE(h.control.In(HeadstockMode::kSpindle));
  EXPECT_FALSE(h.control.waiting());
}

}  // namespace
}  // namespace vmt::control::channel
