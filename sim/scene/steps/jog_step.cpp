// `jog: {axis, direction, hold}` holds a jog key of a channel axis (or of X1 / Y1 of G31) for a
// time; `jog: {axis, to}` jogs an axis to a position by one increment.
#include <cmath>

#include "control/channel/channel.hpp"
#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/scene/steps/step_kind.hpp"

namespace vmt::sim {
namespace {

void Read(const StepSource& src, TimelineStep& s, std::ostringstream& text) {
  const YamlNode a = src.n["jog"];
  if (!src.nc.present) a.Fail("the scene has no nc: section");
  a.AllowKeys({"axis", "direction", "hold", "to"});
  s.kind = TimelineStep::Kind::kJog;
  RequireJogAxis(src.m, src.nc, a["axis"], s);
  if (a.Has("to")) {
    // To a position, as an operator does it in incremental jog mode: the increment set to
    // the distance, one tap toward it (an increment once started is completed).
    if (s.fictive >= 0) a["to"].Fail("a fictive axis has no drive position");
    if (a.Has("direction")) a["direction"].Fail("give direction or to, not both");
    s.jog_to = true;
    s.target = a["to"].Double();
    s.wait_s = a.Has("hold") ? a["hold"].Double(0, kMaxSceneSeconds) : 0.05;
    if (s.wait_s <= 0) a["hold"].Fail("must be > 0");
    text << "jog " << a["axis"].String() << " to " << Fmt(s.target);
    return;
  }
  const std::string dir = a["direction"].String();
  if (dir != "+" && dir != "-") a["direction"].Fail("expected + or -");
  s.direction = dir == "+" ? 1 : -1;
  s.wait_s = a["hold"].Double(0, kMaxSceneSeconds);
  if (s.wait_s <= 0) a["hold"].Fail("must be > 0");
  text << "jog " << a["axis"].String() << dir << " for " << Fmt(s.wait_s) << " s";
}

// The key goes down when the step begins and comes up after `hold`.
bool Play(const TimelineStep& s, const StepTick& tick, TimelinePlay& play) {
  control::channel::Channel* channel = play.channel;
  if (!channel) return true;
  const bool first = tick.t_s == tick.since_s;
  if (s.fictive >= 0) {
    if (first) channel->JogFictive(s.fictive, s.direction);
    if (tick.t_s - tick.since_s < s.wait_s - 1e-9) return false;
    channel->JogFictive(s.fictive, 0);
    return true;
  }
  if (s.jog_to && first) {
    // The distance from the NC's position of the axis (the drive's actual one lags it by
    // the following error; before the NC has taken its axes over, the actual one is all
    // there is); none (already there) presses no key, and an increment of 0 would be
    // continuous jogging.
    const double from = channel->holds_positions()
                            ? channel->position(static_cast<size_t>(s.axis))
                            : tick.at.feedback[s.drive].position;
    const double to_go = s.target - from;
    if (std::abs(to_go) < 5e-4) return true;
    channel->SetJogIncrement(std::abs(to_go));
    channel->Jog(s.axis, to_go > 0 ? 1 : -1);
  } else if (first) {
    channel->Jog(s.axis, s.direction);
  }
  if (tick.t_s - tick.since_s < s.wait_s - 1e-9) return false;
  channel->Jog(s.axis, 0);
  return true;
}

}  // namespace

const StepKind kJogStep{"jog", Read, Play};

}  // namespace vmt::sim
