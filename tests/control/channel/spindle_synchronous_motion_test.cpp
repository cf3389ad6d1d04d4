// The law of G33 thread cutting (ramp-in, run-out, zero mark) and the planning of G33/G63/G64
// blocks, on their own: the channel's thread tests drive them through whole programs.

#include "control/channel/spindle_synchronous_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vmt::control::channel {
namespace {

std::vector<axes::AxisParameters> LatheAxes() {
  axes::AxisParameters x, z, c;
  x.name = "X";
  x.rapid_per_s = 200;
  x.acceleration = 2000;
  x.travel_min = -10;
  x.travel_max = 300;
  z = x;
  z.name = "Z";
  z.acceleration = 1000;
  z.travel_max = 500;
  c.name = "C";
  c.rotary = true;
  c.rapid_per_s = 3600;
  c.acceleration = 36000;
  return {x, z, c};
}

nc::PreparedBlock ThreadBlock(double x, double z, double lead) {
  nc::PreparedBlock b;
  b.motion = nc::Motion::kLinear;
  b.target = {x, z, 0};
  b.programmed = 0b011;
  b.modal.lead = lead;
  return b;
}

TEST(SpindleSynchronousMotion, TheRampMeetsTheLawWithItsSlope) {
  ThreadLaw law;
  law.mm_per_deg = 2.0 / 360;  // lead 2 mm
  law.length = 40;
  law.ramp_in_deg = ThreadLaw::RampDeg(law.mm_per_deg, 6000, 500);  // 1000 rpm, 500 mm/s^2
  // The ramp: k w^2 / (2 a) degrees each side of the mark.
  EXPECT_NEAR(law.ramp_in_deg, 2.0 / 360 * 6000 * 6000 / 1000, 1e-9);
  EXPECT_EQ(law.PathAt(-law.ramp_in_deg - 1), 0);
  EXPECT_EQ(law.PathAt(-law.ramp_in_deg), 0);
  // Continuous, and tangent where the ramp joins s = k psi.
  const double p0 = law.ramp_in_deg, h = 1e-6;
  EXPECT_NEAR(law.PathAt(p0 - h), law.mm_per_deg * (p0 - h), 1e-9);
  EXPECT_NEAR((law.PathAt(p0) - law.PathAt(p0 - h)) / h, law.mm_per_deg, 1e-6);
  EXPECT_NEAR(law.PathAt(p0 + 100), law.mm_per_deg * (p0 + 100), 1e-12);
  // The acceleration over the phase is constant on the ramp: equal second differences.
  const double d = p0 / 4;
  const double a1 = law.PathAt(-d) - 2 * law.PathAt(0) + law.PathAt(d);
  const double a2 = law.PathAt(0) - 2 * law.PathAt(d) + law.PathAt(2 * d);
  EXPECT_NEAR(a1, a2, 1e-12);
  // Without a run-out the path never passes the target.
  EXPECT_EQ(law.PathAt(law.LawEndDeg() + 720), law.length);
}

TEST(SpindleSynchronousMotion, TheRunOutEndsAtTheTargetAtRest) {
  ThreadLaw law;
  law.mm_per_deg = 1.5 / 360;
  law.length = 30;
  law.ramp_in_deg = 50;
  const double begin = law.LawEndDeg() - 80;  // the run-out begins 80 degrees before the end
  law.BeginRunOut(begin);
  ASSERT_TRUE(law.running_out());
  EXPECT_NEAR(law.run_out_deg, 80, 1e-9);
  EXPECT_NEAR(law.run_out_end_deg, begin + 160, 1e-9);
  // On the law up to where the run-out leaves it, then monotone up to L, reached with zero
  // slope, and L after.
  EXPECT_NEAR(law.PathAt(begin), law.mm_per_deg * begin, 1e-12);
  double last = law.PathAt(begin);
  for (double psi = begin; psi <= law.run_out_end_deg; psi += 1) {
    const double s = law.PathAt(psi);
    EXPECT_GE(s, last - 1e-12) << psi;
    EXPECT_LE(s, law.length) << psi;
    last = s;
  }
  const double h = 1e-4;
  EXPECT_NEAR((law.PathAt(law.run_out_end_deg) - law.PathAt(law.run_out_end_deg - h)) / h, 0,
              1e-5);
  EXPECT_EQ(law.PathAt(law.run_out_end_deg), law.length);
  EXPECT_EQ(law.PathAt(law.run_out_end_deg + 1000), law.length);
}

TEST(SpindleSynchronousMotion, TheZeroMarkIsAWholeTurnAheadOfTheRamp) {
  // Turning forwards from 100 deg with a ramp of 30: the first mark at least 130 is 360.
  EXPECT_EQ(ThreadZeroMark(100, +1, 30), 360);
  EXPECT_EQ(ThreadZeroMark(330, +1, 30), 360);
  EXPECT_EQ(ThreadZeroMark(331, +1, 30), 720);
  // Backwards (M4): the first mark at most phi - ramp.
  EXPECT_EQ(ThreadZeroMark(100, -1, 30), 0);
  EXPECT_EQ(ThreadZeroMark(20, -1, 30), -360);
  EXPECT_EQ(ThreadZeroMark(-400, -1, 30), -720);
  // Every pass of a thread cuts the same groove: the mark is a multiple of a turn.
  for (double phi = -1000; phi < 1000; phi += 37.3)
    EXPECT_EQ(std::fmod(ThreadZeroMark(phi, +1, 12.5), 360), 0) << phi;
}

TEST(SpindleSynchronousMotion, ATaperThreadsLeadIsAlongItsLongestTravel) {
  const auto axes = LatheAxes();
  SynchronousPath path;
  // Z travels 40, X 30: the lead of 2 mm is along Z; the path of 50 advances 2.5 mm a turn.
  ASSERT_FALSE(PlanSynchronousPath(ThreadBlock(50, 60, 2), {20, 100, 0}, {0, 0, 0}, axes, 0,
                                   path));
  ASSERT_TRUE(path.line.moves);
  EXPECT_NEAR(path.length, 50, 1e-9);
  EXPECT_NEAR(path.mm_per_deg, 50.0 / 40 * 2 / 360, 1e-12);
  // The axes' limits along the path: no faster than the axes' rapid allows, as G01 plans it.
  EXPECT_GT(path.max_speed, 0);
  EXPECT_LE(path.max_speed, 200 * 50.0 / 40 + 1e-9);
  EXPECT_GT(path.max_accel, 0);
  EXPECT_LE(path.max_accel, 2000 * 50.0 / 30 + 1e-9);
}

TEST(SpindleSynchronousMotion, RotaryAxesAndNoMoveAreRefusedOrDone) {
  const auto axes = LatheAxes();
  SynchronousPath path;
  nc::PreparedBlock with_c = ThreadBlock(50, 60, 2);
  with_c.target[2] = 90;
  with_c.programmed |= 0b100;
  const auto error = PlanSynchronousPath(with_c, {20, 100, 0}, {0, 0, 0}, axes, 0, path);
  ASSERT_TRUE(error);
  EXPECT_NE(error->text.find("linear axes only, not C"), std::string::npos);
  ASSERT_FALSE(PlanSynchronousPath(ThreadBlock(20, 100, 2), {20, 100, 0}, {0, 0, 0}, axes, 0,
                                   path));
  EXPECT_FALSE(path.line.moves);
  // Beyond the travel: the error of PlanBlockMotion, before the move starts.
  EXPECT_TRUE(
      PlanSynchronousPath(ThreadBlock(20, 900, 2), {20, 100, 0}, {0, 0, 0}, axes, 0, path));
}

TEST(SpindleSynchronousMotion, RigidTappingRunsAtTheSlowestOfPathAndSpindle) {
  const auto axes = LatheAxes();
  SynchronousPath path;
  ASSERT_FALSE(PlanSynchronousPath(ThreadBlock(0, 70, 1.5), {0, 100, 0}, {0, 0, 0}, axes, 0,
                                   path));  // M10 x 1.5, 30 deep along Z
  PathProfile profile;
  // 600 rpm: 15 mm/s along Z, within every limit.
  RigidTappingLimits(path, 600, 0, 0, profile);
  EXPECT_NEAR(profile.max_rate * path.length, 15, 1e-9);
  EXPECT_NEAR(profile.max_accel * path.length, path.max_accel, 1e-9);
  // The spindle's speed limit (1800 deg/s = 300 rpm) caps the path at 7.5 mm/s, its
  // acceleration limit the path's acceleration.
  RigidTappingLimits(path, 600, 1800, 3600, profile);
  EXPECT_NEAR(profile.max_rate * path.length, 7.5, 1e-9);
  EXPECT_NEAR(profile.max_accel * path.length, 1.5 / 360 * 3600, 1e-9);
  // A spindle turning backwards taps at the same speed.
  RigidTappingLimits(path, -600, 0, 0, profile);
  EXPECT_NEAR(profile.max_rate * path.length, 15, 1e-9);
  // No faster than the axes' rapid however fast the spindle.
  RigidTappingLimits(path, 1e6, 0, 0, profile);
  EXPECT_NEAR(profile.max_rate * path.length, path.max_speed, 1e-9);
}

}  // namespace
}  // namespace vmt::control::channel
