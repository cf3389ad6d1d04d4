// The table of timeline step kinds, and the reading of a step: its common keys here, the rest by
// its kind.
#include "sim/scene/steps/step_kind.hpp"

#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"

namespace vmt::sim {

namespace {
const StepKind* const kKinds[] = {&kMoveStep,   &kSpeedStep,     &kOrientStep, &kOffStep,
                                  &kOutputStep, &kWaitStep,      &kWaitUntilStep,
                                  &kNcStep,     &kJogStep,       &kHandwheelStep,
                                  &kSignalStep, &kFaultStep};
}  // namespace

const StepKind* FindStepKind(const YamlNode& n) {
  for (const StepKind* k : kKinds)
    if (n.Has(k->key)) return k;
  return nullptr;
}

const StepKind& StepKindOf(TimelineStep::Kind kind) {
  using Kind = TimelineStep::Kind;
  switch (kind) {
    case Kind::kMove:
      return kMoveStep;
    case Kind::kSpeed:
      return kSpeedStep;
    case Kind::kOrient:
      return kOrientStep;
    case Kind::kOff:
      return kOffStep;
    case Kind::kOutput:
      return kOutputStep;
    case Kind::kWait:
      return kWaitStep;
    case Kind::kWaitUntil:
      return kWaitUntilStep;
    case Kind::kJog:
      return kJogStep;
    case Kind::kHandwheel:
      return kHandwheelStep;
    case Kind::kSignal:
      return kSignalStep;
    case Kind::kFault:
      return kFaultStep;
    default:
      return kNcStep;  // the kNc* kinds
  }
}

int ReadDriveParameterSet(const YamlNode& step, std::ostringstream& text) {
  const int set = step.Int("parameter_set", 0);
  if (set < 0 || set > 7) step["parameter_set"].Fail("expected 0..7");
  if (set != 0) text << " (parameter set " << set << ")";
  return set;
}

TimelineStep ReadStep(const MachineModel& m, const YamlNode& n, size_t i, const NcSetup& nc,
                      bool plc) {
  n.AllowKeys({"at", "move", "speed", "orient", "off", "output", "wait", "wait_until", "nc", "jog",
               "handwheel", "signal", "fault", "press"});
  TimelineStep s{};
  s.not_before_s = n.Double("at", 0, 0, kMaxSceneSeconds);
  std::ostringstream text;
  text << "timeline[" << i << "]: ";
  int actions = 0;
  for (const StepKind* k : kKinds) actions += n.Has(k->key);
  if (actions != 1)
    n.Fail(
        "a step needs exactly one of move, speed, orient, off, output, wait, wait_until, nc, jog, "
        "press, "
        "handwheel, signal, fault");
  FindStepKind(n)->read({m, nc, n, plc}, s, text);
  s.text = text.str();
  return s;
}

}  // namespace vmt::sim
