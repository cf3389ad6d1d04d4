// `move: {axis, to, feed, parameter_set}`: a drive's position along a trapezoidal profile.
#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/scene/steps/step_kind.hpp"

namespace vmt::sim {
namespace {

void Read(const StepSource& src, TimelineStep& s, std::ostringstream& text) {
  const YamlNode a = src.n["move"];
  a.AllowKeys({"axis", "to", "feed", "parameter_set"});
  s.kind = TimelineStep::Kind::kMove;
  s.drive = RequireDrive(src.m, a["axis"]);
  s.target = a["to"].Double();
  RequireWithinTravel(src.m, s.drive, s.target, a["to"]);
  s.feed = a["feed"].Double(-kMaxFeed, kMaxFeed) / 60.0;  // mm/min | deg/min, as F words
  if (s.feed <= 0) a["feed"].Fail("must be > 0");
  text << "move " << a["axis"].String() << " to " << Fmt(s.target) << " at F" << Fmt(s.feed * 60);
  s.parameter_set = ReadDriveParameterSet(a, text);
}

bool Play(const TimelineStep& s, const StepTick& tick, TimelinePlay& play) {
  using control::DriveMode;
  const DriveParams& p = play.model->drives[s.drive];
  const double unit = p.info.kind == control::AxisKind::kLinear ? kMmPerM : kDegPerRad;
  // The profile keeps to the limits of the set the move names (set 0's if the drive lacks
  // it: the drive reports that itself).
  const size_t set = static_cast<size_t>(s.parameter_set);
  const DriveParameterSet& g = set < p.parameter_sets.size() ? p.parameter_sets[set] : p;
  // Start where the command is, or where the axis is if it was not position controlled.
  const double from = play.setpoints[s.drive].mode == DriveMode::kPosition
                          ? play.setpoints[s.drive].value
                          : tick.at.feedback[s.drive].position;
  play.profiles[s.drive] = {from, s.target, std::min(s.feed, g.velocity_limit * unit),
                            g.acceleration_limit * unit, tick.t_s};
  play.profiling[s.drive] = true;
  play.setpoints[s.drive] = {DriveMode::kPosition, from, static_cast<uint8_t>(s.parameter_set)};
  return true;
}

}  // namespace

const StepKind kMoveStep{"move", Read, Play};

}  // namespace vmt::sim
