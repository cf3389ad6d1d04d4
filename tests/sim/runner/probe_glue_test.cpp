// The PLC's probe block reaches the drives (fast-measurement 7.2, 7.3): QMFB1A00's Q9992
// initialisation writes the probe parameters into X's and Z's drives over AXD_WR, AxxC.QDDS arms
// X's latch, lathe-c1's ruby touches the d60 shaft and AxxS.IDDS shows the latch, whose value
// lies within a tick's travel of the exact contact. The test plays the NC's measuring cycle
// (Q9992, events 29 and 30) and steps machine, PLC and glue in the runner's order.

#include "sim/runner/probe_glue.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "control/gateway/signal_table.hpp"
#include "control/plc/plc_programs.hpp"
#include "control/plc/plc_runtime.hpp"
#include "sim/model/gateway_layout.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using control::DriveMode;
using control::plc::AxdWrStatus;
namespace pc = control::probe_control;
using testing::Bench;
using testing::Lathe;

constexpr double kMm = 1e-3;
const RevolvedPart kShaft{"workpiece", "spindle", {{60 * kMm, 220 * kMm, 0, 30 * kMm}}};
// X reads the radius of the ruby's lowest point at T3 (stylus_contacts_test); the switch trips
// 5 µm (pre-travel) into the shaft's r 30.
constexpr double kContactXMm = 29.995;
constexpr int64_t kTicksPerScan = 16;  // 4 ms PLC scan

int AxisNumber(const std::string& name) {
  for (const auto& a : GatewayLayoutOf(Lathe()).axes)
    if (a.name == name) return a.number;
  return -1;
}

std::string AxisSignal(const std::string& axis, const char* suffix) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "A%02d", AxisNumber(axis));
  return buf + std::string(suffix);
}

// Machine + PLC + glue, stepped as the runner steps them: the PLC scans on the inputs the field
// bus copied, the glue sets the drives' probe control after the axes' setpoints are written.
struct Cell {
  Cell()
      : backend(Lathe(), {{{"X", 31.0}, {"Z", 100.0}, {"T", 60.0}}, {}}),
        bench(backend),
        image(control::gateway::BuildSignalTable(GatewayLayoutOf(Lathe()))),
        glue(Lathe(), image),
        plc(image, *control::plc::MakePlcProgram("probe_block", image),
            control::plc::PlcTime(4000)) {
    backend.SetWorkpiece(kShaft);
    plc.SetAxdWriter([this](int axis, int ident, int64_t value) {
      return glue.Write(axis, ident, value);
    });
    Set("QMFB1A00.ENABLE", true);
    SetInt("QMFB1A00.ACHS_NR_1", AxisNumber("X"));
    SetInt("QMFB1A00.ACHS_NR_2", AxisNumber("Z"));
  }
  Cell(const Cell&) = delete;

  bool Bool(const std::string& name) const { return image.Bool(image.Require(name)); }
  void Set(const std::string& name, bool v) { image.SetBool(image.Require(name), v); }
  void SetInt(const std::string& name, int64_t v) { image.SetInt(image.Require(name), v); }

  void Tick() {
    const control::AmplifierTelegram& at = backend.Read();
    glue.ReadStatus(at);
    if (ticks % kTicksPerScan == 0) {
      for (const char* input : {"IPROBE_READY", "IPROBE_CONTACT"})
        Set(input, at.inputs[bench.Io(input)] != 0);
      plc.Scan();
    }
    bench.Output("QPROBE_ON", Bool("QPROBE_ON"));
    if (x_feed_mm_min > 0) {
      x_command = std::max(x_to_mm, x_command - x_feed_mm_min / 60 * kDriveTickS);
      bench.Command("X", DriveMode::kPosition, x_command);
    }
    glue.WriteSetpoints(bench.mdt());
    bench.Run(kDriveTickS);
    ++ticks;
  }
  bool RunUntil(const std::function<bool()>& done, double timeout_s) {
    for (int64_t n = 0; n < std::llround(timeout_s / kDriveTickS); ++n) {
      Tick();
      if (done()) return true;
    }
    return false;
  }

  KinematicBackend backend;
  Bench bench;
  control::gateway::SignalImage image;
  ProbeGlue glue;
  control::plc::PlcRuntime plc;
  int64_t ticks = 0;
  double x_feed_mm_min = 0, x_command = 31, x_to_mm = 31;
};

