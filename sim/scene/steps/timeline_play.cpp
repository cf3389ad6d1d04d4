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

double SignalNumber(const control::gateway::SignalImage& image, int id) {
  using control::gateway::SignalType;
  switch (image.table()[id].type) {
    case SignalType::kBool:
      return image.Bool(id) ? 1 : 0;
    case SignalType::kReal:
    case SignalType::kLreal:
      return image.Real(id);
    case SignalType::kString:
      return 0;
    default:
      return static_cast<double>(image.Int(id));
  }
}

void SetSignalNumber(control::gateway::SignalImage& image, int id, double value) {
  using control::gateway::SignalType;
  switch (image.table()[id].type) {
    case SignalType::kBool:
      image.SetBool(id, value != 0);
      return;
    case SignalType::kReal:
    case SignalType::kLreal:
      image.SetReal(id, value);
      return;
    case SignalType::kString:
      return;
    default:
      image.SetInt(id, std::llround(value));
  }
}

bool Holds(const Condition& c, const control::AmplifierTelegram& at,
           const std::vector<ClutchState>& clutches, const control::channel::Channel* channel,
           const control::gateway::SignalImage* image) {
  using namespace control::drive_status;
  switch (c.kind) {
    case Condition::Kind::kSignal:
      return image && SignalNumber(*image, c.index) == c.signal_value;
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
