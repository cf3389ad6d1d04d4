#include "sim/runner/timeline_player.hpp"

#include "sim/scene/steps/step_kind.hpp"

namespace vmt::sim {

using control::DriveMode;

TimelinePlayer::TimelinePlayer(const Scene& scene, const control::AmplifierTelegram& feedback,
                           control::channel::Channel* channel, control::gateway::SignalImage* image)
    : scene_(&scene) {
  const MachineModel& m = *scene.model;
  play_.model = &m;
  play_.channel = channel;
  play_.image = image;
  play_.setpoints.resize(m.drives.size());
  play_.profiles.resize(m.drives.size());
  play_.profiling.assign(m.drives.size(), false);
  play_.outputs.assign(m.io.size(), 0);
  play_.faults.sensor.assign(m.io.size(), -1);
  play_.faults.valve.assign(m.io.size(), -1);
  play_.faults.drive.assign(m.drives.size(), false);
  for (size_t d = 0; d < m.drives.size(); ++d) {
    if (m.drives[d].spindle)
      play_.setpoints[d] = {DriveMode::kVelocity, 0, 0};
    else
      play_.setpoints[d] = {DriveMode::kPosition, feedback.feedback[d].position, 0};
  }
}

void TimelinePlayer::Tick(double t_s, const control::AmplifierTelegram& at,
                        const std::vector<ClutchState>& clutches, control::MasterTelegram& mdt,
                        std::vector<ProgramEvent>& events) {
  while (next_ < scene_->timeline.size()) {
    const TimelineStep& step = scene_->timeline[next_];
    if (t_s < step.not_before_s - 1e-9) break;
    if (step_since_s_ < 0) {
      step_since_s_ = t_s;
      events.push_back({t_s, "step", step.text});
    }
    if (!StepKindOf(step.kind).play(step, {t_s, step_since_s_, at, clutches, events}, play_))
      break;
    ++next_;
    step_since_s_ = -1;
  }
  for (size_t d = 0; d < play_.setpoints.size(); ++d)
    if (play_.profiling[d]) play_.setpoints[d].value = play_.profiles[d].At(t_s);
  mdt.outputs = play_.outputs;
}

}  // namespace vmt::sim
