// The control stage on its own, without a backend or a timeline: what it builds from a scene,
// the PLC's watchdog, the headstock acknowledgement a scene without a PLC gets, which drives
// the channels write and the stop of a PLC that is gone.
#include "sim/runner/control_stage.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

const Scene& DefaultScene() {
  static const Scene scene = LoadScene(testing::SourcePath("scenes/default.yaml"));
  return scene;
}

bool HasMessage(const control::channel::Channel& channel, int number) {
  for (const control::channel::OperatorMessage& m : channel.messages())
    if (m.number == number) return true;
  return false;
}

TEST(ControlStage, BuildsChannelGatewayPlcAndFieldBusFromTheScene) {
  const Scene& scene = DefaultScene();
  ASSERT_TRUE(scene.plc.present);
  ControlStage stage(scene, false, nullptr);
  ASSERT_NE(stage.channel(), nullptr);
  EXPECT_EQ(stage.jog_of_path(), nullptr);
  ASSERT_NE(stage.image(), nullptr);
  ASSERT_NE(stage.plc(), nullptr);
  EXPECT_NE(stage.probe_glue(), nullptr);
  EXPECT_EQ(stage.plc_every(), std::llround(scene.plc.period_s / kDriveTickS));
  // The field bus reads the sensors before each PLC cycle, the first too, and only then.
  EXPECT_TRUE(stage.ReadsInputsAt(0));
  EXPECT_TRUE(stage.ReadsInputsAt(stage.plc_every()));
  EXPECT_FALSE(stage.ReadsInputsAt(1));
  EXPECT_TRUE(stage.NcCycle(0));
  EXPECT_FALSE(stage.NcCycle(stage.channel()->ticks_per_cycle() + 1));
}

TEST(ControlStage, ChannelsMayWriteTheirOwnDrivesOnly) {
  const Scene& scene = DefaultScene();
  ControlStage stage(scene, false, nullptr);
  int channel_drives = 0;
  for (size_t d = 0; d < scene.model->drives.size(); ++d) {
    EXPECT_EQ(stage.MayWriteDrive(d), stage.channel()->MayWriteDrive(d)) << d;
    if (!stage.MayWriteDrive(d)) {
      EXPECT_FALSE(stage.WritesDrive(d)) << d;
    }
    channel_drives += stage.MayWriteDrive(d);
  }
  EXPECT_GT(channel_drives, 0);
}

// Two missed cycles are tolerated; the third stops the PLC and the NC with message 505. A
// missed scan is only counted at the start of a PLC cycle.
TEST(ControlStage, WatchdogStopsThePlcAfterTwoMissedCycles) {
  const Scene& scene = DefaultScene();
  ControlStage stage(scene, false, nullptr);
  const int64_t every = stage.plc_every();
  InjectedFaults faults;
  EXPECT_EQ(stage.ScanPlc(0, faults), "");
  const uint64_t scanned = stage.plc()->cycles();
  faults.plc_missed_scans = 5;
  EXPECT_EQ(stage.ScanPlc(1, faults), "");  // not a PLC cycle
  EXPECT_EQ(faults.plc_missed_scans, 5);
  EXPECT_EQ(stage.ScanPlc(every, faults), "");
  EXPECT_EQ(stage.ScanPlc(2 * every, faults), "");
  EXPECT_FALSE(stage.plc()->stopped());
  const std::string text = stage.ScanPlc(3 * every, faults);
  EXPECT_NE(text.find("3 scans missed"), std::string::npos) << text;
  EXPECT_TRUE(stage.plc()->stopped());
  EXPECT_EQ(stage.plc()->cycles(), scanned);
  EXPECT_TRUE(HasMessage(*stage.channel(), control::channel::kMsgPlcFault));
  // A stopped PLC is not scanned and not told again.
  EXPECT_EQ(stage.ScanPlc(4 * every, faults), "");
  EXPECT_EQ(faults.plc_missed_scans, 2);
}

TEST(ControlStage, ScansAgainWhenTheMissedScansEndInTime) {
  ControlStage stage(DefaultScene(), false, nullptr);
  const int64_t every = stage.plc_every();
  InjectedFaults faults;
  faults.plc_missed_scans = 2;
  for (int64_t k = 0; k < 6; ++k) EXPECT_EQ(stage.ScanPlc(k * every, faults), "") << k;
  EXPECT_FALSE(stage.plc()->stopped());
  EXPECT_EQ(stage.plc()->cycles(), 4u);
}

