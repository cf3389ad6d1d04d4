#include "sim/station/station_frames.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "control/channel/channel.hpp"
#include "control/measure/measuring_pages.hpp"
#include "control/nc/modal_g_codes.hpp"
#include "render/mesh_primitives.hpp"
#include "sim/runner/channel_events.hpp"
#include "sim/scene/steps/timeline_play.hpp"

namespace vmt::sim::station {
namespace {

using Json = nlohmann::ordered_json;

/// Rounded to 1e-6 of its unit: the page needs no more, and the frames stay short (+ 0.0: no
/// "-0.0" on an axis).
double Short(double v) { return std::round(v * 1e6) / 1e6 + 0.0; }

Json Array(const Eigen::Vector3d& v) {
  return Json::array({Short(v.x()), Short(v.y()), Short(v.z())});
}

Json Pose(const Eigen::Isometry3d& X) {
  const Eigen::Quaterniond q(X.rotation());
  const Eigen::Vector3d p = X.translation();
  return Json::array({Short(p.x()), Short(p.y()), Short(p.z()), Short(q.x()), Short(q.y()),
                      Short(q.z()), Short(q.w())});
}

/// A mesh placed by `X` (its origin in the link), with its colour.
Json MeshJson(const std::string& name, const render::Mesh& mesh, const Eigen::Isometry3d& X,
              const render::Rgba& colour) {
  Json positions = Json::array(), normals = Json::array();
  for (size_t i = 0; i + 2 < mesh.positions.size(); i += 3) {
    const Eigen::Vector3d p =
        X * Eigen::Vector3d(mesh.positions[i], mesh.positions[i + 1], mesh.positions[i + 2]);
    positions.push_back(Short(p.x()));
    positions.push_back(Short(p.y()));
    positions.push_back(Short(p.z()));
  }
  for (size_t i = 0; i + 2 < mesh.normals.size(); i += 3) {
    const Eigen::Vector3d n =
        X.linear() * Eigen::Vector3d(mesh.normals[i], mesh.normals[i + 1], mesh.normals[i + 2]);
    normals.push_back(std::round(n.x() * 1e4) / 1e4);
    normals.push_back(std::round(n.y() * 1e4) / 1e4);
    normals.push_back(std::round(n.z() * 1e4) / 1e4);
  }
  return {{"name", name},
          {"positions", std::move(positions)},
          {"normals", std::move(normals)},
          {"indices", mesh.indices},
          {"colour", {colour.r, colour.g, colour.b, colour.a}}};
}

std::vector<std::string> ProgramLines(const Scene& scene) {
  std::vector<std::string> lines;
  if (scene.nc.programs.empty() || scene.nc.programs[0]->program.files.empty()) return lines;
  std::ifstream in(scene.nc.programs[0]->program.files[0]);
  for (std::string line; std::getline(in, line) && lines.size() < 100000;) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(std::move(line));
  }
  return lines;
}

const char* Unit(control::AxisKind kind) {
  return kind == control::AxisKind::kLinear ? "mm" : "deg";
}

/// An event's JSON as a panel of the state: without its time and kind.
Json Panel(nlohmann::ordered_json event) {
  event.erase("t");
  event.erase("event");
  return Json(event);
}

/// The headstock's panel: the changeover's mode and target, and the PLC's side of it.
Json HeadstockPanel(const control::channel::Channel& ch, const control::gateway::SignalImage* image,
                    const StationMarks& marks) {
  const control::axes::HeadstockChangeover* hs = ch.headstock();
  if (!hs) return nullptr;
  Json panel = {{"mode", ToString(hs->mode())},
                {"target", ToString(hs->target())},
                {"busy", hs->busy()},
                {"axis", ch.HeadstockAxisName()},
                {"position", Short(ch.HeadstockPosition())}};
  Json signals = Json::object();
  if (image)
    for (int id = 0; id < image->size(); ++id) {
      const std::string& name = image->table()[id].name;
      const size_t dot = name.find('.');
      const std::string family = dot == std::string::npos ? "" : name.substr(dot + 1);
      if (family == "ROTMOD" || family == "ROTMOD_Q" || family == "SPMOD" || family == "SPMOD_Q")
        signals[name] = image->Bool(id);
    }
  panel["signals"] = std::move(signals);
  Json clutches = Json::object();
  for (const auto& [name, state] : marks.clutches) clutches[name] = state;
  panel["clutches"] = std::move(clutches);
  return panel;
}

}  // namespace

