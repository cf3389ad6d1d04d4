#include "sim/scene/operator_steps.hpp"

#include <cmath>

#include "sim/model/yaml_reader.hpp"

namespace vmt::sim {

std::vector<OperatorStep> ReadOperatorSteps(const std::string& file) {
  const YamlNode root = YamlNode::LoadFile(file);
  if (!root.IsMap()) root.Fail("expected a map with an operator: list");
  root.AllowKeys({"scene", "operator"});
  const YamlNode list = root["operator"];
  if (!list.IsSequence()) list.Fail("expected a list of {tick, signal, value}");
  std::vector<OperatorStep> steps;
  for (size_t i = 0; i < list.size(); ++i) {
    const YamlNode n = list[i];
    if (!n.IsMap()) n.Fail("expected {tick, signal, value} or {tick, handwheel, counts}");
    const bool handwheel = n.Has("handwheel");
    if (handwheel)
      n.AllowKeys({"tick", "handwheel", "counts"});
    else
      n.AllowKeys({"tick", "signal", "value"});
    const double tick = n["tick"].Double(0, 9e15);
    if (!(tick >= 0) || tick > 9e15 || tick != std::floor(tick))
      n["tick"].Fail("expected a whole number of drive ticks, >= 0");
    OperatorStep s;
    s.tick = static_cast<int64_t>(tick);
    if (handwheel) {
      s.handwheel = n["handwheel"].String();
      s.value = n["counts"].Int();
    } else {
      s.signal = n["signal"].String();
      s.value = n["value"].Double();
      if (!std::isfinite(s.value)) n["value"].Fail("expected a finite number");
    }
    if (!steps.empty() && s.tick < steps.back().tick)
      n["tick"].Fail("goes back in time (the steps are in the order they were taken)");
    steps.push_back(std::move(s));
  }
  return steps;
}

}  // namespace vmt::sim
