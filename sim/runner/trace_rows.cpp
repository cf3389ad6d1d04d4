#include "sim/runner/trace_rows.hpp"

#include <algorithm>
#include <charconv>

namespace vmt::sim {
namespace {

// std::to_chars with a precision writes what printf's "%.6f" writes, byte for byte, without
// printf's format parsing and multi-precision arithmetic: a third of a kinematic run's time
// went into formatting the trace. A field is at most `width` characters (31 with its comma): a
// value past 1e23 (a drive gone wild) is cut there, as the trace has always cut it.
void AppendFixed6(std::string& row, double v, size_t width) {
  char buf[400];  // the longest fixed form of a double: 309 digits, sign, point, 6 decimals
  const std::to_chars_result r =
      std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 6);
  row.append(buf, std::min(static_cast<size_t>(r.ptr - buf), width));
}

void Append(std::string& row, double v) {
  row += ',';
  AppendFixed6(row, v == 0 ? 0.0 : v, 30);  // no "-0.000000"
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
  std::string row;
  row.reserve(16 + 16 * (4 * m.drives.size() + clutches.size() + 2));
  AppendFixed6(row, t, 31);
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
  row += '\n';
  return row;
}

}  // namespace vmt::sim
