// The program that runs the fast-measurement function block's instance QMFB1A00 on a gateway
// (mtc200-fast-measurement.md 7.2), with the test playing the NC, the drives and the probe.

#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <vector>

#include "control/drive_bus.hpp"
#include "control/gateway/signal_table.hpp"
#include "control/plc/plc_runtime.hpp"
#include "control/plc/programs/probe_block.hpp"
#include "probe_block_test_support.hpp"

namespace vmt::control::plc {
namespace {

using namespace testing;  // vmt::control::plc::testing

// ---- The program on a gateway ----------------------------------------------------------------

struct Plant {
  gateway::SignalImage image;
  std::shared_ptr<ProbeBlockProgram> program;
  PlcRuntime plc;

  explicit Plant(gateway::GatewayLayout layout)
      : image(gateway::BuildSignalTable(layout)),
        program(std::make_shared<ProbeBlockProgram>(image)),
        plc(
            image, [p = program](PlcScan& s) { (*p)(s); }, kScan) {}
  Plant(const Plant&) = delete;  // the runtime holds the image by reference

  int Id(const char* name) const { return image.Require(name); }
  bool Bool(const char* name) const { return image.Bool(Id(name)); }
  void Set(const char* name, bool v) { image.SetBool(Id(name), v); }
  void SetInt(const char* name, int64_t v) { image.SetInt(Id(name), v); }
  void Scan(int scans = 1) {
    for (int i = 0; i < scans; ++i) plc.Scan();
  }
  const QMFB1Axx& fb() const { return program->Measuring; }
};

gateway::GatewayLayout ThreeAxes() {
  gateway::GatewayLayout layout;
  layout.processes = {0};
  layout.axes = {{1, "X", false, false}, {2, "Z", false, false}, {3, "Y", false, false}};
  return layout;
}

/// The user's side of the wiring: the block enabled on axes 1 and 2, as the lathe measures.
void WireLathe(Plant& p) {
  p.Set("QMFB1A00.ENABLE", true);
  p.SetInt("QMFB1A00.ACHS_NR_1", 1);
  p.SetInt("QMFB1A00.ACHS_NR_2", 2);
}

TEST(ProbeBlockProgramTest, RunsTheMeasuringSequenceOnTheGateway) {
  Plant p(ThreeAxes());
  WireLathe(p);
  p.Scan();
  EXPECT_FALSE(p.fb().FEHLER);

  // NC: SETTING outputs Q9992; the block acknowledges once the drives are prepared.
  p.Set("P00.Q9992", true);
  for (int i = 0; i < 10 && !p.Bool("P00.Q9992_Q"); ++i) p.Scan();
  ASSERT_TRUE(p.Bool("P00.Q9992_Q"));
  EXPECT_TRUE(p.fb().Init_OK_1 && p.fb().Init_OK_2);
  EXPECT_FALSE(p.fb().Init_OK_3);
  p.Set("P00.Q9992", false);
  p.Scan();
  EXPECT_FALSE(p.Bool("P00.Q9992_Q"));

  // NC: PROBE starts (SE 29); the probe reports ready.
  p.Set("P00.EV29", true);
  p.Scan();
  EXPECT_TRUE(p.fb().Q_MTst1);
  EXPECT_FALSE(p.fb().Q_MTstOK);
  p.Set("QMFB1A00.I_MT_OK1", true);
  p.Scan();
  EXPECT_TRUE(p.fb().Q_MTstOK);

  // NC: setup position (SE 30), waiting for event 29 = 0.
  p.Set("P00.EV30", true);
  p.Scan();
  EXPECT_TRUE(p.Bool("A01C.QDDS"));
  EXPECT_TRUE(p.Bool("A02C.QDDS"));
  EXPECT_FALSE(p.Bool("A03C.QDDS"));
  EXPECT_TRUE(p.Bool("P00.EV29"));
  p.Scan();
  EXPECT_FALSE(p.Bool("P00.EV29"));  // acknowledged: the measuring path may start

  // Contact: the drive of axis 1 latches, the probe input closes.
  p.Set("A01S.IDDS", true);
  p.Set("QMFB1A00.I_MTast1", true);
  p.Scan();
  EXPECT_TRUE(p.Bool("P00.EV7"));
  EXPECT_TRUE(p.Bool("QMFB1A00.IDDS_1"));  // the pin shows what the block got
  EXPECT_FALSE(p.Bool("QMFB1A00.IDDS_2"));
  EXPECT_TRUE(p.fb().Q_MTst);

  // NC: end of the measuring path (RE 30); the drive clears its latch with the enable.
  p.Set("P00.EV30", false);
  p.Set("QMFB1A00.I_MTast1", false);
  p.Scan();
  EXPECT_FALSE(p.Bool("A01C.QDDS"));
  EXPECT_FALSE(p.Bool("A02C.QDDS"));
  EXPECT_TRUE(p.Bool("P00.EV7"));
  EXPECT_FALSE(p.fb().Q_MTstKmp);
  EXPECT_FALSE(p.fb().FEHLER);

  // NC: RE 7 after evaluating it: the program does not set it again.
  p.Set("P00.EV7", false);
  p.Scan(2);
  EXPECT_FALSE(p.Bool("P00.EV7"));
}

// The block runs in the PLC: its outputs are PLC variables, shown on the gateway.
TEST(ProbeBlockProgramTest, OutputPinsShowTheBlocksOutputs) {
  Plant p(ThreeAxes());
  WireLathe(p);
  p.SetInt("QMFB1A00.ACHS_NR_1", 0);
  p.SetInt("QMFB1A00.ACHS_NR_2", 0);
  p.Scan();
  EXPECT_EQ(p.fb().FEHLER_NR, 1);
  EXPECT_EQ(p.image.Int(p.Id("QMFB1A00.FEHLER_NR")), 1);
  EXPECT_TRUE(p.Bool("QMFB1A00.FEHLER"));
}

// On a machine with the probe in its I/O map, the program wires it as the typical application
// does: ready and contact to probe 1's pins, the probe request switching the probe on.
TEST(ProbeBlockProgramTest, TheMachinesProbeIsWiredToProbeOne) {
  gateway::GatewayLayout layout = ThreeAxes();
  layout.io = {{"QPROBE_ON", true, "probe activation"},
               {"IPROBE_READY", false, "probe ready"},
               {"IPROBE_CONTACT", false, "stylus deflected"}};
  Plant p(layout);
  WireLathe(p);
  p.Set("P00.Q9992", true);
  for (int i = 0; i < 10 && !p.Bool("P00.Q9992_Q"); ++i) p.Scan();
  p.Set("P00.Q9992", false);
  p.Scan();
  EXPECT_FALSE(p.Bool("QPROBE_ON"));
  p.Set("P00.EV29", true);
  p.Scan();
  EXPECT_TRUE(p.Bool("QPROBE_ON"));  // the measuring program requests probe 1
  EXPECT_FALSE(p.fb().Q_MTstOK);
  p.Set("IPROBE_READY", true);
  p.Scan();
  EXPECT_TRUE(p.Bool("QMFB1A00.I_MT_OK1"));
  EXPECT_TRUE(p.fb().Q_MTstOK);
  p.Set("IPROBE_CONTACT", true);  // displaced during the approach: a collision
  p.Scan();
  EXPECT_TRUE(p.Bool("QMFB1A00.I_MTast1"));
  EXPECT_TRUE(p.fb().Q_MTstKol);
}

// A second probe (lathe-c1's axial stylus) is wired to probe 2's pins; the page's PIN DDS (the
// stylus at the drives' pin 5) selects it, so only it is switched on and watched.
TEST(ProbeBlockProgramTest, ASecondProbeIsWiredToProbeTwo) {
  gateway::GatewayLayout layout = ThreeAxes();
  layout.io = {{"QPROBE_ON", true, "probe activation"},
               {"IPROBE_READY", false, "probe ready"},
               {"IPROBE_CONTACT", false, "stylus deflected"},
               {"QPROBE2_ON", true, "axial probe activation"},
               {"IPROBE2_READY", false, "axial probe ready"},
               {"IPROBE2_CONTACT", false, "axial stylus deflected"}};
  Plant p(layout);
  WireLathe(p);
  p.program->basis_page.PIN_DDS = true;
  p.Set("P00.Q9992", true);
  for (int i = 0; i < 10 && !p.Bool("P00.Q9992_Q"); ++i) p.Scan();
  p.Set("P00.Q9992", false);
  p.Scan();
  p.Set("P00.EV29", true);
  p.Scan();
  EXPECT_TRUE(p.Bool("QPROBE2_ON"));  // the measuring program requests probe 2
  EXPECT_FALSE(p.Bool("QPROBE_ON"));
  p.Set("IPROBE_READY", true);  // probe 1 says nothing about probe 2
  p.Scan();
  EXPECT_FALSE(p.fb().Q_MTstOK);
  p.Set("IPROBE2_READY", true);
  p.Scan();
  EXPECT_TRUE(p.Bool("QMFB1A00.I_MT_OK2"));
  EXPECT_TRUE(p.fb().Q_MTstOK);
  p.Set("IPROBE_CONTACT", true);
  p.Scan();
  EXPECT_FALSE(p.fb().Q_MTstKol);
  p.Set("IPROBE2_CONTACT", true);  // displaced during the approach: a collision
  p.Scan();
  EXPECT_TRUE(p.Bool("QMFB1A00.I_MTast2"));
  EXPECT_TRUE(p.fb().Q_MTstKol);
}

TEST(ProbeBlockProgramTest, PinsChooseTheEventsTheQFunctionAndTheAxes) {
  gateway::GatewayLayout layout = ThreeAxes();
  layout.events = {31, 32};
  layout.q_functions = {9990};
  Plant p(layout);
  WireLathe(p);
  p.SetInt("QMFB1A00.Q_Nummer", 9990);
  p.SetInt("QMFB1A00.Koll_EV", 31);
  p.SetInt("QMFB1A00.Touch_EV", 32);
  p.SetInt("QMFB1A00.ACHS_NR_1", 3);
  p.SetInt("QMFB1A00.ACHS_NR_2", 0);
  p.program->basis_page = {false, false, true, false, false};
  p.Set("QMFB1A00.I_MT_OK1", true);

  p.Set("P00.Q9992", true);  // not the block's Q function
  p.Scan(5);
  EXPECT_FALSE(p.fb().Init_OK_1);
  EXPECT_FALSE(p.Bool("P00.Q9992_Q"));
  p.Set("P00.Q9992", false);
  p.Set("P00.Q9990", true);
  p.Scan(5);
  EXPECT_TRUE(p.Bool("P00.Q9990_Q"));
  p.Set("P00.Q9990", false);
  p.Scan();

  p.Set("P00.EV31", true);
  p.Scan();
  p.Set("P00.EV30", true);
  p.Scan(2);
  EXPECT_FALSE(p.Bool("P00.EV31"));
  EXPECT_TRUE(p.Bool("A03C.QDDS"));
  EXPECT_FALSE(p.Bool("A01C.QDDS"));
  p.Set("A03S.IDDS", true);
  p.Scan();
  EXPECT_TRUE(p.Bool("P00.EV32"));
  EXPECT_FALSE(p.Bool("P00.EV7"));
  EXPECT_FALSE(p.fb().FEHLER);

  // ACHS_NR_1 moved to axis 1: axis 3's latch enable is released, axis 1's takes over.
  p.SetInt("QMFB1A00.ACHS_NR_1", 1);
  p.Scan();
  EXPECT_FALSE(p.Bool("A03C.QDDS"));
  EXPECT_TRUE(p.Bool("A01C.QDDS"));
}

TEST(ProbeBlockProgramTest, AnAxisTheMachineDoesNotHaveIsError40) {
  Plant p(ThreeAxes());
  WireLathe(p);
  p.SetInt("QMFB1A00.ACHS_NR_2", 5);  // a valid number, but no axis 5 on this machine
  p.Set("P00.Q9992", true);
  p.Scan(6);
  EXPECT_EQ(p.fb().FEHLER_NR, 40);
  EXPECT_TRUE(p.fb().Init_OK_1);
  EXPECT_FALSE(p.Bool("P00.Q9992_Q"));
}

// Where the runtime connects AXD_WR to the drives, the block writes each requested axis's drive
// in the order of FEHLER_NR 28..39, and what a drive refuses is the block's error.
TEST(ProbeBlockProgramTest, AxdWrWritesTheProbeParametersIntoTheDrives) {
  Plant p(ThreeAxes());
  WireLathe(p);
  std::vector<std::array<int64_t, 3>> writes;
  p.plc.SetAxdWriter([&writes](int axis, int ident, int64_t value) {
    writes.push_back({axis, ident, value});
    return AxdWrStatus::kDone;
  });
  p.Set("P00.Q9992", true);
  for (int i = 0; i < 10 && !p.Bool("P00.Q9992_Q"); ++i) p.Scan();
  ASSERT_TRUE(p.Bool("P00.Q9992_Q"));
  const std::vector<std::array<int64_t, 3>> expected = {
      {1, 303, 405}, {1, 307, 409}, {1, 169, control::probe_control::kProbe1Positive}, {1, 170, 3},
      {2, 303, 405}, {2, 307, 409}, {2, 169, control::probe_control::kProbe1Positive}, {2, 170, 3}};
  EXPECT_EQ(writes, expected);
}

TEST(ProbeBlockProgramTest, AParameterTheDriveRefusesIsTheBlocksError) {
  Plant p(ThreeAxes());
  WireLathe(p);
  p.plc.SetAxdWriter([](int axis, int ident, int64_t) {
    return axis == 2 && ident == 169 ? AxdWrStatus::kRefused : AxdWrStatus::kDone;
  });
  p.Set("P00.Q9992", true);
  p.Scan(6);
  EXPECT_EQ(p.fb().FEHLER_NR, 35);  // S_0_169, axis 2
  EXPECT_TRUE(p.fb().Init_OK_1);
  EXPECT_FALSE(p.fb().Init_OK_2);
  EXPECT_FALSE(p.Bool("P00.Q9992_Q"));

  Plant q(ThreeAxes());
  WireLathe(q);
  q.plc.SetAxdWriter([](int axis, int, int64_t) {
    return axis == 2 ? AxdWrStatus::kNoAxis : AxdWrStatus::kDone;
  });
  q.Set("P00.Q9992", true);
  q.Scan(6);
  EXPECT_EQ(q.fb().FEHLER_NR, 40);
}

TEST(ProbeBlockProgramTest, ThePageStandInDecidesTheMeasuringAxes) {
  Plant p(ThreeAxes());
  WireLathe(p);
  p.SetInt("QMFB1A00.ACHS_NR_2", 0);  // the lathe's page asks for axis 2 as well
  p.Set("P00.Q9992", true);
  p.Scan(3);
  EXPECT_EQ(p.fb().FEHLER_NR, 21);
  p.program->basis_page.Measuring_axis_2 = false;
  p.Set("QMFB1A00.RESET", true);
  p.Scan();
  p.Set("QMFB1A00.RESET", false);
  p.Scan(4);
  EXPECT_FALSE(p.fb().FEHLER);
  EXPECT_TRUE(p.Bool("P00.Q9992_Q"));
}

// With the NC's pages connected, MTD_RD reads BASISMESSPAGE (page 90) of process MessProc.
TEST(ProbeBlockProgramTest, ReadsBasisMessPageFromTheMeasuringPages) {
  Plant p(ThreeAxes());
  WireLathe(p);
  measure::MeasuringPages pages;
  p.program->measuring_pages = &pages;
  p.program->basis_page = {};  // the stand-in is no longer asked
  // SETTING(X, Z, , ...): measuring axes 1 and 2, as the block's ACHS_NR_1/2 are wired.
  ASSERT_EQ(measure::WriteMtd(pages, {90, 0, {}, 8}, 0, 1), "");
  ASSERT_EQ(measure::WriteMtd(pages, {90, 0, {}, 9}, 0, 1), "");
  p.Set("P00.Q9992", true);
  p.Scan(5);
  EXPECT_FALSE(p.fb().FEHLER) << p.fb().FEHLER_NR;
  EXPECT_TRUE(p.fb().Init_OK_1);
  EXPECT_TRUE(p.fb().Init_OK_2);
  EXPECT_TRUE(p.Bool("P00.Q9992_Q"));
  p.Set("P00.Q9992", false);
  p.Scan();

  // A BasisPage pin that names no BASISMESSPAGE: reading element 6 fails, FEHLER_NR 23.
  p.SetInt("QMFB1A00.BasisPage", 105);
  p.Set("P00.Q9992", true);
  p.Scan(3);
  EXPECT_TRUE(p.fb().FEHLER);
  EXPECT_EQ(p.fb().FEHLER_NR, 23);
  EXPECT_FALSE(p.Bool("P00.Q9992_Q"));
}

TEST(ProbeBlockProgramTest, DisablingReleasesTheLatchEnableAndTouchesNoEvent) {
  Plant p(ThreeAxes());
  WireLathe(p);
  p.Set("QMFB1A00.I_MT_OK1", true);
  p.Set("P00.Q9992", true);
  p.Scan(5);
  p.Set("P00.Q9992", false);
  p.Set("P00.EV29", true);
  p.Scan();
  p.Set("P00.EV30", true);
  p.Scan();
  ASSERT_TRUE(p.Bool("A01C.QDDS"));
  ASSERT_TRUE(p.Bool("P00.EV29"));
  p.Set("QMFB1A00.ENABLE", false);
  p.Scan(2);
  EXPECT_FALSE(p.Bool("A01C.QDDS"));
  EXPECT_FALSE(p.Bool("A02C.QDDS"));
  EXPECT_TRUE(p.Bool("P00.EV29"));  // not acknowledged, not written
  EXPECT_FALSE(p.fb().Init_OK_1);
}

TEST(ProbeBlockProgramTest, AMeasuringProcessTheMachineDoesNotHaveSeesNoNc) {
  Plant p(ThreeAxes());
  WireLathe(p);
  p.SetInt("QMFB1A00.MessProc", 1);
  p.Set("P00.Q9992", true);
  p.Set("P00.EV29", true);
  p.Scan(5);
  EXPECT_FALSE(p.fb().Init_OK_1);
  EXPECT_FALSE(p.fb().FEHLER);
  EXPECT_FALSE(p.Bool("P00.Q9992_Q"));
  EXPECT_TRUE(p.Bool("P00.EV29"));
}

}  // namespace
}  // namespace vmt::control::plc
