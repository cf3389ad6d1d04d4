// The path-parameter profile under extreme limits and random profiles with override changes and
// holds: every limit holds and the time stays near the analytic optimum.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "control/channel/path_profile.hpp"
#include "path_profile_test_support.hpp"

namespace vmt::control::channel {
namespace {

using namespace path_profile_testing;

double LogUniform(std::mt19937_64& rng, double lo, double hi) {
  return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
}

TEST(PathProfileTest, ExtremeLimitsFinishNearTheAnalyticTime) {
  // From a jerk that takes minutes to a jerk of 1e300, tiny and huge accelerations and feeds:
  // bounded time, finite, within the limits.
  int runs = 0;
  for (double jerk : {1e-3, 1.0, 1e6, 1e12, 1e300}) {
    for (double accel : {1e-3, 1.0, 1e6, 1e12}) {
      for (double rate : {1e-2, 1.0, 1e6}) {
        for (double end_share : {0.0, 0.5}) {
          PathProfile p;
          p.max_rate = rate;
          p.max_accel = accel;
          p.max_jerk = jerk;
          p.end_rate = end_share * rate;
          const double best = SCurveTime(1, rate, accel, jerk);
          const auto trace = Simulate(p, static_cast<int>(1.03 * best / kDt) + 3);
          SCOPED_TRACE(Describe(p));
          ASSERT_EQ(trace.back().u, 1.0) << "analytic " << best;
          EXPECT_EQ(CheckTrace(p, trace), "");
          EXPECT_LE(Cycles(trace) * kDt, 1.03 * best + 2 * kDt) << "analytic " << best;
          ++runs;
        }
      }
    }
  }
  EXPECT_EQ(runs, 120);
}

TEST(PathProfileTest, RandomProfilesFinishWithinLimits) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> uniform(0, 1);
  int runs = 0, abrupt = 0;
  double worst_accel_step = 0, worst_rate_step = 0;
  long total_cycles = 0;
  while (runs < 3000) {
    PathProfile p;
    p.max_rate = LogUniform(rng, 0.05, 5e3);
    p.max_accel = LogUniform(rng, 0.5, 1e7);
    p.max_jerk = LogUniform(rng, 5, 1e13);
    p.end_rate = uniform(rng) < 0.5 ? 0 : 1.5 * uniform(rng) * p.max_rate;
    // Random override changes and holds in the first part of the move, then >= 0.1.
    const double slowest = 0.1;
    const double best = SCurveTime(1, slowest * p.max_rate, p.max_accel, p.max_jerk);
    if (best > 5) continue;  // keep the run time bounded
    ++runs;
    const int window = 1 + static_cast<int>(uniform(rng) * 3 * best / kDt);
    std::vector<double> override(window + 1);
    double o = uniform(rng) < 0.2 ? 0 : slowest + 1.9 * uniform(rng);
    int changes = 1;
    for (int k = 0; k <= window; ++k) {
      if (uniform(rng) < 0.01) {
        o = uniform(rng) < 0.3 ? 0 : slowest + 1.9 * uniform(rng);
        ++changes;
      }
      override[k] = o;
    }
    const double last = slowest + 1.9 * uniform(rng);
    const auto override_at = [&](int k) { return k <= window ? override[k] : last; };
    int held = 0;
    for (double v : override) held += v == 0;
    // Moving at >= 10 % and re-accelerating after each change or hold, to at most the speed
    // a rest-to-rest move over the block could reach.
    const double reachable =
        std::min({2 * p.max_rate, std::sqrt(p.max_accel), std::cbrt(p.max_jerk / 4)});
    const double ramp = RampTime(reachable, p.max_accel, p.max_jerk);
    const int bound = held + static_cast<int>((2 * best + changes * 2 * ramp) / kDt) + 10;
    const auto trace = Simulate(p, override_at, bound + 1);
    total_cycles += Cycles(trace);
    ASSERT_LE(Cycles(trace), bound) << Describe(p);
    ASSERT_EQ(trace.back().u, 1.0) << Describe(p);
    Arrival arrival;
    ASSERT_EQ(CheckTrace(p, trace, &arrival), "");
    if (arrival.accel_step > 1 + kSlack || arrival.rate_step > 1 + kSlack) ++abrupt;
    worst_accel_step = std::max(worst_accel_step, arrival.accel_step);
    worst_rate_step = std::max(worst_rate_step, arrival.rate_step);
  }
  std::printf(
      "%d random profiles, %ld cycles: final step beyond the jerk or acceleration limit in %d; "
      "worst %.3g max_jerk*dt, %.3g max_accel*dt\n",
      runs, total_cycles, abrupt, worst_accel_step, worst_rate_step);
  // The abrupt final step is rare and small.
  EXPECT_LE(abrupt, runs / 300);
  EXPECT_LE(worst_accel_step, 1.5);
  EXPECT_LE(worst_rate_step, 1.0 + kSlack);
}

TEST(PathProfileTest, RandomRestToRestMovesAreNearTimeOptimal) {
  std::mt19937_64 rng(7);
  double worst = 0, worst_ratio = 0, worst_cycles = 0;
  for (int i = 0; i < 2000; ++i) {
    PathProfile p;
    p.max_rate = LogUniform(rng, 0.1, 1e4);
    p.max_accel = LogUniform(rng, 1, 1e7);
    p.max_jerk = LogUniform(rng, 10, 1e11);
    const double best = SCurveTime(1, p.max_rate, p.max_accel, p.max_jerk);
    if (best > 5) continue;
    const auto trace = Simulate(p);
    const double t = Cycles(trace) * kDt;
    ASSERT_EQ(CheckTrace(p, trace), "");
    ASSERT_LE(t, 1.03 * best + 2 * kDt) << Describe(p) << " analytic " << best;
    ASSERT_GE(t, best - kDt) << Describe(p) << " analytic " << best;
    worst = std::max(worst, (t - 2 * kDt) / best);
    worst_ratio = std::max(worst_ratio, t / best);
    worst_cycles = std::max(worst_cycles, (t - best) / kDt);
  }
  std::printf(
      "random: worst time / analytic S-curve time %.4f, worst excess %.2f cycles, worst (time - "
      "2 cycles) / analytic %.4f\n",
      worst_ratio, worst_cycles, worst);
}

}  // namespace
}  // namespace vmt::control::channel
