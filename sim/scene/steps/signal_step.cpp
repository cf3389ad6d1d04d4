// `signal: {name, value}`: the timeline writes a gateway signal, as the default PLC passes a
// panel key or value to the NC.
#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/scene/steps/step_kind.hpp"

namespace vmt::sim {
namespace {

void Read(const StepSource& src, TimelineStep& s, std::ostringstream& text) {
  const YamlNode a = src.n["signal"];
  a.AllowKeys({"name", "value"});
  s.kind = TimelineStep::Kind::kSignal;
  s.signal = RequireSignal(src.nc, a["name"]);
  const auto& sig = (*src.nc.signals)[s.signal];
  // The timeline plays the PLC and the operator: it writes what a PLC drives and presses
  // the machine keys; the NC's status and the machine's sensors are not its to set.
  const int io = control::IndexOf(src.m.io, sig.name);
  const bool key = io >= 0 && src.m.io[io].key;
  if (sig.direction == control::gateway::Direction::kNcToPlc)
    a["name"].Fail("the NC writes " + sig.name + ": a PLC cannot set it");
  if (sig.direction == control::gateway::Direction::kMachineToPlc && !key)
    a["name"].Fail(sig.name + " is a sensor of the machine: a PLC cannot set it");
  if (src.plc && !key)
    a["name"].Fail("the scene's PLC program writes " + sig.name +
                   ": with plc: the timeline only presses the operator's keys");
  s.target = SignalValue(src.nc, s.signal, a["value"]);
  if (key && !src.m.io[io].PositionOk(s.target))
    a["value"].Fail(sig.name + " is a selector: expected one of its positions " +
                    src.m.io[io].PositionList());
  text << "signal " << sig.name << " = " << Fmt(s.target);
}

bool Play(const TimelineStep& s, const StepTick&, TimelinePlay& play) {
  if (play.image) play.image->SetNumber(s.signal, s.target);
  return true;
}

}  // namespace

const StepKind kSignalStep{"signal", Read, Play};

}  // namespace vmt::sim
