#include "sim/study/study_plan.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "common/input_file.hpp"
#include "sim/model/yaml_reader.hpp"

namespace vmt::sim::study {

const char* ToString(ReposMode m) {
  return m == ReposMode::kRepositioning ? "repositioning" : "restart";
}

namespace {

// A retract jog (a distance or a position, mm) within the reach of any lathe's axis.
constexpr double kMaxJogMm = 10000;

RetractPattern ReadRetract(const YamlNode& n, const Scene& scene) {
  if (!n.IsMap()) n.Fail("expected {name: ..., jogs: [{axis: X, mm: 20 | to: 150}, ...]}");
  n.AllowKeys({"name", "jogs"});
  RetractPattern r;
  r.name = n["name"].String();
  if (r.name.empty()) n["name"].Fail("a retract needs a name");
  const YamlNode jogs = n["jogs"];
  if (!jogs.IsSequence()) jogs.Fail("expected a list of jogs");
  for (size_t i = 0; i < jogs.size(); ++i) {
    const YamlNode j = jogs[i];
    if (!j.IsMap()) j.Fail("expected {axis: X, mm: 20} or {axis: X, to: 150}");
    j.AllowKeys({"axis", "mm", "to"});
    RetractJog jog;
    jog.axis = j["axis"].String();
    const auto& axes = scene.nc.data.axes;
    if (std::none_of(axes.begin(), axes.end(), [&](const auto& a) { return a.name == jog.axis; }))
      j["axis"].Fail("no NC axis " + jog.axis + " in this scene");
    if (j.Has("to")) {
      if (j.Has("mm")) j["mm"].Fail("give mm (a distance) or to (a position), not both");
      jog.to = j["to"].Double(-kMaxJogMm, kMaxJogMm);
    } else {
      jog.mm = j["mm"].Double(-kMaxJogMm, kMaxJogMm);
      if (jog.mm == 0) j["mm"].Fail("expected a distance, not 0");
    }
    r.jogs.push_back(jog);
  }
  return r;
}

// `manual: [[X, Z], [Z, X]]`: the orders in which the operator jogs the feed axes back (3.1:
// the order is the operator's). An axis not named is not jogged (it stays where the retract
// left it: a case that needs it ends without CREST, verdict error).
std::vector<Subroutine> ReadManualOrders(const YamlNode& n, const Scene& scene) {
  if (!n.IsSequence() || n.size() == 0)
    n.Fail("expected a list of axis orders, e.g. [[X, Z], [Z, X]]");
  std::vector<Subroutine> out;
  for (size_t i = 0; i < n.size(); ++i) {
    const YamlNode order = n[i];
    if (!order.IsSequence() || order.size() == 0)
      order.Fail("expected a list of NC axes, e.g. [X, Z]");
    Subroutine m;
    m.name = "manual ";
    for (size_t k = 0; k < order.size(); ++k) {
      const std::string axis = order[k].String();
      const auto& axes = scene.nc.data.axes;
      if (std::none_of(axes.begin(), axes.end(), [&](const auto& a) { return a.name == axis; }))
        order[k].Fail("no NC axis " + axis + " in this scene");
      if (std::find(m.manual_order.begin(), m.manual_order.end(), axis) != m.manual_order.end())
        order[k].Fail("axis " + axis + " twice in one order");
      m.manual_order.push_back(axis);
      m.name += (k ? "," : "") + axis;
    }
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace

StudyPlan LoadStudyPlan(const std::string& scene_path, const Scene& scene) {
  const YamlNode root = YamlNode::LoadFile(scene_path);
  if (!root.IsMap() || !root.Has("study")) root.Fail("a study needs a `study:` section");
  const YamlNode s = root["study"];
  if (!s.IsMap()) s.Fail("expected a map");
  s.AllowKeys({"interrupt", "retracts", "modes", "subroutines", "manual", "hold", "timeout"});
  if (!scene.nc.present) root.Fail("a study needs an `nc:` section");
  // The case's operator steps are NC and signal steps; an embedded PLC would take the keys.
  if (scene.plc.present)
    root["plc"].Fail("a study scene has no `plc:` (the study is the operator)");
  StudyPlan plan;
  const YamlNode in = s["interrupt"];
  if (!in.IsMap()) in.Fail("expected {every_ms: T} or {per_mille: [250, 750]}");
  in.AllowKeys({"every_ms", "per_mille"});
  if (in.Has("every_ms") == in.Has("per_mille")) in.Fail("expected one of every_ms, per_mille");
  if (in.Has("every_ms")) {
    plan.every_ms = in["every_ms"].Double(kMinEveryMs, kMaxEveryMs);
  } else {
    const YamlNode pm = in["per_mille"];
    if (!pm.IsSequence() || pm.size() == 0 || pm.size() > kMaxPerMillePoints)
      pm.Fail("expected a list of 1.." + std::to_string(kMaxPerMillePoints) + " points 0..1000");
    for (size_t i = 0; i < pm.size(); ++i) {
      plan.per_mille.push_back(pm[i].Int(0, 1000));
    }
  }
  const YamlNode rs = s["retracts"];
  if (!rs.IsSequence() || rs.size() == 0) rs.Fail("expected a list of retract patterns");
  for (size_t i = 0; i < rs.size(); ++i) {
    plan.retracts.push_back(ReadRetract(rs[i], scene));
    for (size_t k = 0; k + 1 < plan.retracts.size(); ++k)
      if (plan.retracts[k].name == plan.retracts.back().name)
        rs[i]["name"].Fail("two retracts named " + plan.retracts.back().name);
  }
  if (s.Has("modes")) {
    const YamlNode ms = s["modes"];
    if (!ms.IsSequence() || ms.size() == 0) ms.Fail("expected [repositioning, restart]");
    plan.modes.clear();
    for (size_t i = 0; i < ms.size(); ++i) {
      const std::string m = ms[i].String();
      if (m == "repositioning")
        plan.modes.push_back(ReposMode::kRepositioning);
      else if (m == "restart")
        plan.modes.push_back(ReposMode::kRestart);
      else
        ms[i].Fail("expected repositioning or restart");
    }
  }
  if (!s.Has("subroutines") && !s.Has("manual"))
    s.Fail("expected `subroutines:` (REPOS subroutines) and/or `manual:` (jog orders)");
  if (s.Has("subroutines")) {
    const YamlNode subs = s["subroutines"];
    if (!subs.IsSequence() || subs.size() == 0) subs.Fail("expected a list of NC files");
    for (size_t i = 0; i < subs.size(); ++i) {
      Subroutine sub{subs[i].String(), "", {}};
      sub.file = (std::filesystem::path(scene_path).parent_path() / sub.name).lexically_normal();
      // Checked here, before the reference run, so a wrong entry fails at once.
      if (const std::string why = common::InputFileProblem(sub.file); !why.empty())
        subs[i].Fail("cannot open NC program " + sub.file + ": " + why);
      for (const Subroutine& o : plan.subroutines)
        if (o.name == sub.name) subs[i].Fail("listed twice");
      plan.subroutines.push_back(sub);
    }
  }
  if (s.Has("manual"))
    for (Subroutine& m : ReadManualOrders(s["manual"], scene)) {
      for (const Subroutine& o : plan.subroutines)
        if (o.name == m.name) s["manual"].Fail("the order " + m.name + " listed twice");
      plan.subroutines.push_back(std::move(m));
    }
  plan.hold_s = s.Double("hold", plan.hold_s, 0.01, 60);
  plan.timeout_s = s.Double("timeout", plan.timeout_s, 0.1, 3600);
  return plan;
}

}  // namespace vmt::sim::study
