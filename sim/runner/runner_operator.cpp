// The operator station's inputs to a run (SceneRun::Operate) and their replay from
// operator.yaml: a key or a signal set at the start of a PLC cycle, the way the timeline's
// `press:` and `signal:` steps set them, and recorded so that the run can be repeated.
#include <fstream>
#include <sstream>
#include <utility>

#include "common/json_text.hpp"
#include "sim/runner/runner_state.hpp"

namespace vmt::sim {

std::string SceneRun::State::OperateError(const std::string& signal) const {
  const control::gateway::SignalImage* image = control_stage->image();
  if (!image) return "the scene has no nc: section, so no gateway signals";
  const int id = image->Find(signal);
  if (id < 0) return "no signal " + signal;
  const control::gateway::Signal& sig = image->table()[id];
  const int io = control::IndexOf(m.io, sig.name);
  if (io >= 0 && m.io[io].key) return "";
  if (sig.direction == control::gateway::Direction::kNcToPlc)
    return "the NC writes " + sig.name + ": a PLC cannot set it";
  if (sig.direction == control::gateway::Direction::kMachineToPlc)
    return sig.name + " is a sensor of the machine: a PLC cannot set it";
  // The embedded PLC writes its outputs every scan: a value set beside it would last one
  // cycle. The station presses keys then, as the timeline does with plc:.
  if (!options.external_plc && control_stage->plc())
    return "the scene's PLC program writes " + sig.name + ": press the operator's keys instead";
  return "";
}

std::string SceneRun::State::ValueError(const std::string& signal, double value) const {
  if (std::string error = OperateError(signal); !error.empty()) return error;
  const control::gateway::SignalImage& image = *control_stage->image();
  const int id = image.Find(signal);
  if (std::string error = control::gateway::ValueError(image.table()[id].type, value);
      !error.empty())
    return signal + ": " + error;
  if (const int io = control::IndexOf(m.io, signal);
      io >= 0 && m.io[io].selector() && !m.io[io].PositionOk(value))
    return signal + " is a selector: expected one of its positions " + m.io[io].PositionList();
  return "";
}

std::string SceneRun::State::Operate(const std::string& signal, double value) {
  if (std::string error = ValueError(signal, value); !error.empty()) return error;
  control::gateway::SignalImage& image = *control_stage->image();
  image.SetNumber(image.Find(signal), value);
  recorder.Event(
      {{"t", tick * kDriveTickS}, {"event", "operator"}, {"signal", signal}, {"value", value}});
  operated.push_back({tick, signal, value, ""});
  return "";
}

std::string SceneRun::State::OperateHandwheel(const std::string& axis, int counts) {
  control::channel::Channel* channel = control_stage->channel();
  if (!channel) return "the scene has no nc: section, so no handwheel";
  if (counts == 0 || counts < -10000 || counts > 10000)
    return "handwheel counts: expected -10000..10000, not 0";
  if (axis == "X1" || axis == "Y1") {
    if (!channel->HandwheelFictive(axis == "X1" ? 0 : 1, counts))
      return "the handwheel of " + axis + " needs G31 in manual handwheel mode";
  } else {
    size_t a = 0;
    while (a < channel->config().axes.size() && channel->AxisName(a) != axis) ++a;
    if (a == channel->config().axes.size()) return "no channel axis " + axis;
    channel->Handwheel(a, counts);
  }
  recorder.Event(
      {{"t", tick * kDriveTickS}, {"event", "operator"}, {"handwheel", axis}, {"counts", counts}});
  operated.push_back({tick, "", static_cast<double>(counts), axis});
  return "";
}

void SceneRun::State::ReplayOperatorSteps() {
  const std::vector<OperatorStep>& steps = options.operator_steps;
  for (; next_operator_step < steps.size() && steps[next_operator_step].tick <= tick;
       ++next_operator_step) {
    const OperatorStep& o = steps[next_operator_step];
    if (o.tick < tick) continue;  // a tick already past (checked when the file was read)
    const std::string error = o.handwheel.empty()
                                  ? Operate(o.signal, o.value)
                                  : OperateHandwheel(o.handwheel, static_cast<int>(o.value));
    if (!error.empty())
      result.failures.push_back("operator step at tick " + std::to_string(o.tick) + ": " + error);
  }
}

void SceneRun::State::WriteOperatorSteps() {
  if (!recorder.writing() || operated.empty()) return;
  std::ostringstream f;
  f << "# The operator station's inputs, at the drive tick of the PLC cycle that took each.\n"
    << "# vmt run SCENE --operator operator.yaml repeats the run to the same trace digest.\n"
    << "scene: " << nlohmann::json(scene.name).dump(-1, ' ', false, common::kReplaceBadUtf8)
    << "\noperator:\n";
  for (const OperatorStep& o : operated) {
    if (o.handwheel.empty())
      f << "  - {tick: " << o.tick
        << ", signal: " << nlohmann::json(o.signal).dump(-1, ' ', false, common::kReplaceBadUtf8)
        << ", value: " << nlohmann::json(o.value).dump(-1, ' ', false, common::kReplaceBadUtf8)
        << "}\n";
    else
      f << "  - {tick: " << o.tick << ", handwheel: "
        << nlohmann::json(o.handwheel).dump(-1, ' ', false, common::kReplaceBadUtf8)
        << ", counts: " << static_cast<int>(o.value) << "}\n";
  }
  WriteOutput(options.out_dir + "/operator.yaml", f.str());
}

std::string SceneRun::OperateError(const std::string& signal) const {
  return state_->OperateError(signal);
}
std::string SceneRun::OperateError(const std::string& signal, double value) const {
  return state_->ValueError(signal, value);
}
std::string SceneRun::Operate(const std::string& signal, double value) {
  return state_->Operate(signal, value);
}
std::string SceneRun::OperateHandwheel(const std::string& axis, int counts) {
  return state_->OperateHandwheel(axis, counts);
}
const std::vector<OperatorStep>& SceneRun::operated() const { return state_->operated; }
const Scene& SceneRun::scene() const { return state_->scene; }
const control::channel::Channel* SceneRun::channel() const {
  return state_->control_stage->channel();
}
const control::AmplifierTelegram& SceneRun::feedback() const {
  // Before the first tick the control has seen nothing yet: the machine as it stands.
  const control::AmplifierTelegram& filtered = state_->fault_filter.filtered();
  return filtered.feedback.empty() ? state_->backend->Read() : filtered;
}
std::vector<double> SceneRun::joint_positions() const { return state_->backend->JointPositions(); }
int64_t SceneRun::tick() const { return state_->tick; }
const control::gateway::SignalImage* SceneRun::image() const {
  return std::as_const(*state_->control_stage).image();
}
std::vector<CylinderPart> SceneRun::TurnedStockCylinders() const {
  // Finer than PathGuard's: the page draws what is cut to a micrometre.
  const StockCutter* cutter = state_->path_guard ? state_->path_guard->cutter() : nullptr;
  return cutter ? cutter->stock().Cylinders(1e-6) : std::vector<CylinderPart>{};
}
int64_t SceneRun::stock_cuts() const {
  return state_->path_guard ? state_->path_guard->stock_cuts() : 0;
}
double SceneRun::end_s() const { return state_->last_tick * kDriveTickS; }

}  // namespace vmt::sim