TEST(ProbeGlueTest, TheBlocksInitialisationArmsTheDriveAndIddsShowsTheContact) {
  Cell cell;
  const int x = cell.bench.Drive("X"), z = cell.bench.Drive("Z");

  // SETTING: Q9992; the block reads BASISMESSPAGE and writes the drives over AXD_WR.
  cell.Set("P00.Q9992", true);
  ASSERT_TRUE(cell.RunUntil([&] { return cell.Bool("P00.Q9992_Q"); }, 0.2));
  cell.Set("P00.Q9992", false);
  EXPECT_FALSE(cell.Bool("QMFB1A00.FEHLER"));
  for (const int d : {x, z}) {
    const control::plc::ProbeDriveParameters& p = cell.glue.parameters(d);
    EXPECT_EQ(p.S_0_0170, pc::kProbeCycleActive);
    EXPECT_EQ(p.S_0_0169, pc::kProbe1Positive);  // PIN4, normally open: the 0-1 edge
    EXPECT_EQ(p.S_0_0303, 405);
    EXPECT_EQ(p.S_0_0307, 409);
  }
  // The parameters persist in the drive; the enable waits for QDDS.
  cell.RunUntil([] { return false; }, 0.01);
  EXPECT_EQ(cell.backend.Read().feedback[x].probe.probe1.positive.latched, false);

  // PROBE: event 29 switches the probe on (Q_MTst1 -> QPROBE_ON); at the setup position event
  // 30; once the probe is ready the block sets QDDS and then acknowledges with event 29 = 0.
  cell.Set("P00.EV29", true);
  ASSERT_TRUE(cell.RunUntil([&] { return cell.Bool("IPROBE_READY"); }, 1.0));
  cell.Set("P00.EV30", true);
  ASSERT_TRUE(cell.RunUntil([&] { return !cell.Bool("P00.EV29"); }, 0.1));
  EXPECT_TRUE(cell.Bool(AxisSignal("X", "C.QDDS")));
  EXPECT_TRUE(cell.bench.mdt().setpoints[x].probe.probe1_enable);
  EXPECT_FALSE(cell.Bool(AxisSignal("X", "S.IDDS")));

  // The measuring path: X at 300 mm/min onto the shaft.
  const double feed = 300;
  cell.x_feed_mm_min = feed;
  cell.x_to_mm = 29.9;
  ASSERT_TRUE(cell.RunUntil([&] { return cell.Bool(AxisSignal("X", "S.IDDS")); }, 2.0));
  const control::ProbeEdgeLatch& latch = cell.backend.Read().feedback[x].probe.probe1.positive;
  ASSERT_TRUE(latch.latched);
  EXPECT_NEAR(latch.exact_position, kContactXMm, 1e-6);
  // The measured value: within feed x 250 µs (plus half an encoder increment) of the contact.
  const double tick_travel = feed / 60 * kDriveTickS;
  EXPECT_LE(std::abs(latch.measured_value - kContactXMm), tick_travel + 0.00005);
  // The block sees it: event 7.
  ASSERT_TRUE(cell.RunUntil([&] { return cell.Bool("P00.EV7"); }, 0.1));
  // Z's drive is armed too but its axis did not move: its latch holds Z where it stood.
  EXPECT_NEAR(cell.backend.Read().feedback[z].probe.probe1.positive.measured_value, 100, 1e-3);

  // End of the measuring path: QDDS off clears the drive's latch and IDDS with it.
  cell.Set("P00.EV30", false);
  ASSERT_TRUE(cell.RunUntil([&] { return !cell.Bool(AxisSignal("X", "S.IDDS")); }, 0.1));
  EXPECT_FALSE(cell.backend.Read().feedback[x].probe.probe1.positive.latched);
}

// What the drive takes: its probe function's parameters on an axis it has.
TEST(ProbeGlueTest, TheDriveRefusesWhatItDoesNotHave) {
  control::gateway::SignalImage image(
      control::gateway::BuildSignalTable(GatewayLayoutOf(Lathe())));
  ProbeGlue glue(Lathe(), image);
  const int x = AxisNumber("X");
  EXPECT_EQ(glue.Write(x, 303, 405), AxdWrStatus::kDone);
  EXPECT_EQ(glue.Write(x, 303, 301), AxdWrStatus::kRefused);
  EXPECT_EQ(glue.Write(x, 307, 413), AxdWrStatus::kRefused);
  EXPECT_EQ(glue.Write(x, 170, 4), AxdWrStatus::kRefused);
  EXPECT_EQ(glue.Write(x, 9999, 1), AxdWrStatus::kRefused);
  EXPECT_EQ(glue.Write(31, 170, 3), AxdWrStatus::kNoAxis);
  EXPECT_EQ(glue.Write(0, 170, 3), AxdWrStatus::kNoAxis);
  EXPECT_EQ(glue.parameters(Lathe().DriveIndex("X")).S_0_0303, 405);
  // Nothing written, nothing changed: the master's probe control stays as the channel wrote it.
  control::MasterTelegram mdt;
  mdt.setpoints.resize(Lathe().drives.size());
  glue.WriteSetpoints(mdt);
  EXPECT_EQ(mdt.setpoints[Lathe().DriveIndex("Z")].probe.probe_cycle_command, 0);
}

}  // namespace
}  // namespace vmt::sim
