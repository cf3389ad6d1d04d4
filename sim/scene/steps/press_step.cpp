// `press: KEY` or `press: {name: KEY, for: S}`: the operator presses a machine key and lets it
// go after `for` seconds (0.1 s). It is read as three steps of the timeline (signal, wait,
// signal) and plays as them.
#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/scene/steps/step_kind.hpp"

namespace vmt::sim {

std::vector<TimelineStep> ReadPress(const MachineModel& m, const YamlNode& n, size_t i,
                                    const NcSetup& nc) {
  n.AllowKeys({"at", "press"});
  const YamlNode a = n["press"];
  const YamlNode name = a.IsMap() ? a["name"] : a;
  if (a.IsMap()) a.AllowKeys({"name", "for"});
  const double hold_s = a.IsMap() ? a.Double("for", 0.1, 0, kMaxSceneSeconds) : 0.1;
  if (!(hold_s > 0)) a["for"].Fail("must be > 0");
  const int io = control::IndexOf(m.io, name.String());
  if (io < 0 || !m.io[io].key) name.Fail("'" + name.String() + "' is not a key (io dir: key)");
  if (m.io[io].selector())
    name.Fail("'" + name.String() + "' is a selector: turn it with {signal: {name: " +
              name.String() + ", value: POSITION}}");
  TimelineStep press{}, hold{}, release{};
  press.kind = release.kind = TimelineStep::Kind::kSignal;
  press.signal = release.signal = RequireSignal(nc, name);
  press.not_before_s = n.Double("at", 0, 0, kMaxSceneSeconds);
  press.target = 1;
  release.target = 0;
  hold.kind = TimelineStep::Kind::kWait;
  hold.wait_s = hold_s;
  const std::string at = "timeline[" + std::to_string(i) + "]: ";
  press.text = at + "press " + name.String();
  hold.text = at + "hold " + name.String() + " " + Fmt(hold_s) + " s";
  release.text = at + "release " + name.String();
  return {press, hold, release};
}

}  // namespace vmt::sim
