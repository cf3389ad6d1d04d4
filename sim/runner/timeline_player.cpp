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
  play_.profiling.assign(m.drives.size(), 0);
  play_.outputs.assign(m.io.size(), 0);
  play_.faults.sensor.assign(m.io.size(), -1);
  play_.faults.valve.assign(m.io.size(), -1);
  play_.faults.drive.assign(m.drives.size(), false);
  encoder_clutch_.assign(m.drives.size(), -1);
  held_.assign(m.drives.size(), 0);
  for (size_t d = 0; d < m.drives.size(); ++d) {
    const DriveParams& p = m.drives[d];
    for (size_t k = 0; k < m.clutches.size() && !p.spindle && p.load_joint >= 0; ++k)
      if (m.clutches[k].motor_joint == p.motor_joint && m.clutches[k].load_joint == p.load_joint)
        encoder_clutch_[d] = static_cast<int>(k);
    held_[d] = encoder_clutch_[d] >= 0;
    held_count_ += held_[d];
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
    if (held_count_ > 0) {
      setpoints_before_ = play_.setpoints;
      profiling_before_ = play_.profiling;
    }
    const bool done =
        StepKindOf(step.kind).play(step, {t_s, step_since_s_, at, clutches, events}, play_);
    for (size_t d = 0; held_count_ > 0 && d < held_.size(); ++d) {
      const control::DriveSetpoint& before = setpoints_before_[d];
      if (held_[d] &&
          (play_.profiling[d] != profiling_before_[d] || play_.setpoints[d].mode != before.mode ||
           play_.setpoints[d].value != before.value ||
           play_.setpoints[d].parameter_set != before.parameter_set))
        Release(d);
    }
    if (!done) break;
    ++next_;
    step_since_s_ = -1;
  }
  for (size_t d = 0; held_count_ > 0 && d < held_.size(); ++d) {
    if (!held_[d] || clutches.empty()) continue;
    control::DriveSetpoint& sp = play_.setpoints[d];
    const double position = at.feedback[d].position;
    if (clutches[encoder_clutch_[d]] != ClutchState::kEngaged)
      sp = {DriveMode::kOff, position, sp.parameter_set};
    else if (sp.mode == DriveMode::kOff)
      sp = {DriveMode::kPosition, position, sp.parameter_set};
  }
  for (size_t d = 0; d < play_.setpoints.size(); ++d)
    if (play_.profiling[d]) play_.setpoints[d].value = play_.profiles[d].At(t_s);
  mdt.outputs = play_.outputs;
}

}  // namespace vmt::sim
