// `wait: S`: the steps after it begin S seconds after it began.
#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/scene/steps/step_kind.hpp"

namespace vmt::sim {
namespace {

void Read(const StepSource& src, TimelineStep& s, std::ostringstream& text) {
  s.kind = TimelineStep::Kind::kWait;
  s.wait_s = src.n["wait"].Double(0, kMaxSceneSeconds);
  if (s.wait_s < 0) src.n["wait"].Fail("must be >= 0");
  text << "wait " << Fmt(s.wait_s) << " s";
}

bool Play(const TimelineStep& s, const StepTick& tick, TimelinePlay&) {
  return tick.t_s - tick.since_s >= s.wait_s - 1e-9;
}

}  // namespace

const StepKind kWaitStep{"wait", Read, Play};

}  // namespace vmt::sim
