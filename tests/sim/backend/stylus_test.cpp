// The stylus on its compliant mount against a stepped shaft: approaches at a known feed along X
// and Z, where the switch trips (to 0.1 µm of the analytic contact), NO vs NC, release,
// over-travel, the ready message and a sphere deflected from the start.

#include "sim/backend/stylus.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/backend/machine_backend.hpp"

namespace vmt::sim {
namespace {

constexpr double kMm = 1e-3;
constexpr double kAnalyticTolM = 1e-7;  // 0.1 µm

// Collar r 30 from z 0 to 50, then the journal r 20 to z 100 (mm).
RevolvedPart SteppedShaft() {
  return {"workpiece", "spindle", {{0, 50 * kMm, 0, 30 * kMm}, {50 * kMm, 100 * kMm, 0, 20 * kMm}}};
}

// lathe-c1's stylus: one ruby r 3, pre-travel 5 µm, over-travel 1 mm, on input 7.
ProbeStylus Ruby(bool normally_closed = false) {
  ProbeStylus s;
  s.t_number = 3;
  s.normally_closed = normally_closed;
  s.spheres = {{Eigen::Vector3d::Zero(), 3 * kMm}};
  s.pre_travel_m = 5e-6;
  s.over_travel_m = 1 * kMm;
  s.contact_input = 7;
  return s;
}

struct Change {
  int tick = -1;
  bool level = false;
  Eigen::Vector3d at_m;  // the centre at the reported instant
};

// Moves the sphere centre from `start` at `velocity` (m/s) for `ticks` drive ticks, ready,
// and records every change of the contact input and the over-travel event.
struct Approach {
  Approach(const ProbeStylus& stylus, const Eigen::Vector3d& start, const Eigen::Vector3d& velocity,
           int ticks, bool ready = true)
      : stylus(stylus) {
    Eigen::Vector3d p = start;
    for (int t = 0; t < ticks; ++t) {
      const Eigen::Vector3d next = p + velocity * kDriveTickS;
      const StylusTick tick = StepStylus(stylus, part, state, {p}, {next}, ready);
      EXPECT_EQ(tick.io_input, stylus.contact_input);
      EXPECT_GE(tick.tick_fraction, 0);
      EXPECT_LE(tick.tick_fraction, 1);
      if (tick.changed) changes.push_back({t, tick.level, p + tick.tick_fraction * (next - p)});
      if (tick.over_travel) {
        over_travel.push_back({t, true, p + tick.over_travel_fraction * (next - p)});
        over_travel_point = tick.over_travel_point_m;
      }
      last = tick;
      p = next;
    }
    end = p;
  }
  ProbeStylus stylus;
  RevolvedPart part = SteppedShaft();
  StylusState state;
  std::vector<Change> changes, over_travel;
  Eigen::Vector3d over_travel_point, end;
  StylusTick last;
};

double MmPerMinToMPerS(double f) { return f / 60 / 1000; }

class FeedTest : public ::testing::TestWithParam<double> {};

TEST_P(FeedTest, ApproachAlongXTripsWhereThePreTravelIsReached) {
  // Radially onto the journal (r 20) at z 75, from 50 µm clear.
  const double v = MmPerMinToMPerS(GetParam());
  const Approach a(Ruby(), {(23 + 0.05) * kMm, 0, 75 * kMm}, {-v, 0, 0},
                   static_cast<int>(0.1 * kMm / v / kDriveTickS) + 2);
  ASSERT_EQ(a.changes.size(), 1u);
  EXPECT_TRUE(a.changes[0].level);
  // The ruby's surface r 3 meets the journal at x 23; the switch trips 5 µm further.
  EXPECT_NEAR(a.changes[0].at_m.x(), 23 * kMm - 5e-6, kAnalyticTolM);
  EXPECT_NEAR(a.changes[0].at_m.x(), 23 * kMm - 5e-6, 1e-9);  // in fact far better
  EXPECT_EQ(a.changes[0].tick, static_cast<int>(std::floor(55e-6 / v / kDriveTickS)));
  EXPECT_NEAR(a.last.deflection_m, 23 * kMm - a.end.x(), 1e-12);
  EXPECT_EQ(a.last.sphere, 0);
  EXPECT_FALSE(a.state.damaged);
}

TEST_P(FeedTest, ApproachAlongZOntoTheShoulderTrips) {
  // Along -Z onto the collar's shoulder (z 50, r 20..30) at r 25.
  const double v = MmPerMinToMPerS(GetParam());
  const Approach a(Ruby(), {25 * kMm, 0, (53 + 0.04) * kMm}, {0, 0, -v},
                   static_cast<int>(0.08 * kMm / v / kDriveTickS) + 2);
  ASSERT_EQ(a.changes.size(), 1u);
  EXPECT_TRUE(a.changes[0].level);
  EXPECT_NEAR(a.changes[0].at_m.z(), 53 * kMm - 5e-6, kAnalyticTolM);
  EXPECT_NEAR(a.changes[0].at_m.z(), 53 * kMm - 5e-6, 1e-9);
}

TEST_P(FeedTest, ApproachOffTheAxisMeetsTheRoundSurface) {
  // Along -X 10 mm beside the axis: the contact lies where hypot(x, 10) = 23 - 0.005.
  const double v = MmPerMinToMPerS(GetParam());
  const double x_contact = std::sqrt(22.995 * 22.995 - 100) * kMm;
  const Approach a(Ruby(), {x_contact + 0.05 * kMm, 10 * kMm, 75 * kMm}, {-v, 0, 0},
                   static_cast<int>(0.1 * kMm / v / kDriveTickS) + 2);
  ASSERT_EQ(a.changes.size(), 1u);
  EXPECT_NEAR(a.changes[0].at_m.x(), x_contact, kAnalyticTolM);
}

// A measuring feed, a faster one and the rapid of X: 1.7 µm, 83 µm and 100 µm per tick.
INSTANTIATE_TEST_SUITE_P(Stylus, FeedTest, ::testing::Values(137.0, 2000.0, 24000.0));

TEST(Stylus, NormallyClosedOpensWhereNormallyOpenCloses) {
  const double v = MmPerMinToMPerS(300);
  const Eigen::Vector3d start(23.05 * kMm, 0, 75 * kMm), velocity(-v, 0, 0);
  const Approach no(Ruby(false), start, velocity, 300);
  const Approach nc(Ruby(true), start, velocity, 300);
  ASSERT_EQ(no.changes.size(), 1u);
  EXPECT_TRUE(no.changes[0].level);
  // NC: closed (1) at rest from the first tick on, open (0) when deflected.
  ASSERT_EQ(nc.changes.size(), 2u);
  EXPECT_EQ(nc.changes[0].tick, 0);
  EXPECT_TRUE(nc.changes[0].level);
  EXPECT_NEAR((nc.changes[0].at_m - start).norm(), 0, 1e-15);
  EXPECT_FALSE(nc.changes[1].level);
  EXPECT_EQ(nc.changes[1].tick, no.changes[0].tick);
  EXPECT_NEAR(nc.changes[1].at_m.x(), no.changes[0].at_m.x(), 1e-12);
}

TEST(Stylus, TripsOnTheWayInAndReleasesOnTheWayOut) {
  const double v = MmPerMinToMPerS(500);
  Approach in(Ruby(), {23.02 * kMm, 0, 75 * kMm}, {-v, 0, 0}, 100);
  ASSERT_EQ(in.changes.size(), 1u);
  ASSERT_TRUE(in.state.tripped);
  // Back out from where it stands, same state.
  StylusState state = in.state;
  Eigen::Vector3d p = in.end;
  std::vector<Change> out;
  for (int t = 0; t < 200; ++t) {
    const Eigen::Vector3d next = p + Eigen::Vector3d(v, 0, 0) * kDriveTickS;
    const StylusTick tick = StepStylus(in.stylus, in.part, state, {p}, {next}, true);
    if (tick.changed) out.push_back({t, tick.level, p + tick.tick_fraction * (next - p)});
    p = next;
  }
  ASSERT_EQ(out.size(), 1u);
  EXPECT_FALSE(out[0].level);
  EXPECT_NEAR(out[0].at_m.x(), 23 * kMm - 5e-6, kAnalyticTolM);
  EXPECT_FALSE(state.tripped);
}

TEST(Stylus, ABriefDeflectionBelowThePreTravelDoesNotTrip) {
  // Touch the journal, 3 µm deep, then away: the switch never trips.
  const double v = MmPerMinToMPerS(100);
  Approach in(Ruby(), {23.01 * kMm, 0, 75 * kMm}, {-v, 0, 0},
              static_cast<int>(13e-6 / v / kDriveTickS));
  EXPECT_TRUE(in.changes.empty());
  EXPECT_GT(in.last.deflection_m, 2e-6);
  EXPECT_LT(in.last.deflection_m, 5e-6);
}

TEST(Stylus, BeyondTheOverTravelTheStylusIsDamagedOnce) {
  const double v = MmPerMinToMPerS(2000);
  // From 50 µm clear to 1.5 mm deep into the journal.
  const Approach a(Ruby(), {23.05 * kMm, 0, 75 * kMm}, {-v, 0, 0},
                   static_cast<int>(1.55 * kMm / v / kDriveTickS));
  ASSERT_EQ(a.over_travel.size(), 1u);
  EXPECT_NEAR(a.over_travel[0].at_m.x(), 22 * kMm, kAnalyticTolM);
  EXPECT_NEAR((a.over_travel_point - Eigen::Vector3d(20 * kMm, 0, 75 * kMm)).norm(), 0, 1e-7);
  EXPECT_TRUE(a.state.damaged);
  EXPECT_GT(a.last.deflection_m, 1.4 * kMm);
  // Still deflected: the switch stays tripped, the event does not repeat.
  ASSERT_EQ(a.changes.size(), 1u);
  EXPECT_TRUE(a.last.level);
}

// From beyond the part's bounding cylinder (where a tick is answered without the exact
// distance) the approach trips where one from near the part does.
TEST(Stylus, AnApproachFromFarTripsWhereTheSurfaceIs) {
  const double v = MmPerMinToMPerS(24000);  // the rapid: 0.1 mm per tick
  const Approach a(Ruby(), {40 * kMm, 0, 25 * kMm}, {-v, 0, 0}, 75);
  ASSERT_EQ(a.changes.size(), 1u);
  EXPECT_TRUE(a.changes[0].level);
  EXPECT_NEAR(a.changes[0].at_m.x(), 33 * kMm - 5e-6, kAnalyticTolM);
  EXPECT_TRUE(a.over_travel.empty());
}

// One tick from far outside to beyond the over-travel: neither crossing is passed over.
TEST(Stylus, OneTickFromFarIntoThePartTripsAndCrashes) {
  const ProbeStylus s = Ruby();
  StylusState state;
  const Eigen::Vector3d from(60 * kMm, 0, 25 * kMm), to(31 * kMm, 0, 25 * kMm);
  const StylusTick quiet = StepStylus(s, SteppedShaft(), state, {from}, {from}, true);
  EXPECT_FALSE(quiet.changed);
  EXPECT_EQ(quiet.sphere, -1);
  const StylusTick tick = StepStylus(s, SteppedShaft(), state, {from}, {to}, true);
  EXPECT_TRUE(tick.changed);
  EXPECT_TRUE(tick.level);
  EXPECT_NEAR((from + tick.tick_fraction * (to - from)).x(), 33 * kMm - 5e-6, kAnalyticTolM);
  EXPECT_TRUE(tick.over_travel);
  EXPECT_NEAR((from + tick.over_travel_fraction * (to - from)).x(), 32 * kMm, kAnalyticTolM);
  EXPECT_NEAR(tick.deflection_m, 2 * kMm, 1e-12);
  EXPECT_TRUE(state.damaged);
}

TEST(Stylus, ASphereDeflectedAtTheStartSetsTheSwitchFromTheFirstTick) {
  const ProbeStylus s = Ruby();
  const RevolvedPart part = SteppedShaft();
  StylusState state;
  const Eigen::Vector3d p(22.9 * kMm, 0, 75 * kMm);  // 0.1 mm deep into the journal
  const StylusTick first = StepStylus(s, part, state, {p}, {p}, true);
  EXPECT_TRUE(first.changed);
  EXPECT_TRUE(first.level);
  EXPECT_EQ(first.tick_fraction, 0);
  EXPECT_NEAR(first.deflection_m, 0.1 * kMm, 1e-12);
  EXPECT_FALSE(first.over_travel);
  const StylusTick second = StepStylus(s, part, state, {p}, {p}, true);
  EXPECT_FALSE(second.changed);
  EXPECT_TRUE(second.level);
}

TEST(Stylus, WithoutTheReadyMessageTheInputStaysLow) {
  const double v = MmPerMinToMPerS(300);
  // NO: deflected, but the probe is off: nothing reaches the input.
  const Approach off(Ruby(false), {23.05 * kMm, 0, 75 * kMm}, {-v, 0, 0}, 300, false);
  EXPECT_TRUE(off.changes.empty());
  EXPECT_TRUE(off.state.tripped);  // the mount deflects all the same
  // NC, off: 0 too, although an NC contact at rest is closed.
  const Approach nc_off(Ruby(true), {23.05 * kMm, 0, 75 * kMm}, {v, 0, 0}, 10, false);
  EXPECT_TRUE(nc_off.changes.empty());
  // The ready message comes while the stylus stands deflected: the level shows at once.
  StylusState state = off.state;
  const StylusTick on = StepStylus(off.stylus, off.part, state, {off.end}, {off.end}, true);
  EXPECT_TRUE(on.changed);
  EXPECT_TRUE(on.level);
  EXPECT_EQ(on.tick_fraction, 0);
  // ... and goes with it.
  const StylusTick gone = StepStylus(off.stylus, off.part, state, {off.end}, {off.end}, false);
  EXPECT_TRUE(gone.changed);
  EXPECT_FALSE(gone.level);
  EXPECT_EQ(gone.tick_fraction, 0);
}

TEST(Stylus, FarFromThePartNothingHappens) {
  const Approach a(Ruby(), {60 * kMm, 0, 75 * kMm}, {-0.5, 0, 0}, 100);
  EXPECT_TRUE(a.changes.empty());
  EXPECT_EQ(a.last.deflection_m, 0);
  EXPECT_EQ(a.last.sphere, -1);
}

TEST(Stylus, TheFirstOfSeveralSpheresToTouchTripsTheSwitch) {
  // A second, smaller sphere 1 mm ahead of the first along -X (a star stylus' finger).
  ProbeStylus s = Ruby();
  s.spheres.push_back({Eigen::Vector3d(-1 * kMm, 0, 0), 1 * kMm});
  const Eigen::Vector3d link_origin(23.05 * kMm, 0, 75 * kMm);
  const std::vector<Eigen::Vector3d> start =
      SphereCentres(s, Eigen::Isometry3d(Eigen::Translation3d(link_origin)));
  ASSERT_EQ(start.size(), 2u);
  EXPECT_NEAR((start[1] - Eigen::Vector3d(22.05 * kMm, 0, 75 * kMm)).norm(), 0, 1e-15);
  // Sphere 2 (r 1 at 1 mm ahead) reaches r 20 when the link is at x 22; sphere 1 at x 23.
  // Sphere 1 comes first.
  const double v = MmPerMinToMPerS(600);
  StylusState state;
  const RevolvedPart part = SteppedShaft();
  std::vector<Eigen::Vector3d> p = start;
  for (int t = 0; t < 200; ++t) {
    std::vector<Eigen::Vector3d> next = p;
    for (Eigen::Vector3d& c : next) c.x() -= v * kDriveTickS;
    const StylusTick tick = StepStylus(s, part, state, p, next, true);
    if (tick.changed) {
      EXPECT_TRUE(tick.level);
      EXPECT_NEAR(p[0].x() + tick.tick_fraction * (next[0].x() - p[0].x()), 23 * kMm - 5e-6,
                  kAnalyticTolM);
      EXPECT_EQ(tick.sphere, 0);
      return;
    }
    p = next;
  }
  ADD_FAILURE() << "the switch did not trip";
}

}  // namespace
}  // namespace vmt::sim
