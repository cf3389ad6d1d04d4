#include "sim/scene/steps/timeline_play.hpp"

#include <algorithm>
#include <cmath>

#include "control/channel/channel.hpp"

namespace vmt::sim {

double TrapezoidProfile::Duration() const {
  const double d = std::abs(end - start);
  if (d == 0) return 0;
  if (d < speed * speed / accel) return 2 * std::sqrt(d / accel);
  return d / speed + speed / accel;
}

double TrapezoidProfile::At(double t_s) const {
  const double d = std::abs(end - start);
  const double sign = end >= start ? 1 : -1;
  const double t = t_s - t0_s;
  const double total = Duration();
  if (t <= 0) return start;
  if (t >= total) return end;
  const double peak = std::min(speed, std::sqrt(d * accel));
  const double t_acc = peak / accel;
  double s;
  if (t < t_acc)
    s = 0.5 * accel * t * t;
  else if (t < total - t_acc)
    s = 0.5 * peak * t_acc + peak * (t - t_acc);
  else
    s = d - 0.5 * accel * (total - t) * (total - t);
  return start + sign * s;
}

bool Holds(const Condition& c, const control::AmplifierTelegram& at,
           const std::vector<ClutchState>& clutches, const control::channel::Channel* channel,
           const control::gateway::SignalImage* image) {
  using namespace control::drive_status;
  switch (c.kind) {
    case Condition::Kind::kSignal:
      return image && image->Number(c.index) == c.signal_value;
    case Condition::Kind::kInput:
      return (at.inputs[c.index] != 0) == c.value;
    case Condition::Kind::kInPosition:
      return ((at.feedback[c.index].status & kInPosition) != 0) == c.value;
    case Condition::Kind::kAtSpeed:
      return ((at.feedback[c.index].status & kAtSpeed) != 0) == c.value;
    case Condition::Kind::kStandstill:
      return ((at.feedback[c.index].status & kStandstill) != 0) == c.value;
    case Condition::Kind::kClutch:
      return clutches[c.index] == c.clutch;
    case Condition::Kind::kNc:
      return channel && channel->state() == c.nc;
  }
  return false;
}

}  // namespace vmt::sim
