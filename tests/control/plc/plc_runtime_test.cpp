// The scan cycle: inputs latched at the start, outputs written at the end, the PLC clock, and
// the repositioning manual's machine-key program (8.2) on it.

#include "control/plc/plc_runtime.hpp"

#include <gtest/gtest.h>

#include <string>

#include "control/gateway/signal_table.hpp"
#include "control/plc/plc_programs.hpp"
#include "control/plc/programs/repos_machine_keys.hpp"

namespace vmt::control::plc {
namespace {

gateway::SignalImage LatheImage() {
  gateway::GatewayLayout layout;
  layout.processes = {0};
  layout.axes = {{1, "X", false, false}, {2, "Z", false, false}};
  layout.io = {{"QROTMODE", true, "valve"},
               {"IROTMODE", false, "switch"},
               {"mREPOS", false, "key"},
               {"mRESTA", false, "key"},
               {"mRaR_OFF", false, "key"}};
  return gateway::SignalImage(gateway::BuildSignalTable(layout));
}

TEST(PlcRuntimeTest, OutputsReachTheImageAtTheEndOfTheScanAndTheClockAdvances) {
  gateway::SignalImage image = LatheImage();
  const int valve = image.Require("QROTMODE"), sw = image.Require("IROTMODE");
  std::vector<int64_t> seen_times;
  bool valve_in_image_during_scan = true;
  PlcRuntime plc(
      image,
      [&](PlcScan& s) {
        seen_times.push_back(s.now().count());
        s.SetBool(valve, s.Bool(sw));
        valve_in_image_during_scan = image.Bool(valve);
      },
      PlcTime(4000));
  image.SetBool(sw, true);
  plc.Scan();
  EXPECT_FALSE(valve_in_image_during_scan);  // written at the end, not during the scan
  EXPECT_TRUE(image.Bool(valve));
  image.SetBool(sw, false);
  plc.Scan();
  EXPECT_FALSE(image.Bool(valve));
  EXPECT_EQ(seen_times, (std::vector<int64_t>{0, 4000}));
  EXPECT_EQ(plc.cycles(), 2u);
  EXPECT_EQ(plc.now(), PlcTime(8000));
}

// A program is a value: a saved runtime keeps its own instances, and restored it scans on from
// them (a run kept in memory), whatever the program did since.
TEST(PlcRuntimeTest, RestoredRuntimeScansOnFromItsSavedInstances) {
  gateway::SignalImage image = LatheImage();
  const int valve = image.Require("QROTMODE");
  // Toggles the valve every third scan: its count is the program's own state.
  PlcRuntime plc(
      image,
      [valve, scans = 0](PlcScan& s) mutable {
        if (++scans % 3 == 0) s.SetBool(valve, !s.Bool(valve));
      },
      PlcTime(4000));
  const auto valve_over = [&](int scans) {
    std::string seen;
    for (int k = 0; k < scans; ++k) plc.Scan(), seen += image.Bool(valve) ? '1' : '0';
    return seen;
  };
  (void)valve_over(2);
  const gateway::SignalImage image_then = image;
  const PlcRuntime::Saved saved = plc.Save();
  const std::string first = valve_over(7);
  EXPECT_EQ(first, "1110001");
  plc.Restore(saved);
  image = image_then;
  EXPECT_EQ(plc.now(), PlcTime(8000));
  EXPECT_EQ(valve_over(7), first);
}

TEST(PlcRuntimeTest, InputsAreLatchedAtTheStartOfTheScan) {
  gateway::SignalImage image = LatheImage();
  const int sw = image.Require("IROTMODE"), valve = image.Require("QROTMODE");
  PlcRuntime plc(
      image,
      [&](PlcScan& s) {
        const bool before = s.Bool(sw);
        image.SetBool(sw, !before);  // the machine changes meanwhile
        s.SetBool(valve, s.Bool(sw) == before);
      },
      PlcTime(4000));
  plc.Scan();
  EXPECT_TRUE(image.Bool(valve));  // the program saw one value throughout the scan
}

TEST(PlcRuntimeTest, OnlySignalsThePlcDrivesAreWritten) {
  gateway::SignalImage image = LatheImage();
  const int status = image.Require("P00S.RUN");
  PlcRuntime plc(
      image, [&](PlcScan& s) { s.SetBool(status, true); }, PlcTime(4000));
  EXPECT_DEATH(plc.Scan(), "P00S.RUN");
  EXPECT_TRUE(PlcDrives(gateway::Direction::kPlcToNc));
  EXPECT_TRUE(PlcDrives(gateway::Direction::kShared));
  EXPECT_FALSE(PlcDrives(gateway::Direction::kMachineToPlc));
}

// A stopped or lost PLC: what only it writes drops to the presets; what the NC writes, the
// machine's sensors and the events both sides write stay.
TEST(PlcRuntimeTest, StopDropsWhatOnlyThePlcWrites) {
  gateway::SignalImage image = LatheImage();
  const int control = image.Require("P00C.REPOS"), valve = image.Require("QROTMODE");
  const int status = image.Require("P00S.RUN"), sensor = image.Require("IROTMODE");
  int shared = -1;
  for (int id = 0; id < image.size() && shared < 0; ++id)
    if (image.table()[id].direction == gateway::Direction::kShared &&
        image.table()[id].type == gateway::SignalType::kBool)
      shared = id;
  ASSERT_GE(shared, 0);
  PlcRuntime plc(
      image,
      [&](PlcScan& s) {
        s.SetBool(control, true);
        s.SetBool(valve, true);
      },
      PlcTime(4000));
  plc.Scan();
  image.SetBool(status, true);
  image.SetBool(sensor, true);
  image.SetBool(shared, true);
  plc.Stop();
  EXPECT_TRUE(plc.stopped());
  EXPECT_FALSE(image.Bool(control));
  EXPECT_FALSE(image.Bool(valve));
  EXPECT_TRUE(image.Bool(status));
  EXPECT_TRUE(image.Bool(sensor));
  EXPECT_TRUE(image.Bool(shared));
  plc.Scan();  // a stopped PLC does not scan
  EXPECT_FALSE(image.Bool(control));
}

TEST(ReposMachineKeysTest, KeysCallRepositioningOrRestartWhileItIsPossible) {
  gateway::SignalImage image = LatheImage();
  auto program = MakePlcProgram("repos_machine_keys", image);
  ASSERT_TRUE(program);
  PlcRuntime plc(image, *program, PlcTime(4000));
  const int possible = image.Require("P00S.REPOS"), repos = image.Require("P00C.REPOS"),
            resta = image.Require("P00C.RESTA"), key_repos = image.Require("mREPOS"),
            key_resta = image.Require("mRESTA"), off = image.Require("mRaR_OFF");
  const auto press = [&](int key) {
    image.SetBool(key, true);
    plc.Scan();
    image.SetBool(key, false);
    plc.Scan();
  };
  press(key_repos);  // not possible yet
  EXPECT_FALSE(image.Bool(repos));
  image.SetBool(possible, true);
  press(key_repos);
  EXPECT_TRUE(image.Bool(repos));  // holds itself
  EXPECT_FALSE(image.Bool(resta));
  press(key_resta);
  EXPECT_FALSE(image.Bool(repos));
  EXPECT_TRUE(image.Bool(resta));
  press(off);
  EXPECT_FALSE(image.Bool(resta));
  press(key_repos);
  EXPECT_TRUE(image.Bool(repos));
  image.SetBool(possible, false);  // the NC withdraws it
  plc.Scan();
  EXPECT_FALSE(image.Bool(repos));
}

TEST(PlcProgramsTest, UnknownNamesAndMissingSignals) {
  gateway::SignalImage image = LatheImage();
  EXPECT_FALSE(MakePlcProgram("no_such_program", image));
  gateway::GatewayLayout bare;
  bare.processes = {0};
  gateway::SignalImage without_keys(gateway::BuildSignalTable(bare));
  EXPECT_THROW(MakePlcProgram("repos_machine_keys", without_keys), std::invalid_argument);
  EXPECT_NE(std::find(PlcProgramNames().begin(), PlcProgramNames().end(), "repos_machine_keys"),
            PlcProgramNames().end());
}

}  // namespace
}  // namespace vmt::control::plc
