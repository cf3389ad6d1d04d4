// The IEC 61131-3 standard function blocks scan by scan: timers against the PLC clock passed in
// (4 ms scans unless a test says otherwise), edge detectors, bistables and counters, with the
// edge cases where implementations tend to differ.

#include "control/plc/iec_standard_blocks.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <limits>

namespace vmt::control::plc {
namespace {

using namespace std::chrono_literals;

constexpr std::int16_t kIntMax = std::numeric_limits<std::int16_t>::max();
constexpr std::int16_t kIntMin = std::numeric_limits<std::int16_t>::min();

// Durations in ms for readable comparisons (and readable failure messages).
double Ms(PlcTime t) { return static_cast<double>(t.count()) / 1000.0; }

// ---- TON ------------------------------------------------------------------------------------

TEST(Ton, StaysOffWhileInIsFalse) {
  TON ton;
  for (PlcTime now = 0ms; now <= 100ms; now += 4ms) {
    ton(false, 10ms, now);
    EXPECT_FALSE(ton.Q);
    EXPECT_EQ(Ms(ton.ET), 0);
  }
}

TEST(Ton, QRisesInTheFirstScanWhoseElapsedTimeReachesPt) {
  TON ton;
  ton(true, 10ms, 0ms);
  EXPECT_FALSE(ton.Q);
  EXPECT_EQ(Ms(ton.ET), 0);
  ton(true, 10ms, 4ms);
  EXPECT_FALSE(ton.Q);
  EXPECT_EQ(Ms(ton.ET), 4);
  ton(true, 10ms, 8ms);
  EXPECT_FALSE(ton.Q);
  EXPECT_EQ(Ms(ton.ET), 8);
  ton(true, 10ms, 12ms);  // 12 ms elapsed >= 10 ms: ET is capped at PT
  EXPECT_TRUE(ton.Q);
  EXPECT_EQ(Ms(ton.ET), 10);
  ton(true, 10ms, 400ms);
  EXPECT_TRUE(ton.Q);
  EXPECT_EQ(Ms(ton.ET), 10);
}

TEST(Ton, ElapsedExactlyPtSetsQ) {
  TON ton;
  ton(true, 8ms, 0ms);
  ton(true, 8ms, 4ms);
  EXPECT_FALSE(ton.Q);
  ton(true, 8ms, 8ms);
  EXPECT_TRUE(ton.Q);
  EXPECT_EQ(Ms(ton.ET), 8);
}

TEST(Ton, TimesFromTheFirstCallThatSeesInTrue) {
  TON ton;
  ton(false, 10ms, 100ms);
  ton(true, 10ms, 104ms);
  ton(true, 10ms, 112ms);
  EXPECT_FALSE(ton.Q);
  EXPECT_EQ(Ms(ton.ET), 8);
  ton(true, 10ms, 116ms);
  EXPECT_TRUE(ton.Q);

  TON first;  // IN already TRUE on the very first call: timing starts there, not at time 0
  first(true, 10ms, 500ms);
  EXPECT_FALSE(first.Q);
  EXPECT_EQ(Ms(first.ET), 0);
  first(true, 10ms, 510ms);
  EXPECT_TRUE(first.Q);
}

TEST(Ton, FallOfInClearsQAndEtInTheSameScan) {
  TON ton;
  ton(true, 10ms, 0ms);
  ton(true, 10ms, 12ms);
  ASSERT_TRUE(ton.Q);
  ton(false, 10ms, 16ms);
  EXPECT_FALSE(ton.Q);
  EXPECT_EQ(Ms(ton.ET), 0);
}

TEST(Ton, PulseShorterThanPtNeverSetsQAndTheNextRiseTimesFromZero) {
  TON ton;
  ton(true, 10ms, 0ms);
  ton(true, 10ms, 4ms);
  ton(true, 10ms, 8ms);
  ton(false, 10ms, 12ms);  // IN fell 8 ms after rising: 2 ms short
  EXPECT_FALSE(ton.Q);
  EXPECT_EQ(Ms(ton.ET), 0);
  ton(true, 10ms, 16ms);
  EXPECT_EQ(Ms(ton.ET), 0);
  ton(true, 10ms, 24ms);
  EXPECT_FALSE(ton.Q);
  EXPECT_EQ(Ms(ton.ET), 8);
  ton(true, 10ms, 28ms);
  EXPECT_TRUE(ton.Q);
}

TEST(Ton, OneScanPulsesNeverSetQ) {
  TON ton;
  for (PlcTime now = 0ms; now <= 200ms; now += 4ms) {
    ton(now % 8ms == 0ms, 4ms, now);  // TRUE every other scan: never 4 ms long
    EXPECT_FALSE(ton.Q);
  }
}

TEST(Ton, ZeroPtPassesInThroughInTheSameScan) {
  TON ton;
  ton(false, 0ms, 0ms);
  EXPECT_FALSE(ton.Q);
  ton(true, 0ms, 4ms);
  EXPECT_TRUE(ton.Q);
  EXPECT_EQ(Ms(ton.ET), 0);
  ton(false, 0ms, 8ms);
  EXPECT_FALSE(ton.Q);
  ton(true, 0ms, 12ms);
  EXPECT_TRUE(ton.Q);
}

TEST(Ton, NegativePtCountsAsZero) {
  TON ton;
  ton(true, -5ms, 0ms);
  EXPECT_TRUE(ton.Q);
  EXPECT_EQ(Ms(ton.ET), 0);
}

TEST(Ton, PtIsReadEachScanWhileRunning) {
  TON ton;
  ton(true, 100ms, 0ms);
  ton(true, 100ms, 20ms);
  EXPECT_FALSE(ton.Q);
  ton(true, 10ms, 24ms);  // PT lowered below the 24 ms elapsed: runs out now
  EXPECT_TRUE(ton.Q);
  EXPECT_EQ(Ms(ton.ET), 10);
}

TEST(Ton, ChangesOfPtAfterRunningOutDoNotToggleQ) {
  TON ton;
  ton(true, 10ms, 0ms);
  ton(true, 10ms, 12ms);
  ASSERT_TRUE(ton.Q);
  ton(true, 1000ms, 16ms);
  EXPECT_TRUE(ton.Q);
  EXPECT_EQ(Ms(ton.ET), 10);
}

TEST(Ton, IrregularScansAndLongTimes) {
  TON ton;
  const PlcTime day = 24h;
  ton(true, 2h, day);
  ton(true, 2h, day + 1h + 59min + 59s + 999ms);
  EXPECT_FALSE(ton.Q);
  EXPECT_EQ(ton.ET, 1h + 59min + 59s + 999ms);
  ton(true, 2h, day + 2h + 3ms);
  EXPECT_TRUE(ton.Q);
  EXPECT_EQ(ton.ET, 2h);
}

// ---- TOF ------------------------------------------------------------------------------------

TEST(Tof, InFalseFromTheStartGivesNoDelay) {
  TOF tof;
  for (PlcTime now = 0ms; now <= 100ms; now += 4ms) {
    tof(false, 10ms, now);
    EXPECT_FALSE(tof.Q);
    EXPECT_EQ(Ms(tof.ET), 0);
  }
}

TEST(Tof, RiseOfInSetsQAtOnce) {
  TOF tof;
  tof(true, 10ms, 0ms);
  EXPECT_TRUE(tof.Q);
  EXPECT_EQ(Ms(tof.ET), 0);
  tof(true, 10ms, 400ms);
  EXPECT_TRUE(tof.Q);
  EXPECT_EQ(Ms(tof.ET), 0);
}

TEST(Tof, FallOfInClearsQPtLaterAndEtHoldsPt) {
  TOF tof;
  tof(true, 10ms, 0ms);
  tof(false, 10ms, 4ms);
  EXPECT_TRUE(tof.Q);
  EXPECT_EQ(Ms(tof.ET), 0);
  tof(false, 10ms, 8ms);
  EXPECT_TRUE(tof.Q);
  EXPECT_EQ(Ms(tof.ET), 4);
  tof(false, 10ms, 12ms);
  EXPECT_TRUE(tof.Q);
  EXPECT_EQ(Ms(tof.ET), 8);
  tof(false, 10ms, 16ms);  // 12 ms since the fall
  EXPECT_FALSE(tof.Q);
  EXPECT_EQ(Ms(tof.ET), 10);
  tof(false, 10ms, 400ms);
  EXPECT_FALSE(tof.Q);
  EXPECT_EQ(Ms(tof.ET), 10);
  tof(true, 10ms, 404ms);  // a rise resets ET
  EXPECT_TRUE(tof.Q);
  EXPECT_EQ(Ms(tof.ET), 0);
}

TEST(Tof, RiseDuringTheDelayRestartsItWithTheNextFall) {
  TOF tof;
  tof(true, 10ms, 0ms);
  tof(false, 10ms, 4ms);
  tof(false, 10ms, 12ms);
  EXPECT_EQ(Ms(tof.ET), 8);
  tof(true, 10ms, 16ms);
  EXPECT_TRUE(tof.Q);
  EXPECT_EQ(Ms(tof.ET), 0);
  tof(false, 10ms, 20ms);  // the full 10 ms again from here
  tof(false, 10ms, 28ms);
  EXPECT_TRUE(tof.Q);
  EXPECT_EQ(Ms(tof.ET), 8);
  tof(false, 10ms, 32ms);
  EXPECT_FALSE(tof.Q);
}

TEST(Tof, OneScanPulseOfInStretchesToPt) {
  TOF tof;
  tof(false, 10ms, 0ms);
  tof(true, 10ms, 4ms);
  EXPECT_TRUE(tof.Q);
  tof(false, 10ms, 8ms);
  tof(false, 10ms, 16ms);
  EXPECT_TRUE(tof.Q);
  tof(false, 10ms, 20ms);
  EXPECT_FALSE(tof.Q);
}

TEST(Tof, ZeroPtPassesInThroughInTheSameScan) {
  TOF tof;
  tof(true, 0ms, 0ms);
  EXPECT_TRUE(tof.Q);
  tof(false, 0ms, 4ms);
  EXPECT_FALSE(tof.Q);
  EXPECT_EQ(Ms(tof.ET), 0);
  tof(true, 0ms, 8ms);
  EXPECT_TRUE(tof.Q);
}

TEST(Tof, RaisingPtAfterRunningOutDoesNotSetQAgain) {
  TOF tof;
  tof(true, 10ms, 0ms);
  tof(false, 10ms, 4ms);
  tof(false, 10ms, 16ms);
  ASSERT_FALSE(tof.Q);
  tof(false, 1000ms, 20ms);
  EXPECT_FALSE(tof.Q);
  EXPECT_EQ(Ms(tof.ET), 10);
}

TEST(Tof, PtIsReadEachScanWhileRunning) {
  TOF tof;
  tof(true, 100ms, 0ms);
  tof(false, 100ms, 4ms);
  tof(false, 100ms, 24ms);
  EXPECT_TRUE(tof.Q);
  tof(false, 10ms, 28ms);
  EXPECT_FALSE(tof.Q);
  EXPECT_EQ(Ms(tof.ET), 10);
}

// ---- TP -------------------------------------------------------------------------------------

TEST(Tp, RiseGivesAPulseOfPtWhateverInDoes) {
  TP tp;
  tp(false, 10ms, 0ms);
  EXPECT_FALSE(tp.Q);
  tp(true, 10ms, 4ms);
  EXPECT_TRUE(tp.Q);
  EXPECT_EQ(Ms(tp.ET), 0);
  tp(false, 10ms, 8ms);  // an input pulse shorter than PT still gives the whole pulse
  EXPECT_TRUE(tp.Q);
  EXPECT_EQ(Ms(tp.ET), 4);
  tp(false, 10ms, 12ms);
  EXPECT_TRUE(tp.Q);
  EXPECT_EQ(Ms(tp.ET), 8);
  tp(false, 10ms, 16ms);  // 12 ms: the pulse is over, and with IN FALSE ET is back to 0
  EXPECT_FALSE(tp.Q);
  EXPECT_EQ(Ms(tp.ET), 0);
}

TEST(Tp, InLongerThanPtEndsThePulseAndEtHoldsPtUntilInFalls) {
  TP tp;
  tp(true, 10ms, 0ms);
  EXPECT_TRUE(tp.Q);
  tp(true, 10ms, 8ms);
  EXPECT_TRUE(tp.Q);
  tp(true, 10ms, 12ms);
  EXPECT_FALSE(tp.Q);
  EXPECT_EQ(Ms(tp.ET), 10);
  tp(true, 10ms, 400ms);
  EXPECT_FALSE(tp.Q);
  EXPECT_EQ(Ms(tp.ET), 10);
  tp(false, 10ms, 404ms);
  EXPECT_FALSE(tp.Q);
  EXPECT_EQ(Ms(tp.ET), 0);
}

TEST(Tp, FirstCallWithInTrueIsARise) {
  TP tp;
  tp(true, 10ms, 40ms);
  EXPECT_TRUE(tp.Q);
  tp(true, 10ms, 52ms);
  EXPECT_FALSE(tp.Q);
}

TEST(Tp, RisesDuringThePulseDoNotRetrigger) {
  TP tp;
  tp(true, 20ms, 0ms);
  tp(false, 20ms, 4ms);
  tp(true, 20ms, 8ms);  // ignored: the pulse still ends 20 ms after the first rise
  EXPECT_TRUE(tp.Q);
  EXPECT_EQ(Ms(tp.ET), 8);
  tp(false, 20ms, 12ms);
  tp(true, 20ms, 16ms);
  EXPECT_TRUE(tp.Q);
  EXPECT_EQ(Ms(tp.ET), 16);
  tp(true, 20ms, 20ms);
  EXPECT_FALSE(tp.Q);
  EXPECT_EQ(Ms(tp.ET), 20);
  tp(true, 20ms, 24ms);  // IN has been TRUE since a rise during the pulse: no new pulse
  EXPECT_FALSE(tp.Q);
  tp(false, 20ms, 28ms);
  tp(true, 20ms, 32ms);
  EXPECT_TRUE(tp.Q);
  EXPECT_EQ(Ms(tp.ET), 0);
}

TEST(Tp, RiseInTheScanThePulseEndsInIsIgnored) {
  TP tp;
  tp(true, 8ms, 0ms);
  tp(false, 8ms, 4ms);
  tp(true, 8ms, 8ms);
  EXPECT_FALSE(tp.Q);
  EXPECT_EQ(Ms(tp.ET), 8);
  tp(true, 8ms, 12ms);
  EXPECT_FALSE(tp.Q);
}

TEST(Tp, NewPulseOnceInWasSeenFalseAfterThePulse) {
  TP tp;
  tp(true, 8ms, 0ms);
  tp(true, 8ms, 8ms);
  ASSERT_FALSE(tp.Q);
  tp(false, 8ms, 12ms);
  tp(true, 8ms, 16ms);
  EXPECT_TRUE(tp.Q);
  EXPECT_EQ(Ms(tp.ET), 0);
  tp(true, 8ms, 24ms);
  EXPECT_FALSE(tp.Q);
}

TEST(Tp, ZeroPtGivesNoPulse) {
  TP tp;
  for (PlcTime now = 0ms; now <= 40ms; now += 4ms) {
    tp(now % 8ms == 0ms, 0ms, now);
    EXPECT_FALSE(tp.Q);
    EXPECT_EQ(Ms(tp.ET), 0);
  }
}

TEST(Tp, StaysOffWhileInIsFalse) {
  TP tp;
  for (PlcTime now = 0ms; now <= 40ms; now += 4ms) {
    tp(false, 10ms, now);
    EXPECT_FALSE(tp.Q);
    EXPECT_EQ(Ms(tp.ET), 0);
  }
}

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
