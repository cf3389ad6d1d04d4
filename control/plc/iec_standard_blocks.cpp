// The IEC 61131-3 standard function blocks (see the header for their semantics).

#include "control/plc/iec_standard_blocks.hpp"

#include <algorithm>
#include <limits>

namespace vmt::control::plc {

namespace {

constexpr std::int16_t kIntMin = std::numeric_limits<std::int16_t>::min();
constexpr std::int16_t kIntMax = std::numeric_limits<std::int16_t>::max();

PlcTime NonNegative(PlcTime pt) { return std::max(pt, PlcTime{0}); }

}  // namespace

void TON::operator()(bool IN, PlcTime PT, PlcTime now) {
  PT = NonNegative(PT);
  if (!IN) {
    Q = false;
    ET = PlcTime{0};
  } else {
    if (!in_before_) start_ = now;
    // After running out, Q and ET hold until IN falls (see the header on changes of PT).
    if (!Q) {
      const PlcTime elapsed = now - start_;
      Q = elapsed >= PT;
      ET = Q ? PT : elapsed;
    }
  }
  in_before_ = IN;
}

void TOF::operator()(bool IN, PlcTime PT, PlcTime now) {
  PT = NonNegative(PT);
  if (IN) {
    Q = true;
    ET = PlcTime{0};
  } else {
    if (in_before_) start_ = now;
    // Only a delay started by a fall runs; once run out, Q and ET hold until IN rises.
    if (Q) {
      const PlcTime elapsed = now - start_;
      Q = elapsed < PT;
      ET = Q ? elapsed : PT;
    }
  }
  in_before_ = IN;
}

void TP::operator()(bool IN, PlcTime PT, PlcTime now) {
  PT = NonNegative(PT);
  const bool rising = IN && !in_before_;
  in_before_ = IN;
  // Q still TRUE from the previous call: the pulse runs and this rise is ignored, even if the
  // pulse ends in this call, as in IEC's diagram (a new pulse needs IN seen FALSE after it).
  if (rising && !Q) {
    start_ = now;
    Q = true;
  }
  if (Q) {
    const PlcTime elapsed = now - start_;
    Q = elapsed < PT;
    ET = Q ? elapsed : PT;
  }
  if (!Q && !IN) ET = PlcTime{0};
}

void R_TRIG::operator()(bool CLK) {
  Q = CLK && !m_;
  m_ = CLK;
}

void F_TRIG::operator()(bool CLK) {
  Q = !CLK && !m_;
  m_ = !CLK;
}

void SR::operator()(bool S1, bool R) { Q1 = S1 || (!R && Q1); }

void RS::operator()(bool S, bool R1) { Q1 = !R1 && (S || Q1); }

void CTU::operator()(bool CU, bool R, std::int16_t PV) {
  const bool up = CU && !cu_before_;
  cu_before_ = CU;
  if (R) {
    CV = 0;
  } else if (up && CV < kIntMax) {
    ++CV;
  }
  Q = CV >= PV;
}

void CTD::operator()(bool CD, bool LD, std::int16_t PV) {
  const bool down = CD && !cd_before_;
  cd_before_ = CD;
  if (LD) {
    CV = PV;
  } else if (down && CV > kIntMin) {
    --CV;
  }
  Q = CV <= 0;
}

void CTUD::operator()(bool CU, bool CD, bool R, bool LD, std::int16_t PV) {
  const bool up = CU && !cu_before_;
  const bool down = CD && !cd_before_;
  cu_before_ = CU;
  cd_before_ = CD;
  if (R) {
    CV = 0;
  } else if (LD) {
    CV = PV;
  } else if (up && !down && CV < kIntMax) {
    ++CV;
  } else if (down && !up && CV > kIntMin) {
    --CV;
  }
  QU = CV >= PV;
  QD = CV <= 0;
}

}  // namespace vmt::control::plc
