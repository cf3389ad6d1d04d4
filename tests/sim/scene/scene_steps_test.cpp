// Reading the timeline's steps and the expectations of a scene: what each step becomes, and
// the errors a wrong one gets, with its YAML path.
#include "sim/scene/scene_steps.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using ::testing::HasSubstr;
using Kind = TimelineStep::Kind;

const std::string kNc =
    "nc: {program: " + testing::SourcePath("scenes/nc/stepped_shaft.mtc") + "}\nduration: 2\n";

Scene Load(const std::string& name, const std::string& body) {
  return LoadScene(testing::WriteLatheScene("scene_steps", name, body));
}
std::string Error(const std::string& name, const std::string& body) {
  return testing::SceneLoadError(testing::WriteLatheScene("scene_steps", name, body));
}

TEST(SceneSteps, APressIsKeyDownHoldAndKeyUp) {
  const Scene s = Load("press", kNc +
                                    "timeline:\n"
                                    "  - press: mREPOS\n"
                                    "  - press: {name: mRESTA, for: 0.25}\n"
                                    "  - {at: 1.5, press: mRaR_OFF}\n");
  ASSERT_EQ(s.timeline.size(), 9u);
  EXPECT_EQ(s.timeline[0].kind, Kind::kSignal);
  EXPECT_EQ(s.timeline[0].target, 1);
  EXPECT_EQ(s.timeline[1].kind, Kind::kWait);
  EXPECT_EQ(s.timeline[1].wait_s, 0.1);  // a tap when no time is given
  EXPECT_EQ(s.timeline[2].kind, Kind::kSignal);
  EXPECT_EQ(s.timeline[2].target, 0);
  EXPECT_EQ(s.timeline[2].signal, s.timeline[0].signal);
  EXPECT_EQ(s.timeline[4].wait_s, 0.25);
  EXPECT_NE(s.timeline[3].signal, s.timeline[0].signal);
  EXPECT_EQ(s.timeline[6].not_before_s, 1.5);  // `at` holds the key down, not its release
  EXPECT_EQ(s.timeline[8].not_before_s, 0);
  EXPECT_EQ(s.timeline[3].text, "timeline[1]: press mRESTA");
  EXPECT_EQ(s.timeline[4].text, "timeline[1]: hold mRESTA 0.25 s");
  EXPECT_EQ(s.timeline[5].text, "timeline[1]: release mRESTA");
}

TEST(SceneSteps, APressNeedsAKeyAndATime) {
  EXPECT_THAT(Error("press_not_key", kNc + "timeline:\n  - press: IROTMODE\n"),
              HasSubstr("timeline[0].press: 'IROTMODE' is not a key (io dir: key)"));
  EXPECT_THAT(Error("press_time", kNc + "timeline:\n  - press: {name: mREPOS, for: 0}\n"),
              HasSubstr("timeline[0].press.for: must be > 0"));
  EXPECT_THAT(Error("press_key", kNc + "timeline:\n  - press: {name: mREPOS, hold: 1}\n"),
              HasSubstr("timeline[0].press.hold: unknown key 'hold'"));
}

// An override switch is turned to one of its positions, not pressed.
TEST(SceneSteps, ASelectorIsTurnedToAPosition) {
  EXPECT_THAT(Error("press_selector", kNc + "timeline:\n  - press: mFOVR\n"),
              HasSubstr("timeline[0].press: 'mFOVR' is a selector"));
  EXPECT_THAT(
      Error("selector_value", kNc + "timeline:\n  - signal: {name: mFOVR, value: 77}\n"),
      HasSubstr("timeline[0].signal.value: mFOVR is a selector: expected one of its positions "
                "0/1/2/4/6/8/10/20/30"));
  EXPECT_THAT(Error("key_value", kNc + "timeline:\n  - signal: {name: mREPOS, value: 2}\n"),
              HasSubstr("timeline[0].signal.value"));
  EXPECT_EQ(Error("selector_ok", kNc + "timeline:\n  - signal: {name: mFOVR, value: 75}\n"), "");
}

