// The channel and its drives: faults stop the program with an NC error message naming the
// drive's trip; Control-Reset acknowledges the trips (SERCOS drives reset a latched error when
// their controller enable is removed).
#include <algorithm>
#include <cstdio>

#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

constexpr uint32_t kTrips =
    drive_status::kOverload | drive_status::kOverspeed | drive_status::kParameterSetError;

}  // namespace

void Channel::SafetyStop(const std::string& text, int number) {
  // The axes stand where they are commanded this cycle: a program's path, a jog or an
  // increment under way end at once, and a held key moves nothing until it is pressed again.
  for (JogAxis& j : jog_.axes)
    j.velocity = 0, j.stepping = j.handwheel = j.homing = j.home_requested = false, j.key = 0;
  for (FictiveJog& f : jog_.fictive) f.velocity = 0, f.stepping = f.handwheel = false, f.key = 0;
  if (config_.spindle_drive >= 0) sp_.command = {DriveMode::kVelocity, 0, 0};
  sp_.jogging = sp_.referencing = sp_.orienting = false;
  if (state_ != ChannelState::kError) Fail(text, number);
}

void Channel::CheckDrives(const AmplifierTelegram& at) {
  auto tripped_text = [](uint32_t status) -> std::string {
    std::string causes;
    auto add = [&](uint32_t bit, const char* what) {
      if (status & bit) causes += (causes.empty() ? "" : ", ") + std::string(what);
    };
    add(drive_status::kOverload, "overload");
    add(drive_status::kOverspeed, "overspeed");
    add(drive_status::kParameterSetError, "parameter set error");
    return causes.empty() ? "drive not ready (drive fault)" : "drive error: " + causes;
  };
  auto acknowledging = [&](int drive) {
    return drives_.trip_reset_ticks > 0 &&
           std::find(drives_.trip_reset.begin(), drives_.trip_reset.end(), drive) !=
               drives_.trip_reset.end();
  };
  // A drive without power (tripped, not ready) is in follow-up: the NC takes its actual
  // position as command value (C-axis manual 4.2: "In a powerless state, the NC corrects the
  // actual values and assigns them to the command values"), so that it does not jump back to
  // the old command when it is powered again after Control-Reset.
  for (size_t a = 0; a < config_.axes.size(); ++a) {
    const DriveFeedback& fb = at.feedback[config_.axes[a].drive];
    if ((fb.status & kTrips) || !(fb.status & drive_status::kReady))
      out_.commanded[a] = out_.previous[a] = fb.position;
  }
  if (state_ == ChannelState::kError) return;
  CheckAxisReady();
  if (state_ == ChannelState::kError) return;
  // The drives answer for themselves: one that is not ready (a fault: its power stage is off)
  // or lags beyond its limit stops the channel at once, every other axis holding where it is.
  // Its trips are named in the message (the drive's diagnosis, as a control displays it).
  const int failed_drive = [&] {
    for (size_t a = 0; a < config_.axes.size(); ++a) {
      const int d = config_.axes[a].drive;
      const uint32_t status = at.feedback[d].status;
      if (acknowledging(d)) continue;
      if (!(status & drive_status::kReady)) {
        // One drive for spindle and rotary axis (section 2): named as the display shows it.
        const bool shared = headstock_ && static_cast<int>(a) == config_.rotary_axis &&
                            !headstock_->config().separate_servo();
        const std::string name = shared ? HeadstockAxisName() : config_.axes[a].name;
        Fail("axis " + name + ": " + tripped_text(status), kMsgDriveFault);
        return d;
      }
      if (status & drive_status::kFollowingError) {
        Fail("axis " + config_.axes[a].name + ": following error beyond its limit",
             kMsgFollowingError);
        return d;
      }
    }
    const int s = config_.spindle_drive;
    if (s >= 0 && !acknowledging(s) && !(at.feedback[s].status & drive_status::kReady)) {
      sp_.command = {DriveMode::kVelocity, 0, 0};
      Fail("spindle: " + tripped_text(at.feedback[s].status), kMsgDriveFault);
      return s;
    }
    return -1;
  }();
  // 2.3 / 3.3 Errors: a drive of the headstock failing during a changeover: the NC proceeds as
  // at power-on (the mode is again the one the PLC acknowledges).
  if (failed_drive >= 0 && headstock_ && headstock_->busy() &&
      (failed_drive == headstock_->config().spindle_drive ||
       failed_drive == headstock_->config().rotary_drive)) {
    headstock_.TakeModeFromPlc();
  }
}

