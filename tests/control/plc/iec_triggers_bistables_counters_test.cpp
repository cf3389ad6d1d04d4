// The IEC 61131-3 standard edge detectors (R_TRIG, F_TRIG), bistables (SR, RS) and counters
// (CTU, CTD, CTUD) scan by scan, with the edge cases where implementations tend to differ, and
// the blocks together as a PLC program uses them.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <limits>

#include "control/plc/iec_standard_blocks.hpp"

namespace vmt::control::plc {
namespace {

using namespace std::chrono_literals;

constexpr std::int16_t kIntMax = std::numeric_limits<std::int16_t>::max();
constexpr std::int16_t kIntMin = std::numeric_limits<std::int16_t>::min();

// ---- R_TRIG / F_TRIG ------------------------------------------------------------------------

TEST(RTrig, FirstCallWithClkTrueIsAnEdge) {
  R_TRIG trig;
  trig(true);
  EXPECT_TRUE(trig.Q);
  trig(true);
  EXPECT_FALSE(trig.Q);
}

TEST(RTrig, OneCallPerRisingEdge) {
  R_TRIG trig;
  const bool clk[] = {false, false, true, true, true, false, true, false, false, true};
  const bool q[] = {false, false, true, false, false, false, true, false, false, true};
  for (int i = 0; i < 10; ++i) {
    trig(clk[i]);
    EXPECT_EQ(trig.Q, q[i]) << "call " << i;
  }
}

// IEC (M := NOT CLK, M initially FALSE, and the standard's note on cold restart): an edge.
// CODESYS / TwinCAT report none here.
TEST(FTrig, FirstCallWithClkFalseIsAnEdgeAsInIec) {
  F_TRIG trig;
  trig(false);
  EXPECT_TRUE(trig.Q);
  trig(false);
  EXPECT_FALSE(trig.Q);
}

TEST(FTrig, FirstCallWithClkTrueIsNoEdge) {
  F_TRIG trig;
  trig(true);
  EXPECT_FALSE(trig.Q);
  trig(false);
  EXPECT_TRUE(trig.Q);
}

TEST(FTrig, OneCallPerFallingEdge) {
  F_TRIG trig;
  const bool clk[] = {true, true, false, false, true, false, true, true, false};
  const bool q[] = {false, false, true, false, false, true, false, false, true};
  for (int i = 0; i < 9; ++i) {
    trig(clk[i]);
    EXPECT_EQ(trig.Q, q[i]) << "call " << i;
  }
}

// ---- SR / RS --------------------------------------------------------------------------------

struct LatchCase {
  bool set, reset, before, after;
};

TEST(Sr, TruthTableWithSetDominant) {
  const LatchCase cases[] = {
      {false, false, false, false}, {false, false, true, true},  {true, false, false, true},
      {true, false, true, true},    {false, true, false, false}, {false, true, true, false},
      {true, true, false, true},    {true, true, true, true},
  };
  for (const LatchCase& c : cases) {
    SR sr;
    sr.Q1 = c.before;
    sr(c.set, c.reset);
    EXPECT_EQ(sr.Q1, c.after) << "S1 " << c.set << " R " << c.reset << " Q1 " << c.before;
  }
}

TEST(Rs, TruthTableWithResetDominant) {
  const LatchCase cases[] = {
      {false, false, false, false}, {false, false, true, true},  {true, false, false, true},
      {true, false, true, true},    {false, true, false, false}, {false, true, true, false},
      {true, true, false, false},   {true, true, true, false},
  };
  for (const LatchCase& c : cases) {
    RS rs;
    rs.Q1 = c.before;
    rs(c.set, c.reset);
    EXPECT_EQ(rs.Q1, c.after) << "S " << c.set << " R1 " << c.reset << " Q1 " << c.before;
  }
}

TEST(Sr, LatchesAcrossScans) {
  SR sr;
  EXPECT_FALSE(sr.Q1);
  sr(true, false);
  sr(false, false);
  sr(false, false);
  EXPECT_TRUE(sr.Q1);
  sr(true, true);
  EXPECT_TRUE(sr.Q1);
  sr(false, true);
  EXPECT_FALSE(sr.Q1);
  sr(false, false);
  EXPECT_FALSE(sr.Q1);
}

TEST(Rs, LatchesAcrossScans) {
  RS rs;
  EXPECT_FALSE(rs.Q1);
  rs(true, false);
  rs(false, false);
  EXPECT_TRUE(rs.Q1);
  rs(true, true);
  EXPECT_FALSE(rs.Q1);
  rs(false, false);
  EXPECT_FALSE(rs.Q1);
}

// ---- CTU ------------------------------------------------------------------------------------

TEST(Ctu, CountsRisingEdgesOnlyAndQAtPv) {
  CTU ctu;
  ctu(false, false, 3);
  EXPECT_EQ(ctu.CV, 0);
  EXPECT_FALSE(ctu.Q);
  ctu(true, false, 3);
  ctu(true, false, 3);  // held: no count
  ctu(true, false, 3);
  EXPECT_EQ(ctu.CV, 1);
  ctu(false, false, 3);
  ctu(true, false, 3);
  EXPECT_EQ(ctu.CV, 2);
  EXPECT_FALSE(ctu.Q);
  ctu(false, false, 3);
  ctu(true, false, 3);
  EXPECT_EQ(ctu.CV, 3);
  EXPECT_TRUE(ctu.Q);
  ctu(false, false, 3);
  ctu(true, false, 3);
  EXPECT_EQ(ctu.CV, 4);  // counts on past PV
  EXPECT_TRUE(ctu.Q);
  ctu(false, false, 5);  // Q follows a changed PV without a count
  EXPECT_FALSE(ctu.Q);
}

TEST(Ctu, FirstCallWithCuTrueCounts) {
  CTU ctu;
  ctu(true, false, 1);
  EXPECT_EQ(ctu.CV, 1);
  EXPECT_TRUE(ctu.Q);
}

TEST(Ctu, ResetWinsOverAnEdgeAndReleasingItWithCuHeldDoesNotCount) {
  CTU ctu;
  ctu(true, false, 2);
  ctu(false, false, 2);
  ctu(true, false, 2);
  ASSERT_TRUE(ctu.Q);
  ctu(false, false, 2);
  ctu(false, true, 2);
  EXPECT_EQ(ctu.CV, 0);
  EXPECT_FALSE(ctu.Q);
  ctu(true, true, 2);  // edge while R: R wins
  EXPECT_EQ(ctu.CV, 0);
  ctu(true, false, 2);  // CU still TRUE when R falls: that edge is gone
  EXPECT_EQ(ctu.CV, 0);
  ctu(false, false, 2);
  ctu(true, false, 2);
  EXPECT_EQ(ctu.CV, 1);
}

TEST(Ctu, PvAtOrBelowZeroGivesQAtOnce) {
  CTU ctu;
  ctu(false, false, 0);
  EXPECT_TRUE(ctu.Q);
  ctu(false, true, -5);
  EXPECT_TRUE(ctu.Q);
}

TEST(Ctu, SaturatesAtIntMax) {
  CTU ctu;
  for (int i = 0; i < kIntMax + 10; ++i) {
    ctu(true, false, kIntMax);
    ctu(false, false, kIntMax);
  }
  EXPECT_EQ(ctu.CV, kIntMax);
  EXPECT_TRUE(ctu.Q);
}

// ---- CTD ------------------------------------------------------------------------------------

TEST(Ctd, LoadsPvAndCountsDownToQ) {
  CTD ctd;
  ctd(false, true, 2);
  EXPECT_EQ(ctd.CV, 2);
  EXPECT_FALSE(ctd.Q);
  ctd(true, false, 2);
  ctd(true, false, 2);  // held: no count
  EXPECT_EQ(ctd.CV, 1);
  EXPECT_FALSE(ctd.Q);
  ctd(false, false, 2);
  ctd(true, false, 2);
  EXPECT_EQ(ctd.CV, 0);
  EXPECT_TRUE(ctd.Q);
}

// IEC counts on below 0 (PVmin is INT's minimum); CODESYS / TwinCAT (WORD) stop at 0.
TEST(Ctd, CountsBelowZeroAsInIec) {
  CTD ctd;
  ctd(false, true, 1);
  for (int i = 0; i < 3; ++i) {
    ctd(true, false, 1);
    ctd(false, false, 1);
  }
  EXPECT_EQ(ctd.CV, -2);
  EXPECT_TRUE(ctd.Q);
}

TEST(Ctd, WithoutLoadCountsDownFromZero) {
  CTD ctd;
  ctd(true, false, 5);  // the first call with CD TRUE is an edge
  EXPECT_EQ(ctd.CV, -1);
  EXPECT_TRUE(ctd.Q);
}

TEST(Ctd, LoadWinsOverAnEdgeAndReleasingItWithCdHeldDoesNotCount) {
  CTD ctd;
  ctd(true, true, 3);
  EXPECT_EQ(ctd.CV, 3);
  ctd(true, false, 3);  // CD still TRUE when LD falls: that edge is gone
  EXPECT_EQ(ctd.CV, 3);
  ctd(false, false, 3);
  ctd(true, false, 3);
  EXPECT_EQ(ctd.CV, 2);
  ctd(false, true, 7);  // a reload while counting
  EXPECT_EQ(ctd.CV, 7);
  ctd(false, true, -4);
  EXPECT_EQ(ctd.CV, -4);
  EXPECT_TRUE(ctd.Q);
}

TEST(Ctd, SaturatesAtIntMin) {
  CTD ctd;
  ctd(false, true, kIntMin + 1);
  for (int i = 0; i < 5; ++i) {
    ctd(true, false, 0);
    ctd(false, false, 0);
  }
  EXPECT_EQ(ctd.CV, kIntMin);
  EXPECT_TRUE(ctd.Q);
}

// ---- CTUD -----------------------------------------------------------------------------------

TEST(Ctud, CountsUpAndDownWithQuAndQd) {
  CTUD c;
  c(false, false, false, false, 2);
  EXPECT_EQ(c.CV, 0);
  EXPECT_FALSE(c.QU);
  EXPECT_TRUE(c.QD);
  c(true, false, false, false, 2);
  c(true, false, false, false, 2);  // held: no count
  EXPECT_EQ(c.CV, 1);
  EXPECT_FALSE(c.QU);
  EXPECT_FALSE(c.QD);
  c(false, false, false, false, 2);
  c(true, false, false, false, 2);
  EXPECT_EQ(c.CV, 2);
  EXPECT_TRUE(c.QU);
  c(true, true, false, false, 2);
  EXPECT_EQ(c.CV, 1);
  EXPECT_FALSE(c.QU);
  c(true, false, false, false, 2);
  c(true, true, false, false, 2);
  EXPECT_EQ(c.CV, 0);
  EXPECT_TRUE(c.QD);
  c(true, false, false, false, 2);
  c(true, true, false, false, 2);
  EXPECT_EQ(c.CV, -1);  // on below 0, as CTD
  EXPECT_TRUE(c.QD);
}

TEST(Ctud, SimultaneousEdgesCancel) {
  CTUD c;
  c(false, false, false, true, 5);
  c(true, true, false, false, 5);
  EXPECT_EQ(c.CV, 5);
  c(false, false, false, false, 5);
  c(true, true, false, false, 5);
  EXPECT_EQ(c.CV, 5);
}

TEST(Ctud, ResetWinsOverLoadWhichWinsOverEdges) {
  CTUD c;
  c(true, false, true, true, 5);
  EXPECT_EQ(c.CV, 0);
  c(false, false, false, true, 5);
  EXPECT_EQ(c.CV, 5);
  EXPECT_TRUE(c.QU);
  EXPECT_FALSE(c.QD);
  c(true, false, false, true, 5);  // an up edge while LD: LD wins
  EXPECT_EQ(c.CV, 5);
  c(true, true, false, false, 5);  // CU held since then: only the down edge counts
  EXPECT_EQ(c.CV, 4);
  c(false, false, true, false, 5);
  EXPECT_EQ(c.CV, 0);
  EXPECT_FALSE(c.QU);
  EXPECT_TRUE(c.QD);
}

TEST(Ctud, ReleasingResetOrLoadWithAnInputHeldDoesNotCount) {
  CTUD c;
  c(false, false, false, true, 5);
  c(false, true, false, true, 5);  // a down edge while LD
  c(false, true, false, false, 5);
  EXPECT_EQ(c.CV, 5);
  c(false, false, true, false, 5);
  c(true, false, true, false, 5);  // an up edge while R
  c(true, false, false, false, 5);
  EXPECT_EQ(c.CV, 0);
}

TEST(Ctud, SaturatesAtBothEnds) {
  CTUD c;
  c(false, false, false, true, kIntMax);
  c(true, false, false, false, kIntMax);
  EXPECT_EQ(c.CV, kIntMax);
  EXPECT_TRUE(c.QU);
  c(false, false, false, true, kIntMin);
  c(false, true, false, false, kIntMin);
  EXPECT_EQ(c.CV, kIntMin);
  EXPECT_TRUE(c.QD);
}

// ---- Together, as a PLC program uses them -----------------------------------------------------

// A button press (R_TRIG) starts a 100 ms pulse (TP) that counts (CTU): one press, one count,
// however long the button is held and however often it is pressed during the pulse.
TEST(Blocks, ComposeOncePerScan) {
  R_TRIG press;
  TP pulse;
  CTU count;
  const auto scan = [&](bool button, PlcTime now) {
    press(button);
    pulse(press.Q, 100ms, now);
    count(pulse.Q, false, 10);
  };
  PlcTime now = 0ms;
  for (int i = 0; i < 50; ++i, now += 4ms) scan(i >= 5, now);  // held 180 ms
  EXPECT_EQ(count.CV, 1);
  EXPECT_FALSE(pulse.Q);
  for (int i = 0; i < 10; ++i, now += 4ms) scan(i % 2 == 0, now);  // chatter
  EXPECT_EQ(count.CV, 2);
  EXPECT_TRUE(pulse.Q);
}

}  // namespace
}  // namespace vmt::control::plc
