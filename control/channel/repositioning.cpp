#include "control/channel/repositioning.hpp"

#include <algorithm>
#include <cmath>

namespace vmt::control::channel {
namespace {

bool Endless(const axes::AxisParameters& axis) {
  return axis.rotary && !(axis.travel_max > axis.travel_min);
}

}  // namespace

const char* ToString(ReposFunction f) {
  switch (f) {
    case ReposFunction::kNone:
      return "none";
    case ReposFunction::kRepositioning:
      return "repositioning";
    case ReposFunction::kRestart:
      return "restart";
  }
  return "?";
}

double ReposDistanceToGo(const axes::AxisParameters& axis, double target, double actual) {
  const double d = target - actual;
  if (!Endless(axis)) return d;
  return d - 360 * std::round(d / 360);  // the short way round, -180..180
}

bool WithinReposWindow(const axes::AxisParameters& axis, double target, double actual) {
  return std::abs(ReposDistanceToGo(axis, target, actual)) <= axis.repos_window + 1e-9;
}

bool WithinFictiveWindow(const axes::AxisParameters& x_axis, nc::FictivePoint target,
                         nc::FictivePoint actual) {
  return std::hypot(target.x1 - actual.x1, target.y1 - actual.y1) <= x_axis.repos_window + 1e-9;
}

ReposZone FictiveZoneOf(double target, double start) {
  if (std::isnan(target)) return {};
  return {true, std::min(target, start), std::max(target, start)};
}

ReposZone ZoneOf(const axes::AxisParameters& axis, double target, double start) {
  if (Endless(axis) || std::isnan(target)) return {};
  return {true, std::min(target, start), std::max(target, start)};
}

bool KeyRestoresSpindle(int spindle_m_before, int key) {
  switch (spindle_m_before) {
    case 3:
    case 4:
      return key == 3 || key == 4;
    case 5:
      return key == 5;
    case 19:
      return key == 19;
  }
  return false;
}

}  // namespace vmt::control::channel
