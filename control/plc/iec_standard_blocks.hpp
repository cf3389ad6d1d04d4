#pragma once
// The IEC 61131-3 standard function blocks for the PLC runtime: timers (TON, TOF, TP), edge
// detectors (R_TRIG, F_TRIG), bistables (SR, RS) and counters (CTU, CTD, CTUD). Each is a plain
// struct with the IEC names of its outputs, called once per scan with its inputs in IEC order:
//   TON1(IN := x, PT := T#2s);  y := TON1.Q;   is   ton1(x, 2s, now);  y = ton1.Q;
//
// Time is the PLC's own clock, passed in by the caller (the scan's start time, `now`), never read
// from a wall clock: the PLC runs in lockstep with the simulated machine, so a run replays
// bit-identically however fast the host is. `now` must not decrease from one call to the next.
// Timers therefore resolve to the scan (4 ms by default): a state change falls in the first scan
// in which the time elapsed since the scan that saw IN change is >= PT. A negative PT counts as 0.
//
// Where IEC 61131-3 and CODESYS / TwinCAT differ, these follow IEC; the comments say where.

#include <chrono>
#include <cstdint>

namespace vmt::control::plc {

/// The PLC clock (IEC TIME): microseconds since the PLC started, signed 64 bit like LTIME. The
/// same alias as plc_runtime.hpp's (a redeclaration to the same type is allowed), so the blocks
/// take PlcScan::now() directly without this header depending on the runtime.
using PlcTime = std::chrono::microseconds;

// ---- Timers ---------------------------------------------------------------------------------
// While a timer runs it compares against the PT of the current call; once it has run out it keeps
// Q and ET (= the PT it ran out at) until IN changes, so a later change of PT cannot toggle Q.

/// On-delay: Q follows IN's rise PT late, and IN's fall at once. PT = 0 gives Q = IN.
struct TON {
  bool Q = false;
  PlcTime ET{};  ///< time IN has been TRUE, up to PT; 0 while IN is FALSE
  void operator()(bool IN, PlcTime PT, PlcTime now);

 private:
  bool in_before_ = false;
  PlcTime start_{};
};

/// Off-delay: Q follows IN's rise at once, and IN's fall PT late. An IN pulse during the delay
/// restarts it with the next fall. PT = 0 gives Q = IN. Q starts FALSE: no delay runs if IN is
/// FALSE from the first call on.
struct TOF {
  bool Q = false;
  PlcTime ET{};  ///< time IN has been FALSE since its last fall, up to PT; 0 while IN is TRUE
  void operator()(bool IN, PlcTime PT, PlcTime now);

 private:
  bool in_before_ = false;
  PlcTime start_{};
};

/// Pulse: a rise of IN gives a pulse of length PT on Q, whatever IN does meanwhile. Not
/// retriggerable: rises of IN while the pulse runs (up to and including the scan it ends in) are
/// ignored. ET holds PT after the pulse until IN is FALSE. PT = 0 gives no pulse at all.
struct TP {
  bool Q = false;
  PlcTime ET{};
  void operator()(bool IN, PlcTime PT, PlcTime now);

 private:
  bool in_before_ = false;
  PlcTime start_{};
};

// ---- Edge detection -------------------------------------------------------------------------

/// Q is TRUE for the one call in which CLK is TRUE after being FALSE. CLK counts as FALSE before
/// the first call, so a first call with CLK TRUE is an edge (IEC, and CODESYS / TwinCAT alike).
struct R_TRIG {
  bool Q = false;
  void operator()(bool CLK);

 private:
  bool m_ = false;  // CLK of the previous call
};

/// Q is TRUE for the one call in which CLK is FALSE after being TRUE.
/// First call: IEC 61131-3 defines M := NOT CLK with M initially FALSE, and says so in a note: a
/// first call with CLK FALSE gives Q TRUE (an edge after cold restart). This follows IEC.
/// CODESYS / TwinCAT report no edge there (their F_TRIG starts as if CLK had been FALSE).
struct F_TRIG {
  bool Q = false;
  void operator()(bool CLK);

 private:
  bool m_ = false;  // NOT CLK of the previous call, as IEC writes it
};

// ---- Bistables ------------------------------------------------------------------------------

/// Set-dominant latch: Q1 := S1 OR (NOT R AND Q1).
struct SR {
  bool Q1 = false;
  void operator()(bool S1, bool R);
};

/// Reset-dominant latch: Q1 := NOT R1 AND (S OR Q1).
struct RS {
  bool Q1 = false;
  void operator()(bool S, bool R1);
};

// ---- Counters -------------------------------------------------------------------------------
// INT counters as IEC defines them (PVmin = -32768, PVmax = 32767): counting stops at the limits
// instead of wrapping. They count rising edges of CU / CD (an edge on the first call if the input
// is TRUE); the edge memory follows the input even while R or LD holds the counter, so releasing
// R or LD with CU / CD still TRUE does not count. CODESYS V3 / TwinCAT count in WORD (0..65535)
// instead; with INT, CTD goes on below 0 down to -32768, as IEC says.

/// Up-counter: R sets CV to 0 (and wins over a CU edge); Q := CV >= PV.
struct CTU {
  bool Q = false;
  std::int16_t CV = 0;
  void operator()(bool CU, bool R, std::int16_t PV);

 private:
  bool cu_before_ = false;
};

/// Down-counter: LD loads CV := PV (and wins over a CD edge); Q := CV <= 0.
struct CTD {
  bool Q = false;
  std::int16_t CV = 0;
  void operator()(bool CD, bool LD, std::int16_t PV);

 private:
  bool cd_before_ = false;
};

/// Up/down counter: R (to 0) wins over LD (to PV), which wins over the edges; rising edges of CU
/// and CD in the same call cancel. QU := CV >= PV, QD := CV <= 0.
struct CTUD {
  bool QU = false;
  bool QD = false;
  std::int16_t CV = 0;
  void operator()(bool CU, bool CD, bool R, bool LD, std::int16_t PV);

 private:
  bool cu_before_ = false;
  bool cd_before_ = false;
};

}  // namespace vmt::control::plc
