// The channel's spindle-synchronous blocks: G33 thread cutting, G63 and G64 tapping (the law in
// spindle_synchronous_motion.hpp). A block of these runs to its end once started: a thread
// cannot stop in its groove, so feed hold (and the feed override) take effect after it; they
// select main spindle mode on a headstock (C-axis manual 4.2, ModeNeeded), which the block waits
// for like M3.
#include <cmath>
#include <cstdio>

#include "control/channel/channel.hpp"

namespace vmt::control::channel {

bool Channel::StartSynchronous(const AmplifierTelegram& at) {
  const nc::Program& program = *ProgramOf(work_.block.program);
  sync_ = Synchronous{};
  auto fail = [&](const std::string& text, int number) {
    Fail(program, work_.block.block, text, number);
    return false;
  };
  const char* g = work_.block.motion == nc::Motion::kThread    ? "G33"
                  : work_.block.motion == nc::Motion::kTapping ? "G63"
                                                               : "G64";
  if (work_.block.modal.compensation != nc::Compensation::kOff)
    return fail(std::string(g) + " with tool nose radius compensation: program G40 first",
                kMsgNotAvailable);
  if (config_.spindle_drive < 0)
    return fail(std::string(g) + " needs a main spindle", kMsgSpindleStill);
  // G33 and G63 need the spindle turning (M3/M4 with S); G64 takes the spindle into position
  // control and needs the direction and speed M3/M4 and S give it.
  const bool rigid = work_.block.motion == nc::Motion::kRigidTapping;
  const bool turning = rigid ? (work_.block.modal.spindle == 3 || work_.block.modal.spindle == 4) &&
                                   work_.block.modal.spindle_speed > 0
                             : sp_.command.mode == DriveMode::kVelocity && sp_.command.value != 0;
  if (!turning)
    return fail(std::string("spindle not turning for ") + g + ": program M3 or M4 with S first",
                kMsgSpindleStill);
  if (const auto error = PlanSynchronousPath(work_.block, out_.commanded, frames_.translation,
                                             config_.axes, FollowUpAxes(work_.block), sync_.path))
    return fail(error->text, error->number);
  work_.profile = PathProfile{};
  work_.continuation_ready = false;
  work_.targets.clear();
  if (!sync_.path.line.moves) return true;
  work_.motion = sync_.path.line;
  const double k = sync_.path.mm_per_deg;
  const DriveFeedback& spindle = at.feedback[config_.spindle_drive];
  if (work_.block.motion == nc::Motion::kThread) {
    sync_.phase = SyncPhase::kWaitForSpeed;
    sync_.spindle_deg = sync_.spindle_last_deg = spindle.position;
  } else if (work_.block.motion == nc::Motion::kTapping) {
    // lead x S along the dominant axis, whatever the spindle actually does.
    const double speed = k * std::abs(work_.block.modal.spindle_speed) * 6;
    if (speed > sync_.path.max_speed * (1 + 1e-9)) {
      char text[160];
      std::snprintf(text, sizeof text, "G63 at %.3f mm/s is faster than the axes' %.3f mm/s", speed,
                    sync_.path.max_speed);
      return fail(text, kMsgLeadTooFast);
    }
    work_.profile.max_rate = speed / work_.motion.length;
    work_.profile.max_accel = sync_.path.max_accel / work_.motion.length;
    work_.profile.max_jerk = sync_.path.max_jerk / work_.motion.length;
    sync_.phase = SyncPhase::kRunning;
  } else {
    sync_.direction = work_.block.modal.spindle == 4 ? -1 : 1;
    RigidTappingLimits(sync_.path, work_.block.modal.spindle_speed, config_.spindle.rapid_per_s,
                       config_.spindle.acceleration, work_.profile);
    // lead x S, within the axes' and the spindle's limits; the spindle override may raise the
    // speed only as far as they allow.
    const double limit = work_.profile.max_rate;
    const double programmed =
        k * std::abs(work_.block.modal.spindle_speed) * 6 / work_.motion.length;
    work_.profile.max_rate = std::min(limit, programmed);
    sync_.max_override = limit / work_.profile.max_rate;
    sync_.phase = SyncPhase::kStopSpindle;
    sp_.command.velocity_feedforward = 0;
    if (!(sp_.command.mode == DriveMode::kPosition && sp_.command.interpolated)) {
      sp_.command.mode = DriveMode::kVelocity;  // brake first; SynchronousCycle takes it over
      sp_.command.value = 0;
    }
  }
  work_.active = true;
  return true;
}

void Channel::SynchronousCycle(const AmplifierTelegram& at, double dt) {
  const DriveFeedback& spindle = at.feedback[config_.spindle_drive];
  const double k = sync_.path.mm_per_deg;
  const double length = work_.motion.length;
  auto finish = [&] {
    out_.commanded = work_.motion.end;  // exactly the programmed point
    work_.active = false;
    sync_.phase = SyncPhase::kNone;
  };
  if (work_.block.motion == nc::Motion::kThread) {
    // The spindle's actual position, unwrapped (a modulo encoder reports 0..360).
    double step = spindle.position - sync_.spindle_last_deg;
    step -= 360 * std::round(step / 360);
    sync_.spindle_deg += step;
    sync_.spindle_last_deg = spindle.position;
    const double w = spindle.velocity;
    if (sync_.phase == SyncPhase::kWaitForSpeed) {
      // The thread starts once the spindle runs at its commanded speed (override included).
      const double target = SpindleSetpoint().value;
      if (sp_.command.mode != DriveMode::kVelocity || sp_.command.value == 0) {
        Fail(*ProgramOf(work_.block.program), work_.block.block, "spindle not turning for G33",
             kMsgSpindleStill);
        return;
      }
      if (target == 0 || std::abs(w - target) > std::max(0.01 * std::abs(target), 1.0)) return;
      const double accel = sync_.path.max_accel;
      if (k * std::abs(w) > sync_.path.max_speed) {
        char text[160];
        std::snprintf(text, sizeof text, "G33 at %.3f mm/s is faster than the axes' %.3f mm/s",
                      k * std::abs(w), sync_.path.max_speed);
        Fail(*ProgramOf(work_.block.program), work_.block.block, text, kMsgLeadTooFast);
        return;
      }
      sync_.direction = w < 0 ? -1 : 1;
      sync_.law.mm_per_deg = k;
      sync_.law.length = length;
      sync_.law.ramp_in_deg = ThreadLaw::RampDeg(k, w, accel);
      if (2 * k * sync_.law.ramp_in_deg > length) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "G33 thread %.3f mm is shorter than its ramp-in and run-out (%.3f mm) at "
                      "this spindle speed",
                      length, 2 * k * sync_.law.ramp_in_deg);
        Fail(*ProgramOf(work_.block.program), work_.block.block, text, kMsgLeadTooFast);
        return;
      }
      // Dead time: the axes reach this cycle's command one NC cycle later (fine
      // interpolation), where the spindle will be w dt further on.
      sync_.zero_mark_deg =
          ThreadZeroMark(sync_.spindle_deg + w * dt, sync_.direction, sync_.law.ramp_in_deg);
      sync_.phase = SyncPhase::kRunning;
    }
    const double psi = sync_.direction * (sync_.spindle_deg + w * dt - sync_.zero_mark_deg);
    if (!sync_.law.running_out() &&
        psi >= sync_.law.LawEndDeg() - ThreadLaw::RampDeg(k, w, sync_.path.max_accel))
      sync_.law.BeginRunOut(std::max(psi, sync_.law.ramp_in_deg));
    const double s = sync_.law.PathAt(psi);
    work_.profile.u = s / length;
    work_.motion.PointAt(work_.profile.u, out_.commanded);
    if (sync_.law.running_out() && psi >= sync_.law.run_out_end_deg) finish();
    return;
  }
  if (work_.block.motion == nc::Motion::kTapping) {
    // Feed override held at 100 %, feed hold after the block.
    work_.profile.Advance(dt, 1.0);
    work_.motion.PointAt(work_.profile.u, out_.commanded);
    if (work_.profile.done()) finish();
    return;
  }
  // G64: brake a turning spindle, then position control where it stands.
  if (sync_.phase == SyncPhase::kStopSpindle) {
    if (sp_.command.mode == DriveMode::kVelocity) {
      const bool still =
          (spindle.status & drive_status::kStandstill) || std::abs(spindle.velocity) < 0.1;
      if (!still) return;
      sp_.command = {DriveMode::kPosition, spindle.position, 0};
      sp_.command.interpolated = true;
    }
    sync_.spindle_start_deg = sp_.previous_deg = sp_.command.value;
    sync_.phase = SyncPhase::kRunning;
  }
  work_.profile.Advance(dt, std::min(sp_.override, sync_.max_override));
  work_.motion.PointAt(work_.profile.u, out_.commanded);
  const double u = std::min(work_.profile.u, 1.0);
  sp_.command.value = sync_.spindle_start_deg + sync_.direction * u * length / k;
  sp_.command.velocity_feedforward = sync_.direction * work_.profile.rate * length / k;
  if (work_.profile.done()) {
    sp_.command.velocity_feedforward = 0;
    finish();  // the spindle stands in position control at its end position
  }
}

}  // namespace vmt::control::channel