// vmt serve's client takes the embedded program's place: no PLC of the stage's own, but the
// field bus still carries the machine's I/O, and a lost client stops the NC the same way.
TEST(ControlStage, ExternalPlcHasTheFieldBusButNoProgram) {
  ControlStage stage(DefaultScene(), true, nullptr);
  EXPECT_EQ(stage.plc(), nullptr);
  EXPECT_TRUE(stage.ReadsInputsAt(0));
  InjectedFaults faults;
  EXPECT_EQ(stage.ScanPlc(0, faults), "");
  stage.StopPlc("PLC connection lost");
  EXPECT_TRUE(HasMessage(*stage.channel(), control::channel::kMsgPlcFault));
  EXPECT_EQ(stage.channel()->state(), control::channel::ChannelState::kError);
}

// Without a PLC the stage acknowledges the headstock as a PLC would where no mechanical
// changeover is needed (lathe-c2's direct drive): the drives enabled and the spindle mode
// reported on the first NC cycle.
TEST(ControlStage, DirectDriveHeadstockWithoutPlcIsAcknowledgedByTheStage) {
  const Scene scene = LoadScene(testing::SourcePath("scenes/c-axis-switching-c2.yaml"));
  ASSERT_FALSE(scene.plc.present);
  ControlStage stage(scene, false, nullptr);
  ASSERT_NE(stage.channel()->headstock(), nullptr);
  ASSERT_FALSE(stage.channel()->headstock()->config().separate_servo());
  EXPECT_EQ(stage.plc(), nullptr);
  const control::gateway::SignalImage& image = *stage.image();
  const auto count = [&image](const std::string& pattern) {
    int on = 0;
    for (int id = 0; id < image.size(); ++id)
      if (image.table()[id].pattern == pattern) on += image.Bool(id);
    return on;
  };
  EXPECT_EQ(count("AxxC.READY"), 0);
  stage.ReadControls(false);  // not an NC cycle
  EXPECT_EQ(count("AxxC.READY"), 0);
  stage.ReadControls(true);
  EXPECT_GT(count("AxxC.READY"), 0);
  EXPECT_GT(count("Axx.SPMOD_Q"), 0);
}

// A separate C servo behind a clutch (lathe-c1) needs the clutch switched first: the stage runs
// the changeover PLC of C-axis manual 4.4 in the scene's place, on the field bus.
TEST(ControlStage, SeparateServoWithoutPlcGetsTheChangeoverPlc) {
  const Scene scene = LoadScene(testing::SourcePath("scenes/c-axis-switching.yaml"));
  ASSERT_FALSE(scene.plc.present);
  ControlStage stage(scene, false, nullptr);
  ASSERT_NE(stage.channel()->headstock(), nullptr);
  ASSERT_TRUE(stage.channel()->headstock()->config().separate_servo());
  ASSERT_NE(stage.plc(), nullptr);
  EXPECT_TRUE(stage.ReadsInputsAt(0));
  InjectedFaults faults;
  EXPECT_EQ(stage.ScanPlc(0, faults), "");
  EXPECT_EQ(stage.plc()->cycles(), 1u);
}

TEST(ControlStage, SceneWithoutNcHasNoChannelAndNoBus) {
  const Scene scene = LoadScene(testing::SourcePath("scenes/c-axis-changeover.yaml"));
  ASSERT_FALSE(scene.nc.present);
  ControlStage stage(scene, false, nullptr);
  EXPECT_EQ(stage.channel(), nullptr);
  EXPECT_EQ(stage.image(), nullptr);
  EXPECT_EQ(stage.plc(), nullptr);
  EXPECT_FALSE(stage.ReadsInputsAt(0));
  InjectedFaults faults;
  EXPECT_EQ(stage.ScanPlc(0, faults), "");
  stage.StopPlc("gone");  // nothing to stop, nothing to tell
  control::MasterTelegram mdt;
  stage.WriteOutputs(mdt);
  EXPECT_TRUE(mdt.outputs.empty());
}

}  // namespace
}  // namespace vmt::sim
