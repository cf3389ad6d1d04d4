#pragma once
// What QMFB1Axx writes into a measuring axis's drive over AXD_WR when the NC outputs Q9992
// (fast-measurement manual 7.2 FEHLER_NR 28..39: S-0-0303, S-0-0307, S-0-0169, S-0-0170 in that
// order), worked out from BASISMESSPAGE, and how the two real-time bits then carry the enable
// and the latched flag between the PLC (AxxC.QDDS, AxxS.IDDS) and the drive (7.3).
//
// The manual names the parameters but not their values. These follow from 7.3 and the page:
// - S-0-0170 = 3: the probe function on.
// - The pin (element 6, PIN DDS): pin 4 is probe 1 (S-0-0405, S-0-0409/0410), pin 5 probe 2.
// - The contact (element 7): a normally open contact closes when the stylus is deflected, so
//   the contact is the input's 0-1 edge, the positive one; a normally closed contact opens: the
//   1-0 edge, the negative one. S-0-0169 selects that edge only: the stylus' return must not
//   overwrite anything.
// - S-0-0303 (real-time control bit 2) := the enable of that probe, so AxxC.QDDS arms it (7.2:
//   "initializes the AxxCQDDS interface signal ... for enabling the acceptance of the measured
//   value").
// - S-0-0307 (real-time status bit 2) := the latched flag of that edge, so AxxS.IDDS "becomes
//   TRUE when the measured value is accepted" (7.2 IDDS_1).

#include <cstdint>

#include "control/drive_bus.hpp"
#include "control/plc/axd_wr.hpp"
#include "control/plc/programs/probe_block.hpp"

namespace vmt::control::plc {

/// The four parameters of one measuring axis's drive; the allocations are SERCOS ident numbers
/// (405 = S-0-0405, ...).
struct ProbeDriveParameters {
  uint16_t S_0_0303 = 0;  ///< ident allocated to real-time control bit 2: 405 or 406
  uint16_t S_0_0307 = 0;  ///< ident allocated to real-time status bit 2: 409..412
  uint16_t S_0_0169 = 0;  ///< probe control parameter (probe_control::k* bits)
  uint8_t S_0_0170 = 0;   ///< probe cycle command: 3
};

/// The parameters AXD_WR writes for this page (see above).
ProbeDriveParameters AxdWrProbeParameters(const BasisMessPage& page);

/// AXD_WR of `p` into the drive of axis number `axis`, in the order of FEHLER_NR 28..39
/// (S-0-0303, S-0-0307, S-0-0169, S-0-0170); the first refusal ends it and is the answer.
AxdWrResult WriteProbeParameters(const AxdWriter& axd_wr, int axis, const ProbeDriveParameters& p);

/// The drive's probe control with real-time control bit 2 (AxxC.QDDS) at `qdds`: the enable
/// S-0-0303 names follows it, the other stays 0.
ProbeControl ProbeControlOf(const ProbeDriveParameters& p, bool qdds);

/// Real-time status bit 2 (AxxS.IDDS): the flag S-0-0307 names, false if it names none.
bool RealTimeStatusBit2(const ProbeDriveParameters& p, const ProbeStatus& status);

}  // namespace vmt::control::plc
