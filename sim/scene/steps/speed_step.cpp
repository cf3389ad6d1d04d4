// `speed: {axis, rpm | feed, parameter_set}`: a drive in velocity control, a spindle in rpm.
#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/scene/steps/step_kind.hpp"

namespace vmt::sim {
namespace {

void Read(const StepSource& src, TimelineStep& s, std::ostringstream& text) {
  const YamlNode a = src.n["speed"];
  s.kind = TimelineStep::Kind::kSpeed;
  s.drive = RequireDrive(src.m, a["axis"]);
  if (src.m.drives[s.drive].info.kind == control::AxisKind::kRotary) {
    a.AllowKeys({"axis", "rpm", "parameter_set"});
    s.target = a["rpm"].Double(-kMaxRpm, kMaxRpm) * 6.0;  // rpm -> deg/s
    text << "speed " << a["axis"].String() << " " << Fmt(a["rpm"].Double(-kMaxRpm, kMaxRpm))
         << " rpm";
  } else {
    a.AllowKeys({"axis", "feed", "parameter_set"});
    s.target = a["feed"].Double(-kMaxFeed, kMaxFeed) / 60.0;
    text << "speed " << a["axis"].String() << " F" << Fmt(a["feed"].Double(-kMaxFeed, kMaxFeed));
  }
  s.parameter_set = ReadDriveParameterSet(a, text);
}

bool Play(const TimelineStep& s, const StepTick&, TimelinePlay& play) {
  play.profiling[s.drive] = false;
  play.setpoints[s.drive] = {control::DriveMode::kVelocity, s.target,
                             static_cast<uint8_t>(s.parameter_set)};
  return true;
}

}  // namespace

const StepKind kSpeedStep{"speed", Read, Play};

}  // namespace vmt::sim
