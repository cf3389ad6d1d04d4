// The fast-measurement function block QMFB1Axx (mtc200-fast-measurement.md 7.2) alone: its
// error numbers (figure 7-28), how they hold and reset, and the initialisation they make wait.

#include <gtest/gtest.h>

#include "control/plc/programs/probe_block.hpp"
#include "probe_block_test_support.hpp"

namespace vmt::control::plc {
namespace {

using namespace testing;  // vmt::control::plc::testing

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

}  // namespace
}  // namespace vmt::control::plc
