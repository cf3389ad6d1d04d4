// The IEC 61131-3 standard timers TON, TOF and TP scan by scan, against the PLC clock passed in
// (4 ms scans unless a test says otherwise), with the edge cases where implementations tend to
// differ.

#include <gtest/gtest.h>

#include <chrono>

#include "control/plc/iec_standard_blocks.hpp"

namespace vmt::control::plc {
namespace {

using namespace std::chrono_literals;

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

}  // namespace
}  // namespace vmt::control::plc
