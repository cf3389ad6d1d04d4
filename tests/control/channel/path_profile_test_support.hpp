#pragma once
// What the path profile's tests share: the jerk-free profile kept as a reference, the analytic
// time-optimal times, a recorder of every cycle and a checker of the limits in each, and the
// table of blocks from 1 um to 1 m.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "control/channel/path_profile.hpp"

namespace vmt::control::channel::path_profile_testing {

inline constexpr double kDt = 1e-3;  // the NC cycle
inline constexpr double kSlack = 1e-9;

// The profile before the jerk limit, kept as the reference for max_jerk = 0.
struct OldPathProfile {
  double u = 0;
  double rate = 0;
  double max_rate = 0;
  double max_accel = 0;

  bool done() const { return u >= 1; }

  void Advance(double dt, double override) {
    if (done()) return;
    const double remaining = 1 - u;
    const double braking = std::sqrt(2 * max_accel * remaining);
    const double target = std::min(max_rate * std::max(0.0, override), braking);
    const double step = max_accel * dt;
    rate = std::clamp(target, rate - step, rate + step);
    if (rate < 0) rate = 0;
    u += rate * dt;
    if (u >= 1 || (remaining < 1e-9 && override > 0) || (rate * dt >= remaining && override > 0)) {
      u = 1;
      rate = 0;
    }
  }
};

// Time from rest to speed v (and, mirrored, from v to rest) under accel and jerk limits.
inline double RampTime(double v, double accel, double jerk) {
  return v * jerk >= accel * accel ? v / accel + accel / jerk : 2 * std::sqrt(v / jerk);
}

// Analytic time-optimal rest-to-rest time over `distance` (7-phase S-curve).
inline double SCurveTime(double distance, double rate, double accel, double jerk) {
  const double ramp = RampTime(rate, accel, jerk);
  if (rate * ramp <= distance) return 2 * ramp + (distance - rate * ramp) / rate;
  // The rate is not reached: the peak rate v with v * RampTime(v) = distance.
  double lo = 0, hi = rate;
  for (int i = 0; i < 200; ++i) {
    const double m = (lo + hi) / 2;
    (m * RampTime(m, accel, jerk) < distance ? lo : hi) = m;
  }
  return 2 * RampTime(hi, accel, jerk);
}

// Analytic acceleration-limited rest-to-rest time (trapezoid).
inline double TrapezoidTime(double distance, double rate, double accel) {
  if (rate * rate / accel <= distance) return rate / accel + distance / rate;
  return 2 * std::sqrt(distance / accel);
}

struct Sample {
  double u, rate, accel, override;
};

// Runs until done or max_cycles; trace[0] is the start, trace[k] the state after cycle k, run at
// trace[k].override.
inline std::vector<Sample> Simulate(PathProfile p, const std::function<double(int)>& override_at,
                                    int max_cycles) {
  std::vector<Sample> trace{{p.u, p.rate, p.accel, 1}};
  for (int k = 1; k <= max_cycles && !p.done(); ++k) {
    const double override = override_at(k);
    p.Advance(kDt, override);
    trace.push_back({p.u, p.rate, p.accel, override});
  }
  return trace;
}

inline std::vector<Sample> Simulate(const PathProfile& p, int max_cycles = 10'000'000) {
  return Simulate(
      p, [](int) { return 1.0; }, max_cycles);
}

inline int Cycles(const std::vector<Sample>& trace) { return static_cast<int>(trace.size()) - 1; }

inline std::string Describe(const PathProfile& p) {
  char s[200];
  std::snprintf(s, sizeof s, "max_rate %.17g max_accel %.17g max_jerk %.17g end_rate %.17g",
                p.max_rate, p.max_accel, p.max_jerk, p.end_rate);
  return s;
}

// What the final cycle (the arrival at u = 1) did.
struct Arrival {
  double accel_step = 0;  // |accel change| in units of max_jerk * dt
  double rate_step = 0;   // |rate change| in units of max_accel * dt
};

// Checks every cycle of a trace of p: no NaN, u monotonic and never past 1, rate >= 0, the
// acceleration and jerk limits (jerk except in the final cycle), rate <= max_rate * override
// except while braking down after an override reduction (or from a carried-in speed), the end at
// rate <= end_rate. Returns an empty string if all hold, else the first violation.
inline std::string CheckTrace(const PathProfile& p, const std::vector<Sample>& trace,
                              Arrival* arrival = nullptr) {
  const double jerk_step = p.max_jerk * kDt * (1 + kSlack);
  const double accel_max = p.max_accel * (1 + kSlack);
  bool braking_down = trace[0].rate > p.max_rate * (1 + kSlack);
  for (size_t k = 1; k < trace.size(); ++k) {
    const Sample &s = trace[k], &prev = trace[k - 1];
    const auto fail = [&](const char* what) {
      std::ostringstream where;
      where.precision(17);
      where << what << " in cycle " << k << " (u " << s.u << " rate " << s.rate << " accel "
            << s.accel << ", before u " << prev.u << " rate " << prev.rate << " accel "
            << prev.accel << ", override " << s.override << ") of " << Describe(p);
      return where.str();
    };
    if (!std::isfinite(s.u) || !std::isfinite(s.rate) || !std::isfinite(s.accel))
      return fail("not finite");
    if (s.u < prev.u) return fail("u decreased");
    if (s.u > 1) return fail("u past 1");
    if (s.rate < -1e-12) return fail("negative rate");
    if (std::abs(s.accel) > accel_max) return fail("acceleration limit");
    const bool final = s.u >= 1;
    if (!final && std::abs(s.accel - prev.accel) > jerk_step) return fail("jerk limit");
    // The rate cannot change by more than the acceleration limit allows in one cycle.
    if (!final && std::abs(s.rate - prev.rate) > p.max_accel * kDt * (1 + kSlack))
      return fail("rate step beyond max_accel * dt");
    const double limit = p.max_rate * s.override;
    // After a reduction the rate may go on rising while the acceleration is brought down.
    if (s.override < prev.override) braking_down = true;
    if (braking_down && s.rate <= limit * (1 + kSlack) && s.accel <= 0) braking_down = false;
    if (!braking_down && s.rate > limit * (1 + kSlack) + 1e-12) return fail("rate limit");
    if (final) {
      if (s.rate > p.end_rate * (1 + kSlack) + 1e-12) return fail("above end_rate");
      if (k != trace.size() - 1) return fail("went on after the end");
      if (arrival) {
        arrival->accel_step = std::abs(s.accel - prev.accel) / (p.max_jerk * kDt);
        arrival->rate_step = std::abs(s.rate - prev.rate) / (p.max_accel * kDt);
      }
    }
  }
  return "";
}

// A block of `length` (mm) at `feed` (mm/s) with axis limits accel (mm/s^2) and jerk (mm/s^3),
// in units of u.
inline PathProfile Block(double length, double feed, double accel, double jerk) {
  PathProfile p;
  p.max_rate = feed / length;
  p.max_accel = accel / length;
  p.max_jerk = jerk / length;
  return p;
}

struct Case {
  double length, feed, accel, jerk;
};

// Lengths from 1 um to 1 m: long blocks that cruise, blocks that reach the acceleration but not
// the feed, blocks that reach neither, blocks shorter than one cycle, huge and small jerk.
inline const std::vector<Case> kCases = {
    {100, 100, 4000, 40000},   {100, 100, 4000, 4e6},    {100, 500, 2000, 20000},
    {1000, 1000, 5000, 50000}, {10, 100, 4000, 40000},   {1, 100, 4000, 40000},
    {0.1, 100, 4000, 40000},   {0.01, 100, 4000, 40000}, {0.001, 100, 4000, 40000},
    {5, 50, 1000, 1e6},        {5, 50, 1000, 100},       {20, 200, 10000, 1e5},
    {0.3, 20, 500, 5000},      {50, 33.3, 777, 12345},   {2.5, 1000, 100, 1e4},
    {100, 100, 4000, 1e12},    {0.001, 1e5, 1e5, 1e12},  {1e-6, 100, 4000, 40000},
    {1e-3, 100, 4000, 1e9},    {250, 80, 800, 8000},     {7, 300, 3000, 3e4},
    {0.05, 10, 100, 1e3},      {40, 400, 4000, 4000},    {3, 60, 30000, 3e6},
};

// Time-optimal braking time from rate v, acceleration a to rest under jerk and accel limits,
// the distance aside: a lower bound on the time any profile needs from that state.
inline double BrakingTime(double v, double a, double accel, double jerk) {
  if (a < 0 && v <= a * a / (2 * jerk)) return -a / jerk;
  const double peak = std::sqrt(jerk * v + a * a / 2);
  if (peak <= accel) return (a + peak) / jerk + peak / jerk;
  return (a + accel) / jerk + (v + a * a / (2 * jerk) - accel * accel / jerk) / accel +
         accel / jerk;
}

}  // namespace vmt::control::channel::path_profile_testing
