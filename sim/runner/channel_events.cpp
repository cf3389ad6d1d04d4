#include "sim/runner/channel_events.hpp"

#include <cmath>

#include "control/channel/channel.hpp"

namespace vmt::sim {
namespace {

double Micro(double v) { return std::round(v * 1000) / 1000; }  // mm to the µm, no binary noise

}  // namespace

nlohmann::ordered_json GuardEvent(double t, const control::channel::GuardRecord& r,
                                  const MachineModel& m) {
  const control::PathCheck& c = r.check;
  nlohmann::ordered_json e = {{"t", t}, {"event", "path_guard"}, {"move", r.move}};
  e["clear"] = c.clear;
  if (r.checks > 1) e["checks"] = r.checks;
  // The checked move, of the drives that move: an increment, a G77 or a closing move from
  // where it starts to its end (a continuous jog: to where it could brake at its last check).
  nlohmann::ordered_json from = nlohmann::ordered_json::object(), to = from;
  for (size_t d = 0; d < r.from.size() && d < r.to.size() && d < m.drives.size(); ++d)
    if (r.from[d] != r.to[d]) {
      from[m.drives[d].info.name] = Micro(r.from[d]) + 0.0;
      to[m.drives[d].info.name] = Micro(r.to[d]) + 0.0;
    }
  e["from"] = from;
  e["to"] = to;
  if (!c.clear) {
    e["parts"] = {c.part_a, c.part_b};
    e["point"] = {Micro(c.point[0]), Micro(c.point[1]), Micro(c.point[2])};
    e["distance"] = Micro(c.distance);
    nlohmann::ordered_json at = nlohmann::ordered_json::object();
    for (size_t d = 0; d < c.position.size() && d < m.drives.size(); ++d)
      if (r.from[d] != r.to[d]) at[m.drives[d].info.name] = Micro(c.position[d]);
    e["position"] = at;  // of the drives that move
    e["reaction"] = r.stopped ? "stop" : "warn";
  } else {
    e["min_clearance"] = Micro(c.min_clearance);
    e["closest"] = {c.closest_a, c.closest_b};
  }
  return e;
}

nlohmann::ordered_json StylusOverTravelEvent(const StylusOverTravel& o) {
  nlohmann::ordered_json e = {{"t", o.t_s}, {"event", "stylus"}, {"state", "over_travel"}};
  e["T"] = o.t_number;
  e["sphere"] = o.sphere + 1;
  e["parts"] = {o.sphere_part, o.part};
  const Eigen::Vector3d p = o.point_m * kMmPerM;
  const auto mm = [](double v) { return Micro(v) + 0.0; };  // + 0.0: no "-0.0" on the axis
  e["point"] = {mm(p.x()), mm(p.y()), mm(p.z())};
  return e;
}

nlohmann::ordered_json ProbeLatchEvent(double t, const std::string& drive, int pin, bool positive,
                                       const control::ProbeEdgeLatch& latch) {
  const auto nano = [](double v) { return std::round(v * 1e6) / 1e6 + 0.0; };
  nlohmann::ordered_json e = {{"t", t}, {"event", "probe_latch"}, {"drive", drive}};
  e["input"] = pin == 5 ? "PIN5" : "PIN4";
  e["edge"] = positive ? "positive" : "negative";
  e["measured_value"] = nano(latch.measured_value);
  e["exact_position"] = nano(latch.exact_position);
  e["sampling_error"] = nano(latch.measured_value - latch.exact_position);
  return e;
}

nlohmann::ordered_json ReposEvent(double t, const control::channel::ReposStatus& s) {
  nlohmann::ordered_json e = {{"t", t}, {"event", "repos"}};
  e["function"] = ToString(s.function);
  e["allowed"] = s.allowed;                          // PxxS.REPOS
  e["conditions_restored"] = s.conditions_restored;  // PxxS.CREST
  e["left_contour"] = s.left_contour;
  e["subroutine"] = s.subroutine_running;
  if (s.axes.empty()) return e;
  nlohmann::ordered_json axes = nlohmann::ordered_json::object();
  for (const control::channel::ReposAxisStatus& a : s.axes) {
    if (!a.relevant && a.final_value == 0 && a.distance_to_go == 0) {
      axes[a.name] = {{"command", Micro(a.command_value)}, {"relevant", false}};
      continue;
    }
    axes[a.name] = {{"final", Micro(a.final_value)},
                    {"command", Micro(a.command_value)},
                    {"to_go", Micro(a.distance_to_go)},
                    {"relevant", a.relevant},
                    {"adjust", a.adjust}};
  }
  e["axes"] = axes;
  const control::channel::ReposSpindleStatus& sp = s.spindle;
  e["spindle"] = {{"relevant", sp.relevant},
                  {"actual_rpm", Micro(sp.actual_rpm)},
                  {"command_rpm", Micro(sp.command_rpm)},
                  {"override", sp.override},
                  {"actual_m", sp.actual_m},
                  {"command_m", sp.command_m},
                  {"adjust", sp.adjust}};
  // 2.2, 7.3: every further spindle of the channel, as the main one.
  for (const control::channel::ReposFurtherSpindleStatus& f : s.further_spindles)
    e["spindles"][f.name] = {{"actual_rpm", Micro(f.actual_rpm)},
                             {"command_rpm", Micro(f.command_rpm)},
                             {"actual_m", f.actual_m},
                             {"command_m", f.command_m},
                             {"adjust", f.adjust}};
  if (s.tool_storage_relevant) e["tool_storage"] = {{"adjust", s.tool_storage_adjust}};
  e["F"] = s.programmed_feed;
  e["feed_override"] = s.feed_override;
  e["program"] = s.program;
  e["line"] = s.line;
  e["T"] = s.tool;
  e["D"] = s.correction;
  e["M"] = {s.spindle_m, s.coolant};
  e["G"] = s.g_codes;
  return e;
}

void ReposEventKey(const control::channel::ReposStatus& s, std::string& key) {
  key = ToString(s.function);
  key += s.allowed ? "A" : "a";
  key += s.conditions_restored ? "C" : "c";
  key += s.left_contour ? "L" : "l";
  key += s.subroutine_running ? "S" : "s";
  for (const control::channel::ReposAxisStatus& a : s.axes) key += a.adjust ? "1" : "0";
  key += s.spindle.adjust ? "1" : "0";
  for (const control::channel::ReposFurtherSpindleStatus& f : s.further_spindles)
    key += f.adjust ? "1" : "0";
  key += s.tool_storage_adjust ? "1" : "0";
}

nlohmann::ordered_json BlockSearchEvent(double t, const control::channel::Channel& channel,
                                        const std::string& warning) {
  const control::channel::BlockSearchStatus& st = channel.block_search();
  nlohmann::ordered_json e = {{"t", t}, {"event", "block_search"}};
  if (!warning.empty()) {
    e["warning"] = warning;
    return e;
  }
  e["state"] = ToString(st.state);
  e["active"] = st.active();
  e["block_count"] = st.block_count;
  e["dist_prog_start_mm"] = Micro(st.dist_prog_start);
  if (!st.continue_position.empty()) {
    nlohmann::ordered_json at = nlohmann::ordered_json::object();
    for (size_t a = 0; a < st.continue_position.size(); ++a)
      at[channel.AxisName(a)] = Micro(st.continue_position[a]);
    e["continue_position"] = at;
    e["path_deviation_mm"] = Micro(st.path_deviation);
  }
  return e;
}

}  // namespace vmt::sim