void Channel::CheckAxisReady() {
  // C-axis manual 4.2: "The NC employs the 'axis ready' control signal to monitor the ready
  // state of a main spindle with rotary axis capability in rotary axis mode and in main spindle
  // mode": one axis, one AxxC.READY, whichever designation is shown. Without it the drive is
  // powerless (HeadstockChangeover::WriteSetpoints) and its command values follow the actual
  // ones (HeadstockCycle), so an NC that still needs the axis -- a program running, the
  // spindle commanded to turn or to position, the rotary axis jogged, a changeover -- stops
  // with 503 rather than lose the motion unseen. Section 3's two READY are the PLC's controller
  // enables (4.3): removing one puts that drive in follow-up, without a message.
  if (!headstock_ || headstock_->config().separate_servo() || headstock_.RotaryReady()) return;
  const size_t r = static_cast<size_t>(config_.rotary_axis);
  const JogAxis& jog = jog_.axes[r];
  const bool spindle_commanded = sp_.command.mode == DriveMode::kPosition || sp_.command.value != 0;
  const bool jogged = jog.key != 0 || jog.stepping || jog.velocity != 0;
  const bool changing = headstock_->busy();
  if (state_ != ChannelState::kRunning && !spindle_commanded && !jogged && !changing) return;
  char signal[16];
  std::snprintf(signal, sizeof signal, "A%02dC.READY", config_.axes[r].number);
  sp_.command = {DriveMode::kVelocity, 0, 0};
  Fail("axis " + HeadstockAxisName() + ": not ready (" + signal + " removed)", kMsgDriveFault);
  // 2.3 Errors: during a changeover the NC proceeds as at power-on.
  if (changing) {
    headstock_.TakeModeFromPlc();
  }
}

void Channel::CollectTrips(const AmplifierTelegram& at) {
  // Control-Reset acknowledges the drives' errors as a real control does: a drive that tripped
  // gets its controller enable removed (kOff, the drive's fault reset) for one NC cycle, then
  // the channel's setpoints again (AcknowledgeDriveTrips). Meanwhile it is not reported; a
  // cause still present trips it again, and CheckDrives reports it after that cycle.
  drives_.trip_reset_pending = false;
  drives_.trip_reset.clear();
  auto collect = [&](int d) {
    if (d >= 0 && d < static_cast<int>(at.feedback.size()) && (at.feedback[d].status & kTrips) &&
        std::find(drives_.trip_reset.begin(), drives_.trip_reset.end(), d) ==
            drives_.trip_reset.end())
      drives_.trip_reset.push_back(d);
  };
  for (const ChannelAxis& a : config_.axes) collect(a.drive);
  collect(config_.spindle_drive);
  if (headstock_) collect(headstock_->config().rotary_drive);
  drives_.trip_reset_ticks = drives_.trip_reset.empty() ? 0 : config_.ticks_per_cycle;
}

std::vector<bool> Channel::DrivesWritten() const {
  std::vector<bool> written;
  const auto mark = [&written](int drive) {
    if (drive < 0) return;
    if (static_cast<size_t>(drive) >= written.size()) written.resize(drive + 1);
    written[drive] = true;
  };
  // As Tick writes them: the rotary axis of a headstock and the main spindle through it.
  for (size_t a = 0; a < config_.axes.size(); ++a)
    if (!config_.headstock || static_cast<int>(a) != config_.rotary_axis)
      mark(config_.axes[a].drive);
  if (config_.headstock) {
    mark(config_.headstock->spindle_drive);
    if (config_.headstock->separate_servo()) mark(config_.headstock->rotary_drive);
  } else {
    mark(config_.spindle_drive);
  }
  for (const ChannelSpindle& s : config_.spindles) mark(s.drive);
  return written;
}

void Channel::AcknowledgeDriveTrips(MasterTelegram& mdt) {
  if (drives_.trip_reset_ticks <= 0) return;
  for (int d : drives_.trip_reset)
    if (d < static_cast<int>(mdt.setpoints.size())) mdt.setpoints[d] = {DriveMode::kOff, 0, 0};
  if (--drives_.trip_reset_ticks == 0) drives_.trip_reset.clear();
}

}  // namespace vmt::control::channel
