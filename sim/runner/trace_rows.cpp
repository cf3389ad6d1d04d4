#include "sim/runner/trace_rows.hpp"

#include <cstdio>

namespace vmt::sim {
namespace {

void Append(std::string& row, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, ",%.6f", v == 0 ? 0.0 : v);  // no "-0.000000"
  row += buf;
}

}  // namespace

std::string TraceHeader(const MachineModel& m, bool nc) {
  std::string h = "t";
  for (const DriveParams& d : m.drives) {
    const std::string& n = d.info.name;
    h += "," + n + ".cmd," + n + ".pos," + n + ".vel";
    if (d.spindle || d.info.kind == control::AxisKind::kRotary) h += "," + n + ".rpm";
    if (d.parameter_sets.size() > 1) h += "," + n + ".set";  // S-0-0254, current set
  }
  for (const DogClutch& k : m.clutches) h += "," + k.name + ".state";
  if (nc) h += ",nc.state,nc.line";
  return h + "\n";
}

std::string TraceRow(double t, const MachineModel& m, const control::AmplifierTelegram& at,
                     const control::MasterTelegram& mdt, const std::vector<ClutchState>& clutches,
                     const control::channel::Channel* channel) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6f", t);
  std::string row = buf;
  for (size_t d = 0; d < m.drives.size(); ++d) {
    const control::DriveFeedback& fb = at.feedback[d];
    Append(row, mdt.setpoints[d].mode == control::DriveMode::kOff ? 0.0 : mdt.setpoints[d].value);
    Append(row, fb.position);
    Append(row, fb.velocity);
    if (m.drives[d].spindle || m.drives[d].info.kind == control::AxisKind::kRotary)
      Append(row, fb.velocity / 6.0);
    if (m.drives[d].parameter_sets.size() > 1) Append(row, fb.parameter_set);
  }
  for (ClutchState c : clutches) Append(row, static_cast<int>(c));
  if (channel) {
    Append(row, static_cast<int>(channel->state()));
    Append(row, channel->line());
  }
  return row + "\n";
}

}  // namespace vmt::sim
