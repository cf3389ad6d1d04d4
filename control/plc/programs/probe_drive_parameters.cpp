#include "control/plc/programs/probe_drive_parameters.hpp"

#include <utility>

namespace vmt::control::plc {

ProbeDriveParameters AxdWrProbeParameters(const BasisMessPage& page) {
  const bool probe2 = page.PIN_DDS;
  const bool opens = page.Pushbutton_contact;  // normally closed: deflection opens it
  ProbeDriveParameters p;
  p.S_0_0170 = probe_control::kProbeCycleActive;
  p.S_0_0303 = probe2 ? 406 : 405;
  if (!probe2) {
    p.S_0_0169 = opens ? probe_control::kProbe1Negative : probe_control::kProbe1Positive;
    p.S_0_0307 = opens ? 410 : 409;
  } else {
    p.S_0_0169 = opens ? probe_control::kProbe2Negative : probe_control::kProbe2Positive;
    p.S_0_0307 = opens ? 412 : 411;
  }
  return p;
}

AxdWrResult WriteProbeParameters(const AxdWriter& axd_wr, int axis,
                                 const ProbeDriveParameters& p) {
  const std::pair<int, int64_t> writes[] = {
      {303, p.S_0_0303}, {307, p.S_0_0307}, {169, p.S_0_0169}, {170, p.S_0_0170}};
  for (const auto& [ident, value] : writes) {
    switch (axd_wr(axis, ident, value)) {
      case AxdWrStatus::kDone:
        continue;
      case AxdWrStatus::kNoAxis:
        return {false, 0};
      case AxdWrStatus::kRefused:
        return {true, ident};
    }
  }
  return {true, 0};
}

ProbeControl ProbeControlOf(const ProbeDriveParameters& p, bool qdds) {
  ProbeControl c;
  c.probe_cycle_command = p.S_0_0170;
  c.probe_control_parameter = p.S_0_0169;
  c.probe1_enable = qdds && p.S_0_0303 == 405;
  c.probe2_enable = qdds && p.S_0_0303 == 406;
  return c;
}

bool RealTimeStatusBit2(const ProbeDriveParameters& p, const ProbeStatus& status) {
  switch (p.S_0_0307) {
    case 409:
      return status.probe1.positive.latched;
    case 410:
      return status.probe1.negative.latched;
    case 411:
      return status.probe2.positive.latched;
    case 412:
      return status.probe2.negative.latched;
    default:
      return false;
  }
}

}  // namespace vmt::control::plc
