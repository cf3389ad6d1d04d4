// `wait_until: {CONDITION, timeout}`: the steps after it wait until the machine, the NC or a
// gateway signal shows a state; a timeout is a failure of the run, which still goes on.
#include <string>

#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/scene/steps/step_kind.hpp"

namespace vmt::sim {
namespace {

Condition ReadCondition(const MachineModel& m, const YamlNode& n, const NcSetup& nc) {
  Condition c;
  if (n.Has("signal")) {
    n.AllowKeys({"signal", "value", "timeout"});
    c.kind = Condition::Kind::kSignal;
    c.index = RequireSignal(nc, n["signal"]);
    c.signal_value = n.Has("value") ? SignalValue(nc, c.index, n["value"]) : 1;
    return c;
  }
  if (n.Has("nc")) {
    n.AllowKeys({"nc", "timeout"});
    c.kind = Condition::Kind::kNc;
    c.nc = ParseNcState(n["nc"]);
    return c;
  }
  if (n.Has("input")) {
    n.AllowKeys({"input", "value", "timeout"});
    c.kind = Condition::Kind::kInput;
    c.index = RequireIo(m, n["input"]);
    c.value = n.Bool("value", true);
  } else if (n.Has("clutch")) {
    n.AllowKeys({"clutch", "state", "timeout"});
    c.kind = Condition::Kind::kClutch;
    c.index = -1;
    for (size_t k = 0; k < m.clutches.size(); ++k)
      if (m.clutches[k].name == n["clutch"].String()) c.index = static_cast<int>(k);
    if (c.index < 0) n["clutch"].Fail("no clutch '" + n["clutch"].String() + "'");
    c.clutch = ParseClutchState(n["state"]);
  } else if (n.Has("axis")) {
    n.AllowKeys({"axis", "in_position", "at_speed", "standstill", "timeout"});
    c.index = RequireDrive(m, n["axis"]);
    if (n.Has("in_position"))
      c.kind = Condition::Kind::kInPosition, c.value = n.Bool("in_position", true);
    else if (n.Has("at_speed"))
      c.kind = Condition::Kind::kAtSpeed, c.value = n.Bool("at_speed", true);
    else if (n.Has("standstill"))
      c.kind = Condition::Kind::kStandstill, c.value = n.Bool("standstill", true);
    else
      n.Fail("expected one of in_position, at_speed, standstill");
  } else {
    n.Fail("expected input:, clutch:, axis:, nc: or signal:");
  }
  return c;
}

void Read(const StepSource& src, TimelineStep& s, std::ostringstream& text) {
  const YamlNode a = src.n["wait_until"];
  s.kind = TimelineStep::Kind::kWaitUntil;
  s.until = ReadCondition(src.m, a, src.nc);
  s.timeout_s = a.Double("timeout", 10, 0, kMaxSceneSeconds);
  text << "wait until";
  for (const std::string& k : a.Keys())
    if (k != "timeout") text << " " << k << "=" << a[k].String();
}

bool Play(const TimelineStep& s, const StepTick& tick, TimelinePlay& play) {
  // The feedback in hand is one tick old: it cannot yet show the effect of commands given in
  // this tick (an "at speed" of the old setpoint), so a wait never ends in its first tick.
  if (tick.t_s == tick.since_s) return false;
  // "In position" means the move is done, not that the axis has yet to start.
  const bool moving =
      s.until.kind == Condition::Kind::kInPosition && play.profiling[s.until.index] &&
      tick.t_s < play.profiles[s.until.index].t0_s + play.profiles[s.until.index].Duration();
  if (!moving && Holds(s.until, tick.at, tick.clutches, play.channel, play.image)) return true;
  if (tick.t_s - tick.since_s >= s.timeout_s) {
    play.failures.push_back(s.text + " timed out after " + std::to_string(s.timeout_s) + " s");
    tick.events.push_back({tick.t_s, "timeout", s.text});
    return true;  // go on: the rest of the run is still worth its trace
  }
  return false;
}

}  // namespace

const StepKind kWaitUntilStep{"wait_until", Read, Play};

}  // namespace vmt::sim
