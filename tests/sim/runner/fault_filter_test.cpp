// The injected faults as filters on their own: nothing changes until a fault is injected; then a
// stuck sensor reads its level and a faulted drive is not ready on the way in, and a stuck valve
// keeps its level and a faulted drive's power stage is off on the way out.
#include "sim/runner/fault_filter.hpp"

#include <gtest/gtest.h>

namespace vmt::sim {
namespace {

constexpr uint32_t kReadyEnabled = control::drive_status::kReady | control::drive_status::kEnabled;

control::AmplifierTelegram Machine() {
  control::AmplifierTelegram at;
  at.inputs = {0, 1, 0};
  at.feedback.resize(2);
  for (auto& fb : at.feedback) fb.status = kReadyEnabled | control::drive_status::kInPosition;
  return at;
}

TEST(FaultFilter, NothingChangesUntilAFaultIsInjected) {
  const control::AmplifierTelegram raw = Machine();
  InjectedFaults none;
  none.sensor = {-1, -1, -1};
  FaultFilter filter;
  EXPECT_EQ(&filter.In(raw, none), &raw);
  EXPECT_TRUE(filter.filtered().feedback.empty());
  control::MasterTelegram mdt;
  mdt.outputs = {1, 0, 1};
  mdt.setpoints.assign(2, {control::DriveMode::kVelocity, 5, 0});
  FaultFilter::Out(none, mdt);
  EXPECT_EQ(mdt.outputs[0], 1);
  EXPECT_EQ(mdt.setpoints[1].mode, control::DriveMode::kVelocity);
}

TEST(FaultFilter, StuckSensorsAndValvesAndAFaultedDrive) {
  const control::AmplifierTelegram raw = Machine();
  InjectedFaults f;
  f.sensor = {1, -1, -1};  // input 0 stuck high
  f.valve = {-1, 1, -1};   // output 1 stays high
  f.drive = {false, true};
  f.any = true;
  FaultFilter filter;
  const control::AmplifierTelegram& seen = filter.In(raw, f);
  EXPECT_EQ(seen.inputs[0], 1);
  EXPECT_EQ(seen.inputs[1], 1);  // as the machine has it
  EXPECT_EQ(seen.feedback[0].status & kReadyEnabled, kReadyEnabled);
  EXPECT_EQ(seen.feedback[1].status & kReadyEnabled, 0u);
  EXPECT_NE(seen.feedback[1].status & control::drive_status::kInPosition, 0u);
  EXPECT_EQ(raw.inputs[0], 0);  // the machine's own telegram is left alone
  EXPECT_EQ(&filter.filtered(), &seen);

  control::MasterTelegram mdt;
  mdt.outputs = {1, 0, 1};
  mdt.setpoints.assign(2, {control::DriveMode::kVelocity, 5, 0});
  FaultFilter::Out(f, mdt);
  EXPECT_EQ(mdt.outputs[0], 1);
  EXPECT_EQ(mdt.outputs[1], 1);
  EXPECT_EQ(mdt.setpoints[0].mode, control::DriveMode::kVelocity);
  EXPECT_EQ(mdt.setpoints[1].mode, control::DriveMode::kOff);
}

}  // namespace
}  // namespace vmt::sim
