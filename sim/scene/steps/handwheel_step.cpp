// `handwheel: {axis, counts}`: the handwheel of a channel axis (or of X1 / Y1 of G31) turned by
// a number of counts.
#include "control/channel/channel.hpp"
#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/scene/steps/step_kind.hpp"

namespace vmt::sim {
namespace {

void Read(const StepSource& src, TimelineStep& s, std::ostringstream& text) {
  const YamlNode a = src.n["handwheel"];
  if (!src.nc.present) a.Fail("the scene has no nc: section");
  a.AllowKeys({"axis", "counts"});
  s.kind = TimelineStep::Kind::kHandwheel;
  RequireJogAxis(src.m, src.nc, a["axis"], s);
  s.code = a["counts"].Int();
  text << "handwheel " << a["axis"].String() << " " << s.code << " counts";
}

bool Play(const TimelineStep& s, const StepTick&, TimelinePlay& play) {
  if (play.channel && s.fictive >= 0)
    play.channel->HandwheelFictive(s.fictive, s.code);
  else if (play.channel)
    play.channel->Handwheel(s.axis, s.code);
  return true;
}

}  // namespace

const StepKind kHandwheelStep{"handwheel", Read, Play};

}  // namespace vmt::sim
