#include "control/channel/spindle_synchronous_motion.hpp"

#include <cmath>
#include <limits>

#include "control/channel/channel_messages.hpp"

namespace vmt::control::channel {

double ThreadLaw::PathAt(double psi) const {
  const double k = mm_per_deg;
  double s;
  if (psi <= -ramp_in_deg) {
    s = 0;
  } else if (psi < ramp_in_deg) {
    // Constant acceleration in the spindle's phase: tangent to s = k psi at psi0.
    s = k * (psi + ramp_in_deg) * (psi + ramp_in_deg) / (4 * ramp_in_deg);
  } else {
    s = k * psi;
  }
  if (running_out()) {
    // The mirror image of the ramp-in: from the law with its slope to L at rest.
    const double from = run_out_end_deg - 2 * run_out_deg;
    if (psi >= run_out_end_deg) return length;
    if (psi > from) {
      const double left = run_out_end_deg - psi;
      s = length - k * left * left / (4 * run_out_deg);
    }
  }
  return std::min(s, length);
}

double ThreadLaw::RampDeg(double mm_per_deg, double spindle_deg_per_s, double accel) {
  return mm_per_deg * spindle_deg_per_s * spindle_deg_per_s / (2 * accel);
}

void ThreadLaw::BeginRunOut(double psi) {
  // The run-out leaves the law at psi and reaches L where the law would be psi1 further on.
  run_out_deg = std::max(LawEndDeg() - psi, 1e-9);
  run_out_end_deg = psi + 2 * run_out_deg;
}

double ThreadZeroMark(double phi, int direction, double ramp_in_deg) {
  const double from = phi + direction * ramp_in_deg;
  return direction > 0 ? std::ceil(from / 360) * 360 : std::floor(from / 360) * 360;
}

std::optional<MotionError> PlanSynchronousPath(const nc::PreparedBlock& block,
                                               const std::vector<double>& start,
                                               const std::vector<double>& translation,
                                               const std::vector<axes::AxisParameters>& axes,
                                               uint64_t follow_up, SynchronousPath& out) {
  out = SynchronousPath{};
  for (size_t a = 0; a < axes.size(); ++a)
    if (axes[a].rotary && (block.programmed >> a & 1))
      return MotionError{"G33/G63/G64 move linear axes only, not " + axes[a].name,
                         kMsgProgramError};
  // The straight line and its limits as G01 has them, at a feed no axis can reach: max_rate
  // is then the axes' rapid.
  nc::PreparedBlock line = block;
  line.motion = nc::Motion::kLinear;
  line.modal.feed = 1e15;
  line.modal.feed_per_revolution = false;
  if (auto error = PlanBlockMotion(line, start, translation, axes, 0, out.line, follow_up))
    return error;
  if (!out.line.moves) return std::nullopt;
  double length2 = 0, dominant = 0;
  for (size_t a = 0; a < axes.size(); ++a) {
    if (axes[a].rotary) continue;
    const double d = out.line.end[a] - out.line.start[a];
    length2 += d * d;
    dominant = std::max(dominant, std::abs(d));
  }
  if (dominant < 1e-9) {
    out.line.moves = false;
    return std::nullopt;
  }
  out.length = std::sqrt(length2);
  out.mm_per_deg = out.length / dominant * block.modal.lead / 360;
  out.max_speed = out.line.max_rate * out.line.length;
  out.max_accel = out.line.max_accel * out.line.length;
  out.max_jerk = out.line.max_jerk * out.line.length;
  return std::nullopt;
}

void RigidTappingLimits(const SynchronousPath& path, double spindle_rpm,
                        double spindle_max_deg_per_s, double spindle_max_accel,
                        PathProfile& profile) {
  const double k = path.mm_per_deg;
  double speed = std::min(k * std::abs(spindle_rpm) * 6, path.max_speed);
  double accel = path.max_accel;
  if (spindle_max_deg_per_s > 0) speed = std::min(speed, k * spindle_max_deg_per_s);
  if (spindle_max_accel > 0) accel = std::min(accel, k * spindle_max_accel);
  profile = PathProfile{};
  profile.max_rate = speed / path.length;
  profile.max_accel = accel / path.length;
  profile.max_jerk = path.max_jerk / path.length;
}

}  // namespace vmt::control::channel
