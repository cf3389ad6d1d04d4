// A run kept in memory and gone back to: each stage's values are copied out, and copied back
// into the same objects, which keep pointing at each other.

#include <memory>
#include <stdexcept>
#include <string>

#include "sim/runner/runner_state.hpp"

namespace vmt::sim {

std::shared_ptr<const SavedRun> SceneRun::State::Save() const {
  std::unique_ptr<MachineBackend> machine = backend->Copy();
  if (!machine)
    throw std::runtime_error(std::string("a run on the ") +
                             ToString(options.backend.value_or(scene.backend)) +
                             " backend cannot be kept in memory: its world does not copy");
  if (recorder.writing())
    throw std::runtime_error("a run that writes its files as it goes cannot be kept in memory");
  if (options.external_plc)
    throw std::runtime_error("a run whose PLC is an external client cannot be kept in memory");
  return std::make_shared<const SavedRun>(SavedRun{
      std::move(machine),
      path_guard ? std::optional(path_guard->Save()) : std::nullopt,
      control_stage->Save(),
      *timeline,
      machine_events,
      channel_events,
      tick,
      last_tick,
      finished,
      recorder.Save(),
      result,
      expectations,
      snapshots.Save(),
      clutches,
      mdt,
      events,
      fault_filter,
      plc_client_gone_told,
      probe_latch_point,
      operated,
      next_operator_step,
  });
}

void SceneRun::State::Restore(const SavedRun& saved) {
  backend->Restore(*saved.backend);
  if (path_guard) path_guard->Restore(*saved.path_guard);
  control_stage->Restore(saved.control_stage);
  *timeline = saved.timeline;
  machine_events = saved.machine_events;
  channel_events = saved.channel_events;
  tick = saved.tick;
  last_tick = saved.last_tick;
  finished = saved.finished;
  recorder.Restore(saved.recorder);
  result = saved.result;
  expectations = saved.expectations;
  snapshots.Restore(saved.snapshots);
  clutches = saved.clutches;
  mdt = saved.mdt;
  events = saved.events;
  fault_filter = saved.fault_filter;
  plc_client_gone_told = saved.plc_client_gone_told;
  probe_latch_point = saved.probe_latch_point;
  operated = saved.operated;
  next_operator_step = saved.next_operator_step;
}

std::shared_ptr<const SavedRun> SceneRun::Save() const { return state_->Save(); }
void SceneRun::Restore(const SavedRun& saved) { state_->Restore(saved); }

}  // namespace vmt::sim