void StationMarks::Note(const nlohmann::ordered_json& event) {
  const std::string kind = event.value("event", "");
  if (kind == "path_guard") {
    if (!event.value("clear", true) && event.contains("point")) {
      Json point = Json::array();
      for (const auto& c : event["point"]) point.push_back(c.get<double>() / kMmPerM);
      guard = Json{{"parts", event.value("parts", Json::array())},
                   {"point", point},
                   {"move", event.value("move", "")}}
                  .dump();
    }
  } else if (kind == "probe_latch") {
    probe = Json{{"drive", event.value("drive", "")},
                 {"value", event.value("measured_value", 0.0)},
                 {"t", event.value("t", 0.0)},
                 {"edge", event.value("edge", "")}}
                .dump();
    if (latches.size() == kLatchesKept) latches.erase(latches.begin());
    latches.push_back(probe);
  } else if (kind == "clutch") {
    clutches[event.value("name", "")] = event.value("state", "");
  } else if (kind == "nc" && event.value("state", "") == "idle") {
    guard.clear();  // Control-Reset acknowledged the refusal
  }
}

std::string ModelJson(const SceneRun& run, const std::string& pace) {
  const Scene& scene = run.scene();
  const MachineModel& m = *scene.model;
  Json links = Json::array();
  for (const Link& link : m.links) {
    Json visuals = Json::array();
    for (const Visual& v : link.visuals)
      if (v.mesh) visuals.push_back(MeshJson(v.name, *v.mesh, v.X_LinkVisual, v.colour));
    links.push_back({{"name", link.name}, {"visuals", std::move(visuals)}});
  }
  // The workpiece, as the pictures show it: a visual of the link that holds it.
  const int wp_link = scene.workpiece.present ? m.LinkIndex(scene.workpiece.part.link) : -1;
  if (wp_link >= 0)
    for (const RevolvedSection& s : scene.workpiece.part.sections) {
      const double length = s.z1_m - s.z0_m;
      const render::Mesh mesh = s.r_inner_m > 0
                                    ? render::MakeTube(s.r_inner_m, s.r_outer_m, length, 96)
                                    : render::MakeCylinder(s.r_outer_m, length, 96);
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      X.translation().z() = s.z0_m;
      links[wp_link]["visuals"].push_back(MeshJson("workpiece", mesh, X, scene.workpiece.colour));
    }
  Json cameras = Json::array();
  for (const NamedCamera& c : scene.cameras)
    cameras.push_back({{"name", c.name},
                       {"eye", Array(c.eye_m)},
                       {"target", Array(c.target_m)},
                       {"up", Array(c.up)},
                       {"fov_deg", c.fov_y_deg}});
  Json keys = Json::array(), selectors = Json::array();
  for (const control::IoInfo& io : m.io) {
    if (io.selector())
      selectors.push_back(
          {{"name", io.name}, {"positions", io.positions}, {"initial", io.initial}});
    else if (io.key)
      keys.push_back(io.name);
  }
  Json axes = Json::array();
  if (const control::channel::Channel* ch = run.channel()) {
    for (size_t a = 0; a < ch->config().axes.size(); ++a)
      axes.push_back(
          {{"name", ch->AxisName(a)}, {"unit", ch->config().axes[a].rotary ? "deg" : "mm"}});
  } else {
    for (const DriveParams& d : m.drives)
      axes.push_back({{"name", d.info.name}, {"unit", Unit(d.info.kind)}});
  }
  Json handwheel = Json::array();
  if (const control::channel::Channel* ch = run.channel()) {
    for (size_t a = 0; a < ch->config().axes.size(); ++a) handwheel.push_back(ch->AxisName(a));
    handwheel.push_back("X1");  // G31's fictive axes (REPOS manual 5.2)
    handwheel.push_back("Y1");
  }
  Json program = nullptr;
  if (!scene.nc.programs.empty() && !scene.nc.programs[0]->program.files.empty())
    program = {{"file", scene.nc.programs[0]->program.files[0]}, {"lines", ProgramLines(scene)}};
  return Json{{"scene", scene.name},
              {"pace", pace},
              {"end_s", run.end_s()},
              {"links", std::move(links)},
              {"cameras", cameras},
              {"keys", keys},
              {"selectors", std::move(selectors)},
              {"handwheel_axes", std::move(handwheel)},
              {"axes", axes},
              {"program", program},
              {"signals_count", scene.nc.signals ? scene.nc.signals->size() : 0}}
      .dump();
}

