// `off: {axis}`: the drive's controller enable off.
#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/scene/steps/step_kind.hpp"

namespace vmt::sim {
namespace {

void Read(const StepSource& src, TimelineStep& s, std::ostringstream& text) {
  const YamlNode a = src.n["off"];
  a.AllowKeys({"axis"});
  s.kind = TimelineStep::Kind::kOff;
  s.drive = RequireDrive(src.m, a["axis"]);
  text << "controller enable off " << a["axis"].String();
}

bool Play(const TimelineStep& s, const StepTick&, TimelinePlay& play) {
  play.profiling[s.drive] = false;
  play.setpoints[s.drive] = {control::DriveMode::kOff, 0, 0};
  return true;
}

}  // namespace

const StepKind kOffStep{"off", Read, Play};

}  // namespace vmt::sim
