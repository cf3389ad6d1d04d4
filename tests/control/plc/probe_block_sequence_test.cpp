// The fast-measurement function block QMFB1Axx (mtc200-fast-measurement.md 7.2; 6.1 Q9992,
// 6.2 events 7/29/30) alone: its presets, the measuring sequence from Q9992 to the contact,
// the probes and contacts, collisions and a test point not found.

#include <gtest/gtest.h>

#include "control/plc/programs/probe_block.hpp"
#include "probe_block_test_support.hpp"

namespace vmt::control::plc {
namespace {

using namespace testing;  // vmt::control::plc::testing

// ---- The block alone -------------------------------------------------------------------------

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

}  // namespace
}  // namespace vmt::control::plc
