// `orient: {axis, to, parameter_set}`: a spindle to an angle in position control.
#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/scene/steps/step_kind.hpp"

namespace vmt::sim {
namespace {

void Read(const StepSource& src, TimelineStep& s, std::ostringstream& text) {
  const YamlNode a = src.n["orient"];
  a.AllowKeys({"axis", "to", "parameter_set"});
  s.kind = TimelineStep::Kind::kOrient;
  s.drive = RequireDrive(src.m, a["axis"]);
  if (!src.m.drives[s.drive].spindle) a["axis"].Fail("orient needs a spindle drive");
  s.target = a["to"].Double();
  text << "orient " << a["axis"].String() << " to " << Fmt(s.target);
  s.parameter_set = ReadDriveParameterSet(a, text);
}

bool Play(const TimelineStep& s, const StepTick&, TimelinePlay& play) {
  play.profiling[s.drive] = false;
  play.setpoints[s.drive] = {control::DriveMode::kPosition, s.target,
                             static_cast<uint8_t>(s.parameter_set)};
  return true;
}

}  // namespace

const StepKind kOrientStep{"orient", Read, Play};

}  // namespace vmt::sim
