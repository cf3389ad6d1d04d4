// The fast-measurement function block QMFB1Axx (mtc200-fast-measurement.md 7.2, figure 7-28's
// error numbers; 6.1 Q9992, 6.2 events 7/29/30) alone, and the program that runs the instance
// QMFB1A00 on a gateway, with the test playing the NC, the drives and the probe.

#include "control/plc/programs/probe_block.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "control/gateway/signal_table.hpp"
#include "control/plc/plc_runtime.hpp"

namespace vmt::control::plc {
namespace {

constexpr PlcTime kScan{4000};

// ---- The block alone -------------------------------------------------------------------------

/// Calls the block `scans` times, the PLC clock advancing a scan each call.
struct Bench {
  QMFB1Axx fb;
  PlcTime now{0};
  void Scan(int scans = 1) {
    for (int i = 0; i < scans; ++i, now += kScan) fb(now);
  }
};

/// A block wired as on a lathe: measuring axes 1 and 2, the page requesting both, probe 1 with
/// a normally open contact.
Bench Lathe() {
  Bench b;
  b.fb.ENABLE = true;
  b.fb.ACHS_NR_1 = 1;
  b.fb.ACHS_NR_2 = 2;
  b.fb.MTD_RD.page.Measuring_axis_1 = true;
  b.fb.MTD_RD.page.Measuring_axis_2 = true;
  return b;
}

/// Q9992 until the block acknowledges it (at most 10 scans), then the NC drops it.
void Initialise(Bench& b) {
  b.fb.Q_FKT = true;
  for (int i = 0; i < 10 && !b.fb.Q_FKT_Q; ++i) b.Scan();
  ASSERT_TRUE(b.fb.Q_FKT_Q);
  b.fb.Q_FKT = false;
  b.Scan();
  ASSERT_FALSE(b.fb.Q_FKT_Q);
}

/// From the start of a PROBE to the acknowledged setup position, the probe ready.
void ToMeasuringPath(Bench& b) {
  b.fb.EV_Koll = true;  // SE 29
  b.fb.I_MT_OK1 = true;
  b.Scan();
  b.fb.EV_Mess = true;  // SE 30 at the setup position
  b.Scan(2);            // arm, then acknowledge
  ASSERT_FALSE(b.fb.EV_Koll);
  ASSERT_FALSE(b.fb.FEHLER);
}

TEST(QMFB1AxxTest, InputsArePresetAsTheManualSays) {
  const QMFB1Axx fb;
  EXPECT_EQ(fb.Q_Nummer, 9992);
  EXPECT_EQ(fb.Koll_EV, 29);
  EXPECT_EQ(fb.Mess_EV, 30);
  EXPECT_EQ(fb.Touch_EV, 7);
  EXPECT_EQ(fb.BasisPage, 90);
}

TEST(QMFB1AxxTest, NormalSequenceFromQ9992ToTheContact) {
  Bench b = Lathe();
  b.Scan();
  EXPECT_FALSE(b.fb.FEHLER);
  EXPECT_FALSE(b.fb.Init_OK_1);

  // Q9992: the page is read (one scan), then each requested drive prepared (a scan each).
  b.fb.Q_FKT = true;
  b.Scan();
  EXPECT_TRUE(b.fb.MTDaktiv);
  EXPECT_FALSE(b.fb.AXDaktiv);
  b.Scan();
  EXPECT_FALSE(b.fb.MTDaktiv);
  EXPECT_TRUE(b.fb.AXDaktiv);
  EXPECT_FALSE(b.fb.Init_OK_1);
  b.Scan();
  EXPECT_TRUE(b.fb.Init_OK_1);
  EXPECT_FALSE(b.fb.Init_OK_2);
  EXPECT_FALSE(b.fb.Q_FKT_Q);
  b.Scan();
  EXPECT_TRUE(b.fb.Init_OK_2);
  EXPECT_FALSE(b.fb.Init_OK_3);  // not requested
  EXPECT_FALSE(b.fb.AXDaktiv);
  EXPECT_TRUE(b.fb.Q_FKT_Q);  // "from now on, measuring is possible"
  b.Scan();
  EXPECT_TRUE(b.fb.Q_FKT_Q);  // held until the NC takes it
  b.fb.Q_FKT = false;
  b.Scan();
  EXPECT_FALSE(b.fb.Q_FKT_Q);
  EXPECT_FALSE(b.fb.Q_MTst1);  // no instruction yet: the probe is not requested

  // MOVE/PROBE sets event 29: the probe is requested; it is not ready yet.
  b.fb.EV_Koll = true;
  b.Scan();
  EXPECT_TRUE(b.fb.Q_MTst1);
  EXPECT_FALSE(b.fb.Q_MTst2);
  EXPECT_FALSE(b.fb.Q_MTstOK);

  // Setup position (event 30) with the probe still not ready: no latch, no acknowledgement.
  b.fb.EV_Mess = true;
  b.Scan(3);
  EXPECT_FALSE(b.fb.QDDS_1);
  EXPECT_TRUE(b.fb.EV_Koll);
  EXPECT_FALSE(b.fb.FEHLER);

  // Ready: the latch is enabled first, the acknowledgement (event 29 reset) a scan later.
  b.fb.I_MT_OK1 = true;
  b.Scan();
  EXPECT_TRUE(b.fb.Q_MTstOK);
  EXPECT_TRUE(b.fb.QDDS_1);
  EXPECT_TRUE(b.fb.QDDS_2);
  EXPECT_FALSE(b.fb.QDDS_3);
  EXPECT_TRUE(b.fb.EV_Koll);
  b.Scan();
  EXPECT_FALSE(b.fb.EV_Koll);
  EXPECT_TRUE(b.fb.Q_MTst1);  // still requested on the measuring path

  // The measuring path: contact -> event 7.
  b.Scan(3);
  EXPECT_FALSE(b.fb.EV_Touch);
  EXPECT_FALSE(b.fb.Q_MTst);
  b.fb.I_MTast1 = true;
  b.fb.IDDS_1 = true;
  b.Scan();
  EXPECT_TRUE(b.fb.Q_MTst);
  EXPECT_TRUE(b.fb.EV_Touch);
  EXPECT_FALSE(b.fb.Q_MTstKol);
  EXPECT_TRUE(b.fb.QDDS_1);  // until the end of the measuring path

  // End of the measuring path (RE 30): latch enable off, event 7 kept for the NC.
  b.fb.EV_Mess = false;
  b.fb.I_MTast1 = false;
  b.fb.IDDS_1 = false;
  b.Scan();
  EXPECT_FALSE(b.fb.QDDS_1);
  EXPECT_FALSE(b.fb.QDDS_2);
  EXPECT_FALSE(b.fb.Q_MTst1);
  EXPECT_FALSE(b.fb.Q_MTstKmp);
  EXPECT_TRUE(b.fb.EV_Touch);
  EXPECT_FALSE(b.fb.FEHLER);
  EXPECT_EQ(b.fb.FEHLER_NR, 0);

  // The next measurement starts with event 7 clear.
  b.fb.EV_Koll = true;
  b.Scan();
  b.fb.EV_Mess = true;
  b.Scan();
  EXPECT_FALSE(b.fb.EV_Touch);
  EXPECT_TRUE(b.fb.QDDS_1);
}

TEST(QMFB1AxxTest, TheDrivesLatchCountsAsContactAndMustBeClearBeforeTheAcknowledgement) {
  Bench b = Lathe();
  Initialise(b);
  b.fb.EV_Koll = true;
  b.fb.I_MT_OK1 = true;
  b.Scan();
  b.fb.EV_Mess = true;
  b.fb.IDDS_2 = true;  // a stale latch of axis 2
  b.Scan(3);
  EXPECT_TRUE(b.fb.QDDS_2);
  EXPECT_TRUE(b.fb.EV_Koll);  // not acknowledged while a latch is set
  b.fb.IDDS_2 = false;
  b.Scan();
  EXPECT_FALSE(b.fb.EV_Koll);
  // A contact too short for the SPS input: only the drive saw it.
  b.fb.IDDS_2 = true;
  b.Scan();
  EXPECT_TRUE(b.fb.EV_Touch);
  EXPECT_FALSE(b.fb.Q_MTst);
}

TEST(QMFB1AxxTest, ProbeTwoAndNormallyClosedContact) {
  Bench b = Lathe();
  b.fb.MTD_RD.page.PIN_DDS = true;             // pin 5: probe 2
  b.fb.MTD_RD.page.Pushbutton_contact = true;  // NC contact: open = displaced
  Initialise(b);
  b.fb.EV_Koll = true;
  b.fb.I_MT_OK1 = true;  // probe 1 is not the one measured with
  b.Scan();
  EXPECT_FALSE(b.fb.Q_MTst1);
  EXPECT_TRUE(b.fb.Q_MTst2);
  EXPECT_FALSE(b.fb.Q_MTstOK);
  b.fb.I_MT_OK2 = true;
  b.fb.I_MTast2 = true;  // closed: at rest
  b.Scan();
  EXPECT_TRUE(b.fb.Q_MTstOK);
  EXPECT_FALSE(b.fb.Q_MTst);
  b.fb.EV_Mess = true;
  b.Scan(2);
  EXPECT_FALSE(b.fb.EV_Koll);
  b.fb.I_MTast2 = false;  // opens: displaced
  b.Scan();
  EXPECT_TRUE(b.fb.Q_MTst);
  EXPECT_TRUE(b.fb.EV_Touch);
}

TEST(QMFB1AxxTest, AContactOfAProbeThatIsNotReadyIsIgnored) {
  Bench b = Lathe();
  Initialise(b);
  ToMeasuringPath(b);
  b.fb.I_MT_OK1 = false;  // the Renishaw switches itself off: contact and ready trip together
  b.fb.I_MTast1 = true;
  b.Scan();
  EXPECT_FALSE(b.fb.Q_MTst);
  EXPECT_FALSE(b.fb.Q_MTstOK);
  EXPECT_FALSE(b.fb.EV_Touch);
  EXPECT_FALSE(b.fb.FEHLER);  // the manual has no "probe not ready" error
}

TEST(QMFB1AxxTest, CollisionDuringTheApproachIsLatchedUntilReset) {
  Bench b = Lathe();
  Initialise(b);
  b.fb.EV_Koll = true;
  b.fb.I_MT_OK1 = true;
  b.Scan();
  b.fb.I_MTast1 = true;  // displaced during the approach
  b.Scan();
  EXPECT_TRUE(b.fb.Q_MTstKol);
  EXPECT_FALSE(b.fb.FEHLER);  // a flag of its own, not an error number
  b.fb.I_MTast1 = false;
  b.Scan();
  EXPECT_TRUE(b.fb.Q_MTstKol);
  b.fb.EV_Mess = true;  // no latch, no acknowledgement after a collision
  b.Scan(3);
  EXPECT_FALSE(b.fb.QDDS_1);
  EXPECT_TRUE(b.fb.EV_Koll);
  b.fb.RESET = true;
  b.Scan();
  EXPECT_FALSE(b.fb.Q_MTstKol);
  EXPECT_TRUE(b.fb.Init_OK_1);  // RESET keeps the drives prepared
  b.fb.RESET = false;
  b.Scan(2);
  EXPECT_FALSE(b.fb.EV_Koll);  // the sequence goes on
  EXPECT_TRUE(b.fb.QDDS_1);
}

TEST(QMFB1AxxTest, ProbeDisplacedAtTheSetupPositionIsACollision) {
  Bench b = Lathe();
  Initialise(b);
  b.fb.EV_Koll = true;
  b.fb.I_MT_OK1 = true;
  b.Scan();
  b.fb.EV_Mess = true;
  b.fb.I_MTast1 = true;
  b.Scan(2);
  EXPECT_TRUE(b.fb.Q_MTstKol);
  EXPECT_TRUE(b.fb.EV_Koll);
  EXPECT_FALSE(b.fb.EV_Touch);
}

TEST(QMFB1AxxTest, TestPointNotFound) {
  Bench b = Lathe();
  Initialise(b);
  ToMeasuringPath(b);
  b.Scan(5);
  b.fb.EV_Mess = false;  // end of the measuring path without a contact
  b.Scan();
  EXPECT_TRUE(b.fb.Q_MTstKmp);
  EXPECT_FALSE(b.fb.EV_Touch);
  EXPECT_FALSE(b.fb.FEHLER);
  b.Scan(3);
  EXPECT_TRUE(b.fb.Q_MTstKmp);  // latched
  b.fb.RESET = true;
  b.Scan();
  EXPECT_FALSE(b.fb.Q_MTstKmp);
}

TEST(QMFB1AxxTest, MeasuringPathEndedBeforeTheAcknowledgementIsNoMissedTestPoint) {
  Bench b = Lathe();
  Initialise(b);
  b.fb.EV_Koll = true;
  b.Scan();
  b.fb.EV_Mess = true;  // probe not ready: no acknowledgement
  b.Scan(2);
  b.fb.EV_Mess = false;
  b.fb.EV_Koll = false;
  b.Scan();
  EXPECT_FALSE(b.fb.Q_MTstKmp);
  EXPECT_FALSE(b.fb.FEHLER);
}

// -- Error numbers (figure 7-28) --

struct AxisCase {
  int16_t nr1, nr2, nr3;
  int16_t fehler;  // 0: none
};

TEST(QMFB1AxxTest, ParameterErrorsAtTheBlock) {
  const AxisCase cases[] = {
      {0, 0, 0, 1},  {33, 1, 1, 2},  {1, 33, 1, 3}, {1, 1, 33, 4}, {-1, 1, 1, 5}, {1, -1, 1, 6},
      {1, 1, -1, 7}, {33, -1, 0, 2},  // "> 32" before "< 1"
      {1, 1, 33, 4}, {-1, 0, 33, 4}, {32, 0, 0, 0}, {1, 0, 0, 0},  {0, 0, 3, 0},  {-5, -5, -5, 5},
  };
  for (const AxisCase& c : cases) {
    SCOPED_TRACE(::testing::Message() << c.nr1 << ", " << c.nr2 << ", " << c.nr3);
    Bench b;
    b.fb.ENABLE = true;
    b.fb.ACHS_NR_1 = c.nr1;
    b.fb.ACHS_NR_2 = c.nr2;
    b.fb.ACHS_NR_3 = c.nr3;
    b.Scan();
    EXPECT_EQ(b.fb.FEHLER, c.fehler != 0);
    EXPECT_EQ(b.fb.FEHLER_NR, c.fehler);
  }
}

TEST(QMFB1AxxTest, AnErrorHoldsUntilResetOrDisable) {
  Bench b;
  b.fb.ENABLE = true;
  b.fb.ACHS_NR_1 = 40;
  b.Scan();
  EXPECT_EQ(b.fb.FEHLER_NR, 2);
  b.fb.ACHS_NR_1 = 1;  // corrected: the error stays
  b.Scan();
  EXPECT_TRUE(b.fb.FEHLER);
  EXPECT_EQ(b.fb.FEHLER_NR, 2);
  b.fb.RESET = true;
  b.Scan();
  EXPECT_FALSE(b.fb.FEHLER);
  EXPECT_EQ(b.fb.FEHLER_NR, 0);
  b.fb.RESET = false;
  b.Scan();
  EXPECT_FALSE(b.fb.FEHLER);

  b.fb.ACHS_NR_1 = 0;
  b.Scan();
  EXPECT_EQ(b.fb.FEHLER_NR, 1);
  b.fb.ENABLE = false;  // "pending errors are cleared and the FB is reset"
  b.Scan();
  EXPECT_FALSE(b.fb.FEHLER);
  EXPECT_EQ(b.fb.FEHLER_NR, 0);
  b.fb.ENABLE = true;  // still wrong: back at once
  b.Scan();
  EXPECT_EQ(b.fb.FEHLER_NR, 1);
  b.fb.RESET = true;  // while RESET is held, nothing is reported
  b.Scan(2);
  EXPECT_FALSE(b.fb.FEHLER);
}

TEST(QMFB1AxxTest, Error10EventsBeforeQ9992) {
  for (const bool koll : {true, false}) {
    Bench b = Lathe();
    b.Scan();
    if (koll) {
      b.fb.EV_Koll = true;
    } else {
      b.fb.EV_Mess = true;
    }
    b.Scan();
    EXPECT_TRUE(b.fb.FEHLER);
    EXPECT_EQ(b.fb.FEHLER_NR, 10);
    EXPECT_FALSE(b.fb.Q_MTst1);
  }
}

TEST(QMFB1AxxTest, Error12MeasuringPathWithoutCollisionEvent) {
  Bench b = Lathe();
  Initialise(b);
  b.fb.I_MT_OK1 = true;
  b.fb.EV_Mess = true;
  b.Scan();
  EXPECT_EQ(b.fb.FEHLER_NR, 12);
  EXPECT_FALSE(b.fb.QDDS_1);
}

TEST(QMFB1AxxTest, Error13CollisionEventWhileTheMeasuringPathEventIsSet) {
  Bench b = Lathe();
  Initialise(b);
  ToMeasuringPath(b);
  b.fb.EV_Koll = true;  // SE 29 on the measuring path
  b.Scan();
  EXPECT_EQ(b.fb.FEHLER_NR, 13);
  EXPECT_FALSE(b.fb.QDDS_1);
  EXPECT_FALSE(b.fb.Q_MTst1);
  EXPECT_TRUE(b.fb.Init_OK_1);  // the drives stay prepared
}

TEST(QMFB1AxxTest, BothEventsInOneScanAndEscapeAfterTheMeasuringPathAreNoErrors) {
  Bench b = Lathe();
  Initialise(b);
  b.fb.I_MT_OK1 = true;
  b.fb.EV_Koll = b.fb.EV_Mess = true;  // SE 29, SE 30 between two scans
  b.Scan(2);
  EXPECT_FALSE(b.fb.FEHLER);
  EXPECT_FALSE(b.fb.EV_Koll);
  b.fb.I_MTast1 = true;
  b.Scan();
  b.fb.I_MTast1 = false;
  b.fb.EV_Mess = false;  // RE 30 and SE 29 for the escape in the same scan
  b.fb.EV_Koll = true;
  b.Scan();
  EXPECT_FALSE(b.fb.FEHLER);
  EXPECT_TRUE(b.fb.EV_Touch);
}

TEST(QMFB1AxxTest, Error11And20To22FromThePage) {
  {
    Bench b = Lathe();
    b.fb.MTD_RD.page = {};
    b.fb.Q_FKT = true;
    b.Scan(2);
    EXPECT_EQ(b.fb.FEHLER_NR, 11);
    EXPECT_FALSE(b.fb.Q_FKT_Q);
  }
  for (int n = 0; n < 3; ++n) {
    Bench b;
    b.fb.ENABLE = true;
    b.fb.ACHS_NR_1 = n == 0 ? 0 : 1;
    b.fb.ACHS_NR_2 = n == 1 ? 0 : 2;
    b.fb.ACHS_NR_3 = n == 2 ? 0 : 3;
    b.fb.MTD_RD.page = {false, false, true, true, true};
    b.fb.Q_FKT = true;
    b.Scan(2);
    EXPECT_EQ(b.fb.FEHLER_NR, 20 + n);
    EXPECT_FALSE(b.fb.Init_OK_1 || b.fb.Init_OK_2 || b.fb.Init_OK_3);
    EXPECT_FALSE(b.fb.Q_FKT_Q);
  }
}

TEST(QMFB1AxxTest, Errors23To27ReadingThePage) {
  for (int element = 6; element <= 10; ++element) {
    Bench b = Lathe();
    b.fb.MTD_RD.failed_element = element;
    b.fb.Q_FKT = true;
    b.Scan();
    EXPECT_FALSE(b.fb.FEHLER);  // the read is under way
    b.Scan();
    EXPECT_EQ(b.fb.FEHLER_NR, 23 + element - 6);
    EXPECT_FALSE(b.fb.MTDaktiv);
    b.Scan(3);
    EXPECT_FALSE(b.fb.Q_FKT_Q);  // a failed initialisation is not acknowledged
  }
}

TEST(QMFB1AxxTest, Errors28To38And40WritingTheDrives) {
  struct Case {
    int axis, parameter, fehler;
  };
  const Case cases[] = {
      {0, 303, 28}, {1, 303, 29}, {2, 303, 30}, {0, 307, 31}, {1, 307, 32},
      {2, 307, 33}, {0, 169, 34}, {1, 169, 35}, {2, 169, 36}, {0, 170, 37},
      {1, 170, 38}, {2, 170, 40},  // the manual gives no number for S-0-0170 of axis 3
      {1, 401, 40},                // a parameter the block does not write
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(::testing::Message() << "axis " << c.axis + 1 << " S-0-0" << c.parameter);
    Bench b = Lathe();
    b.fb.ACHS_NR_3 = 3;
    b.fb.MTD_RD.page.Measuring_axis_3 = true;
    b.fb.AXD_WR[c.axis].failed_parameter = c.parameter;
    b.fb.Q_FKT = true;
    b.Scan(2 + c.axis + 1);  // page, then one scan per axis up to the failing one
    EXPECT_EQ(b.fb.FEHLER_NR, c.fehler);
    EXPECT_EQ(b.fb.Init_OK_1, c.axis > 0);  // the axes before it were prepared
    EXPECT_EQ(b.fb.Init_OK_2, c.axis > 1);
    EXPECT_FALSE(b.fb.Init_OK_3);
    EXPECT_FALSE(b.fb.AXDaktiv);
    EXPECT_FALSE(b.fb.Q_FKT_Q);
  }
  Bench b = Lathe();
  b.fb.AXD_WR[1].axis_exists = false;
  b.fb.Q_FKT = true;
  b.Scan(4);
  EXPECT_EQ(b.fb.FEHLER_NR, 40);
}

TEST(QMFB1AxxTest, AfterAFailedInitialisationResetRetriesTheStillPendingQ9992) {
  Bench b = Lathe();
  b.fb.AXD_WR[0].failed_parameter = 303;
  b.fb.Q_FKT = true;
  b.Scan(3);
  ASSERT_EQ(b.fb.FEHLER_NR, 28);
  b.fb.AXD_WR[0].failed_parameter = 0;
  b.fb.RESET = true;
  b.Scan();
  b.fb.RESET = false;
  b.Scan(4);
  EXPECT_FALSE(b.fb.FEHLER);
  EXPECT_TRUE(b.fb.Init_OK_1 && b.fb.Init_OK_2);
  EXPECT_TRUE(b.fb.Q_FKT_Q);
}

TEST(QMFB1AxxTest, DisabledChannelsAndFullProcessDataChannelsMakeTheInitialisationWait) {
  Bench b = Lathe();
  b.fb.MTDdisabl = true;
  b.fb.Q_FKT = true;
  b.Scan(3);
  EXPECT_FALSE(b.fb.MTDaktiv);
  EXPECT_FALSE(b.fb.FEHLER);
  b.fb.MTDdisabl = false;
  b.fb.MTD_RD.channels_occupied = true;
  b.Scan(2);
  EXPECT_TRUE(b.fb.P_Dat_ovr);
  EXPECT_FALSE(b.fb.MTDaktiv);
  b.fb.MTD_RD.channels_occupied = false;
  b.fb.AXDdisabl = true;
  b.Scan();
  EXPECT_FALSE(b.fb.P_Dat_ovr);
  EXPECT_TRUE(b.fb.MTDaktiv);
  b.Scan(3);
  EXPECT_FALSE(b.fb.AXDaktiv);
  EXPECT_FALSE(b.fb.Init_OK_1);
  b.fb.AXDdisabl = false;
  b.Scan(4);
  EXPECT_TRUE(b.fb.Init_OK_2);
  EXPECT_TRUE(b.fb.Q_FKT_Q);
}

TEST(QMFB1AxxTest, DisableResetsEverythingIncludingTheInitialisation) {
  Bench b = Lathe();
  Initialise(b);
  ToMeasuringPath(b);
  EXPECT_TRUE(b.fb.QDDS_1);
  b.fb.ENABLE = false;
  b.Scan();
  EXPECT_FALSE(b.fb.QDDS_1 || b.fb.Init_OK_1 || b.fb.Init_OK_2 || b.fb.Q_MTst1 || b.fb.Q_MTstOK ||
               b.fb.FEHLER);
  b.fb.ENABLE = true;
  b.fb.EV_Mess = false;
  b.Scan();
  b.fb.EV_Koll = true;  // a PROBE without a new SETTING
  b.Scan();
  EXPECT_EQ(b.fb.FEHLER_NR, 10);
}

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
