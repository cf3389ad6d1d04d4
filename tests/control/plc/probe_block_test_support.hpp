#pragma once
// Shared by the tests of the fast-measurement function block QMFB1Axx and its program
// (probe_block_*_test.cpp): the PLC scan, and the block alone on a bench, wired as on a lathe.

#include <gtest/gtest.h>

#include "control/plc/programs/probe_block.hpp"

namespace vmt::control::plc::testing {

inline constexpr PlcTime kScan{4000};

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
inline Bench Lathe() {
  Bench b;
  b.fb.ENABLE = true;
  b.fb.ACHS_NR_1 = 1;
  b.fb.ACHS_NR_2 = 2;
  b.fb.MTD_RD.page.Measuring_axis_1 = true;
  b.fb.MTD_RD.page.Measuring_axis_2 = true;
  return b;
}

/// Q9992 until the block acknowledges it (at most 10 scans), then the NC drops it.
inline void Initialise(Bench& b) {
  b.fb.Q_FKT = true;
  for (int i = 0; i < 10 && !b.fb.Q_FKT_Q; ++i) b.Scan();
  ASSERT_TRUE(b.fb.Q_FKT_Q);
  b.fb.Q_FKT = false;
  b.Scan();
  ASSERT_FALSE(b.fb.Q_FKT_Q);
}

/// From the start of a PROBE to the acknowledged setup position, the probe ready.
inline void ToMeasuringPath(Bench& b) {
  b.fb.EV_Koll = true;  // SE 29
  b.fb.I_MT_OK1 = true;
  b.Scan();
  b.fb.EV_Mess = true;  // SE 30 at the setup position
  b.Scan(2);            // arm, then acknowledge
  ASSERT_FALSE(b.fb.EV_Koll);
  ASSERT_FALSE(b.fb.FEHLER);
}

}  // namespace vmt::control::plc::testing