namespace {

// The probes' switches as the PLC sees them: the contact input and the ready message.
Json ProbeSwitchesJson(const MachineModel& m, const control::gateway::SignalImage* image) {
  Json list = Json::array();
  auto value = [&](int io) -> Json {
    if (io < 0 || !image) return nullptr;
    const int id = image->Find(m.io[io].name);
    return id >= 0 ? Json(image->Bool(id)) : Json(nullptr);
  };
  for (const ProbeStylus& p : m.probes)
    list.push_back({{"pin", p.pin5 ? "PIN5" : "PIN4"},
                    {"t", p.t_number},
                    {"contact", p.contact_input >= 0 ? Json(m.io[p.contact_input].name) : Json()},
                    {"on", value(p.contact_input)},
                    {"ready_input", p.ready_input >= 0 ? Json(m.io[p.ready_input].name) : Json()},
                    {"ready", p.ready_input >= 0 ? value(p.ready_input) : Json(true)}});
  return list;
}

// The machine data pages of fast measurement as MTD( ) reads them: every element of each page's
// rows, the rows of styluses, spheres, points and compares only where something is set.
Json MeasuringPagesJson(const control::measure::MeasuringPages& pages) {
  namespace measure = control::measure;
  Json out = Json::array();
  for (const measure::Page page : measure::kPages) {
    const int number = pages.NumberOf(page), elements = measure::ElementCount(page);
    Json designations = Json::array();
    for (int e = 1; e <= elements; ++e)
      designations.push_back(measure::ElementDesignation(page, e));
    std::vector<std::pair<std::optional<double>, std::optional<double>>> rows;
    bool sparse = true;
    switch (page) {
      case measure::Page::kBasisMessPage:
      case measure::Page::kZwischenspeicherPage:
        for (int p = 0; p < pages.config.processes; ++p) rows.push_back({p, std::nullopt});
        sparse = false;
        break;
      case measure::Page::kTastwerkzeugPage:
        for (int t = 1; t <= measure::kStyluses; ++t) rows.push_back({t, std::nullopt});
        break;
      case measure::Page::kEichwertePage:
        for (int t = 1; t <= measure::kStyluses; ++t)
          for (int k = 1; k <= measure::kSpheres; ++k) rows.push_back({t, k});
        break;
      case measure::Page::kPointPage:
      case measure::Page::kErgebnisPage: {
        const int n =
            page == measure::Page::kPointPage ? pages.config.points : pages.config.results;
        for (int p = 0; p < pages.config.processes; ++p)
          for (int k = 1; k <= n; ++k) rows.push_back({p, k});
        break;
      }
    }
    Json list = Json::array();
    for (const auto& [lv1, lv2] : rows) {
      Json values = Json::array();
      bool set = !sparse;
      for (int e = 1; e <= elements; ++e) {
        const measure::MtdRead r =
            measure::ReadMtd(pages, {double(number), lv1, lv2, double(e)}, 0);
        values.push_back(r.error.empty() ? Short(r.value) : 0.0);
        set = set || (r.error.empty() && r.value != 0);
      }
      if (set)
        list.push_back({{"lv1", lv1 ? Json(*lv1) : Json()},
                        {"lv2", lv2 ? Json(*lv2) : Json()},
                        {"values", std::move(values)}});
    }
    out.push_back({{"name", measure::PageName(page)},
                   {"number", number},
                   {"elements", std::move(designations)},
                   {"rows", std::move(list)}});
  }
  return out;
}

}  // namespace