TEST(SceneSteps, WaitUntilConditionsOfEveryKind) {
  const Scene s = Load("wait_until", kNc +
                                         "timeline:\n"
                                         "  - wait_until: {input: IROTMODE, value: false}\n"
                                         "  - wait_until: {axis: Z, in_position: true}\n"
                                         "  - wait_until: {axis: S1, at_speed: true}\n"
                                         "  - wait_until: {nc: hold, timeout: 3}\n"
                                         "  - wait_until: {signal: P00S.CREST, value: true}\n");
  ASSERT_EQ(s.timeline.size(), 5u);
  for (const TimelineStep& step : s.timeline) EXPECT_EQ(step.kind, Kind::kWaitUntil);
  EXPECT_EQ(s.timeline[0].until.kind, Condition::Kind::kInput);
  EXPECT_FALSE(s.timeline[0].until.value);
  EXPECT_EQ(s.timeline[0].timeout_s, 10);  // the default
  EXPECT_EQ(s.timeline[1].until.kind, Condition::Kind::kInPosition);
  EXPECT_EQ(s.timeline[2].until.kind, Condition::Kind::kAtSpeed);
  EXPECT_EQ(s.timeline[3].until.kind, Condition::Kind::kNc);
  EXPECT_EQ(s.timeline[3].until.nc, control::channel::ChannelState::kHold);
  EXPECT_EQ(s.timeline[3].timeout_s, 3);
  EXPECT_EQ(s.timeline[4].until.kind, Condition::Kind::kSignal);
  EXPECT_EQ(s.timeline[4].until.signal_value, 1);
}

TEST(SceneSteps, WrongConditionsAreNamedWhereTheyStand) {
  EXPECT_THAT(Error("until_none", kNc + "timeline:\n  - wait_until: {timeout: 1}\n"),
              HasSubstr("timeline[0].wait_until: expected input:, clutch:, axis:, nc: or signal:"));
  EXPECT_THAT(Error("until_nc", kNc + "timeline:\n  - wait_until: {nc: parked}\n"),
              HasSubstr("expected idle, running, hold, ended or error"));
  EXPECT_THAT(Error("until_axis", kNc + "timeline:\n  - wait_until: {axis: Z}\n"),
              HasSubstr("expected one of in_position, at_speed, standstill"));
  EXPECT_THAT(Error("until_signal", kNc + "timeline:\n  - wait_until: {signal: P00S.NOPE}\n"),
              HasSubstr("no gateway signal 'P00S.NOPE' (vmt signals MODEL lists them)"));
}

TEST(SceneSteps, ATimelineSignalIsOneAPlcWrites) {
  // The NC's own outputs and the machine's sensors are not the PLC's to set.
  EXPECT_THAT(Error("signal_nc", kNc + "timeline:\n  - signal: {name: P00S.CREST, value: true}\n"),
              HasSubstr("the NC writes P00S.CREST: a PLC cannot set it"));
  const Scene s = Load("signal", kNc + "timeline:\n  - signal: {name: P00C.REPOS, value: true}\n");
  ASSERT_EQ(s.timeline.size(), 1u);
  EXPECT_EQ(s.timeline[0].kind, Kind::kSignal);
  EXPECT_EQ(s.timeline[0].target, 1);
}

TEST(SceneSteps, AValueMustFitTheSignalsType) {
  // QMFB1A00.ACHS_NR_1 is an INT: the gateway could not hold these, so the scene says where.
  EXPECT_THAT(
      Error("signal_range",
            kNc + "timeline:\n  - signal: {name: QMFB1A00.ACHS_NR_1, value: 40000}\n"),
      HasSubstr("timeline[0].signal.value: QMFB1A00.ACHS_NR_1: 40000 is outside INT's range "
                "-32768..32767"));
  EXPECT_THAT(
      Error("signal_fraction",
            kNc + "timeline:\n  - signal: {name: QMFB1A00.ACHS_NR_1, value: 1.5}\n"),
      HasSubstr("timeline[0].signal.value: QMFB1A00.ACHS_NR_1: 1.5 is not an integer: INT"));
  EXPECT_THAT(Error("constant_range", kNc + "plc:\n  program: probe_block\n"
                                            "  constants: {QMFB1A00.ACHS_NR_1: -40000}\n"),
              HasSubstr("plc.constants.QMFB1A00.ACHS_NR_1: QMFB1A00.ACHS_NR_1: -40000 is outside "
                        "INT's range"));
  const Scene s = Load("signal_fits",
                       kNc + "timeline:\n  - signal: {name: QMFB1A00.ACHS_NR_1, value: -32768}\n");
  ASSERT_EQ(s.timeline.size(), 1u);
  EXPECT_EQ(s.timeline[0].target, -32768);
}

TEST(SceneSteps, NumbersInMessagesAreShort) {
  EXPECT_EQ(Fmt(400), "400");
  EXPECT_EQ(Fmt(0.25), "0.25");
  EXPECT_EQ(Fmt(-5), "-5");
}

}  // namespace
}  // namespace vmt::sim
