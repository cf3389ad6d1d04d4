#include "sim/runner/probe_glue.hpp"

#include <string_view>

#include "sim/model/gateway_layout.hpp"

namespace vmt::sim {

namespace gw = control::gateway;
using control::plc::AxdWrStatus;

ProbeGlue::ProbeGlue(const MachineModel& model, gw::SignalImage& image)
    : image_(&image), drives_(model.drives.size()) {
  for (const gw::GatewayLayout::Axis& a : GatewayLayoutOf(model).axes) {
    const int d = model.DriveIndex(a.name);
    if (d >= 0) drives_[d].axis = a.number;
  }
  for (int id = 0; id < image.size(); ++id) {
    const gw::Signal& s = image.table()[id];
    if (s.scope != gw::Scope::kAxis) continue;
    const std::string_view p = s.pattern;
    for (Drive& d : drives_) {
      if (d.axis != s.instance) continue;
      if (p == "AxxC.QDDS") d.qdds = id;
      if (p == "AxxS.IDDS") d.idds = id;
    }
  }
}

AxdWrStatus ProbeGlue::Write(int axis, int ident, int64_t value) {
  Drive* drive = nullptr;
  for (Drive& d : drives_)
    if (d.axis == axis && axis > 0) drive = &d;
  if (!drive) return AxdWrStatus::kNoAxis;
  control::plc::ProbeDriveParameters& p = drive->parameters;
  switch (ident) {
    case 303:
      if (value != 0 && value != 405 && value != 406) return AxdWrStatus::kRefused;
      p.S_0_0303 = static_cast<uint16_t>(value);
      break;
    case 307:
      if (value != 0 && (value < 409 || value > 412)) return AxdWrStatus::kRefused;
      p.S_0_0307 = static_cast<uint16_t>(value);
      break;
    case 169:
      if (value < 0 || value > 0xffff) return AxdWrStatus::kRefused;
      p.S_0_0169 = static_cast<uint16_t>(value);
      break;
    case 170:
      if (value < 0 || value > 3) return AxdWrStatus::kRefused;
      p.S_0_0170 = static_cast<uint8_t>(value);
      break;
    default:
      return AxdWrStatus::kRefused;  // a parameter vmt's drive does not have
  }
  drive->written = true;
  return AxdWrStatus::kDone;
}

void ProbeGlue::WriteSetpoints(control::MasterTelegram& mdt) const {
  for (size_t d = 0; d < drives_.size() && d < mdt.setpoints.size(); ++d) {
    const Drive& drive = drives_[d];
    if (!drive.written) continue;
    const bool qdds = drive.qdds >= 0 && image_->Bool(drive.qdds);
    mdt.setpoints[d].probe = control::plc::ProbeControlOf(drive.parameters, qdds);
  }
}

void ProbeGlue::ReadStatus(const control::AmplifierTelegram& at) {
  for (size_t d = 0; d < drives_.size() && d < at.feedback.size(); ++d) {
    const Drive& drive = drives_[d];
    if (!drive.written || drive.idds < 0) continue;
    image_->SetBool(drive.idds,
                    control::plc::RealTimeStatusBit2(drive.parameters, at.feedback[d].probe));
  }
}

}  // namespace vmt::sim
