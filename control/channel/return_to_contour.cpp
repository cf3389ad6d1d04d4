#include "control/channel/return_to_contour.hpp"

#include <cmath>
#include <limits>

#include "control/channel/block_search_support.hpp"

namespace vmt::control::channel {

ReturnLeg FirstReturnLeg(const std::vector<double>& commanded, const std::vector<double>& restart,
                         const std::vector<ChannelAxis>& axes, bool cax_track) {
  if (cax_track) {
    for (size_t a = 0; a < commanded.size(); ++a) {
      if (axes[a].name != "C" || std::abs(restart[a] - commanded[a]) < 1e-12) continue;
      ReturnLeg leg{commanded, true};
      leg.to[a] = restart[a];
      return leg;
    }
  }
  return {restart, false};
}

StraightReturn PlanStraightReturn(const std::vector<double>& from, const std::vector<double>& to,
                                  const std::vector<ChannelAxis>& axes) {
  StraightReturn r;
  r.motion.start = from;
  r.motion.end = to;
  double rate = std::numeric_limits<double>::infinity(), accel = rate;
  for (size_t a = 0; a < from.size(); ++a) {
    const double distance = std::abs(to[a] - from[a]);
    if (distance < 1e-12) continue;
    rate = std::min(rate, axes[a].rapid_per_s / distance);
    accel = std::min(accel, axes[a].acceleration / distance);
  }
  if (!std::isfinite(rate)) return r;  // already there
  r.motion.moves = true;
  r.motion.length = 0;
  for (size_t a = 0; a < from.size(); ++a) r.motion.length += std::pow(to[a] - from[a], 2);
  r.motion.length = std::sqrt(r.motion.length);
  r.rate = rate;
  r.accel = accel;
  return r;
}

ManualReturn CheckManualReturn(const std::vector<double>& commanded,
                               const std::vector<double>& restart,
                               const std::vector<ChannelAxis>& axes, int64_t deviation_max) {
  ManualReturn r;
  double deviation2 = 0;
  for (size_t a = 0; a < commanded.size(); ++a)
    if (MainAxis(axes[a].name)) deviation2 += std::pow(commanded[a] - restart[a], 2);
  r.deviation_mm = std::sqrt(deviation2);
  r.allowed_mm = static_cast<double>(deviation_max) * 1e-4;
  r.within = !(r.deviation_mm > r.allowed_mm + 1e-9);
  if (!r.within) return r;
  r.offset.assign(commanded.size(), 0.0);
  for (size_t a = 0; a < commanded.size(); ++a) r.offset[a] = commanded[a] - restart[a];
  return r;
}

}  // namespace vmt::control::channel