std::string StateJson(const SceneRun& run, int64_t plc_cycle, const std::string& run_state,
                      size_t events, const StationMarks& marks) {
  const MachineModel& m = *run.scene().model;
  Json poses = Json::array();
  for (const Eigen::Isometry3d& X : LinkPoses(m, run.joint_positions())) poses.push_back(Pose(X));
  const control::AmplifierTelegram& at = run.feedback();
  Json axes = Json::array(), nc = nullptr, messages = Json::array();
  Json repos = nullptr, headstock = nullptr, block_search = nullptr;
  if (const control::channel::Channel* ch = run.channel()) {
    double feed_sq = 0;
    for (size_t a = 0; a < ch->config().axes.size(); ++a) {
      const int d = ch->config().axes[a].drive;
      const bool fed = d >= 0 && static_cast<size_t>(d) < at.feedback.size();
      const double actual = fed ? at.feedback[d].position : ch->position(a);
      if (fed && !ch->config().axes[a].rotary)
        feed_sq += at.feedback[d].velocity * at.feedback[d].velocity;
      axes.push_back({{"name", ch->AxisName(a)},
                      {"machine", Short(actual)},
                      {"command", Short(ch->position(a))},
                      {"program", Short(ch->position(a) - ch->Translation(a))},
                      {"following_error", fed ? Short(at.feedback[d].following_error) : 0.0}});
    }
    const control::nc::ModalState& modal = ch->modal();
    Json g = Json::array();
    for (int code : control::nc::ActiveGCodes(modal)) {
      char text[8];
      std::snprintf(text, sizeof text, "G%02d", code);
      g.push_back(text);
    }
    const control::channel::SpindleStatus sp = ch->spindle_status();
    nc = {{"state", ToString(ch->state())},
          {"mode", ToString(ch->mode())},
          {"line", ch->line()},
          {"modal", std::move(g)},
          {"tool", {{"t", modal.tool}, {"d", modal.correction}}},
          {"feed", {{"command", modal.feed}, {"actual", Short(std::sqrt(feed_sq) * 60)}}},
          {"spindle",
           {{"command", sp.programmed_rpm},
            {"actual", Short(sp.actual_rpm)},
            {"shown", sp.speeds_shown}}},
          {"override", {{"feed", sp.feed_override}, {"spindle", sp.spindle_override}}}};
    repos = Panel(ReposEvent(run.time_s(), ch->repos_status(&at)));
    block_search = Panel(BlockSearchEvent(run.time_s(), *ch));
    headstock = HeadstockPanel(*ch, run.image(), marks);
    for (const control::channel::OperatorMessage& msg : ch->messages())
      messages.push_back({{"number", msg.number},
                          {"text", msg.text.empty() ? "PLC message " + std::to_string(msg.number) +
                                                          " (" + std::to_string(msg.parameter) + ")"
                                                    : msg.text},
                          {"source", ToString(msg.source)}});
  } else {
    for (size_t d = 0; d < m.drives.size() && d < at.feedback.size(); ++d)
      axes.push_back({{"name", m.drives[d].info.name},
                      {"machine", Short(at.feedback[d].position)},
                      {"following_error", Short(at.feedback[d].following_error)}});
  }
  // Where the operator's selectors stand (the override switches).
  Json selectors = Json::object();
  if (const control::gateway::SignalImage* image = run.image())
    for (const control::IoInfo& io : m.io)
      if (const int id = io.selector() ? image->Find(io.name) : -1; id >= 0)
        selectors[io.name] = image->Int(id);
  const std::optional<Eigen::Vector3d> tip = run.ToolTip();
  Json probe = nullptr;
  if (!marks.probe.empty()) {
    probe = Json::parse(marks.probe);
    const std::optional<Eigen::Vector3d> point = run.ProbeLatchPoint();
    probe["point"] = point ? Array(*point) : Json(nullptr);
    Json latches = Json::array();
    for (const std::string& latch : marks.latches) latches.push_back(Json::parse(latch));
    probe["latches"] = std::move(latches);
  }
  return Json{{"t", run.time_s()},
              {"cycle", plc_cycle},
              {"run", run_state},
              {"poses", std::move(poses)},
              {"tool_tip", tip ? Array(*tip) : Json(nullptr)},
              {"nc", std::move(nc)},
              {"axes", std::move(axes)},
              {"messages", std::move(messages)},
              {"selectors", std::move(selectors)},
              {"events", events},
              {"guard", marks.guard.empty() ? Json(nullptr) : Json::parse(marks.guard)},
              {"probe", std::move(probe)},
              {"probe_switches", ProbeSwitchesJson(m, run.image())},
              {"measuring_pages",
               run.measuring_pages() ? MeasuringPagesJson(*run.measuring_pages()) : Json(nullptr)},
              {"repos", std::move(repos)},
              {"headstock", std::move(headstock)},
              {"block_search", std::move(block_search)},
              {"stock", run.stock_cuts()}}
      .dump();
}

std::string StockJson(const SceneRun& run) {
  Json cylinders = Json::array();
  std::string link;
  for (const CylinderPart& c : run.TurnedStockCylinders()) {
    link = c.link;
    cylinders.push_back(
        {Short(c.z_m), Short(c.length_m), Short(c.radius_m), Short(c.inner_radius_m)});
  }
  return Json{{"version", run.stock_cuts()}, {"link", link}, {"cylinders", std::move(cylinders)}}
      .dump();
}

std::string SignalsJson(SceneRun& run) {
  const control::gateway::SignalImage* image = run.image();
  Json list = Json::array();
  if (image)
    for (int id = 0; id < image->size(); ++id) {
      const control::gateway::Signal& s = image->table()[id];
      Json value;
      if (s.type == control::gateway::SignalType::kString)
        value = image->String(id);
      else
        value = image->Number(id);
      list.push_back({{"name", s.name},
                      {"area", s.name.substr(0, s.name.find('.'))},
                      {"direction", ToString(s.direction)},
                      {"type", ToString(s.type)},
                      {"value", std::move(value)},
                      {"writable", run.OperateError(s.name).empty()}});
    }
  return Json{{"t", run.time_s()}, {"signals", std::move(list)}}.dump();
}

}  // namespace vmt::sim::station
