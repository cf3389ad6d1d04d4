#pragma once
// AXD_WR, the SPS's system function that writes a drive parameter over the SERCOS service
// channel (fast-measurement 7.2: QMFB1Axx initialises the measuring axes' drives with it, and
// FEHLER_NR 28..40 are its failures). The PLC runtime offers it to the programs; whoever runs
// the PLC next to the drives connects it (the scene runner: sim/runner/probe_glue).

#include <cstdint>
#include <functional>

namespace vmt::control::plc {

/// What the drive answered.
enum class AxdWrStatus : uint8_t {
  kDone,     ///< the drive keeps the value
  kNoAxis,   ///< no drive has that axis number
  kRefused,  ///< the drive does not take that value for that parameter
};

/// Writes `value` into parameter S-0-`ident` of the drive of axis number `axis` (1..32).
using AxdWriter = std::function<AxdWrStatus(int axis, int ident, int64_t value)>;

}  // namespace vmt::control::plc
