// `output: {name, value}`: the timeline sets a valve, as the machine's default PLC would.
#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/scene/steps/step_kind.hpp"

namespace vmt::sim {
namespace {

void Read(const StepSource& src, TimelineStep& s, std::ostringstream& text) {
  const YamlNode a = src.n["output"];
  a.AllowKeys({"name", "value"});
  s.kind = TimelineStep::Kind::kOutput;
  s.io = RequireIo(src.m, a["name"]);
  if (!src.m.io[s.io].is_output) a["name"].Fail("'" + a["name"].String() + "' is an input");
  if (src.plc)
    a["name"].Fail("the scene's PLC program drives the valves (a fault: step makes one stick)");
  s.level = a["value"].Bool();
  text << "output " << a["name"].String() << " = " << (s.level ? 1 : 0);
}

bool Play(const TimelineStep& s, const StepTick&, TimelinePlay& play) {
  play.outputs[s.io] = s.level;
  return true;
}

}  // namespace

const StepKind kOutputStep{"output", Read, Play};

}  // namespace vmt::sim
