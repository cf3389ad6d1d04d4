// The stylus inside the backends: lathe-c1's ruby (T3, station 3) driven in X onto a d60 shaft
// trips IPROBE_CONTACT within the tick, and the drives' latch holds X where the contact really
// was; the latch needs S-0-0170 = 3 before the enable's 0-1 (fast-measurement 7.3); driven on,
// the stylus passes its over-travel and reports the crash.

#include "sim/backend/stylus_contacts.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/runner/make_backend.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using control::DriveMode;
namespace pc = control::probe_control;
using testing::Bench;
using testing::Lathe;

constexpr double kMm = 1e-3;
constexpr double kZMm = 100;       // the ruby at z ~ 160 mm: mid-shaft
constexpr double kStation3 = 60;   // T: 30 degrees per station, station 1 at 0
constexpr double kStartXMm = 31;   // the ruby's lowest point 1 mm clear of the shaft
// The d60 shaft, z 60..220 mm on the spindle (the scenes' `workpiece: {diameter: 60, ...}`).
const RevolvedPart kShaft{"workpiece", "spindle", {{60 * kMm, 220 * kMm, 0, 30 * kMm}}};
// lathe-c1 gives T3 the tool list's X 0 / Z 0 like the turning tool, so X reads the radius of
// the ruby's lowest point (checked below). The switch trips when the part has pushed the ruby
// back by the pre-travel, 5 µm: with the lowest point at r 30 - 0.005.
constexpr double kContactXMm = 30 - 0.005;  // 29.995
// The over-travel, 1 mm of deflection: the lowest point at r 29.
constexpr double kOverTravelXMm = 30 - 1.0;

struct StylusRig {
  explicit StylusRig(BackendKind kind)
      : backend(MakeBackend(kind, Lathe(), {{{"X", kStartXMm}, {"Z", kZMm}, {"T", kStation3}}, {}})),
        bench(*backend),
        x(bench.Drive("X")),
        contact(bench.Io("IPROBE_CONTACT")) {
    backend->SetWorkpiece(kShaft);
    bench.Output("QPROBE_ON", true);  // the probe on: the contact shows once it is ready
    bench.RunUntil([&] { return bench.Input("IPROBE_READY"); }, 1.0);
  }
  control::ProbeControl& probe() { return bench.mdt().setpoints[x].probe; }
  const control::ProbeInputStatus& status() { return bench.Feedback("X").probe.probe1; }
  // Feeds X down from where it stands at `feed_mm_min` to `to_mm`, the command a ramp.
  void FeedX(double feed_mm_min, double to_mm, const std::function<void()>& each = {}) {
    const double v = feed_mm_min / 60;
    double command = bench.Feedback("X").position;
    bench.RunUntil(
        [&] {
          if (each) each();
          command = std::max(to_mm, command - v * kDriveTickS);
          // Mode and value only: Bench::Command writes the whole setpoint, probe control too.
          bench.mdt().setpoints[x].mode = DriveMode::kPosition;
          bench.mdt().setpoints[x].value = command;
          return bench.Feedback("X").position <= to_mm + 1e-4;
        },
        10.0);
  }
  std::unique_ptr<MachineBackend> backend;
  Bench bench;
  int x, contact;
};

// The convention the expected numbers rest on: at T3 the ruby's lowest point stands at the radius
// X reads, in the shaft's length.
TEST(StylusContactsTest, XReadsTheRadiusOfTheRubysLowestPoint) {
  const MachineModel& m = Lathe();
  KinematicBackend backend(m, {{{"X", 45.0}, {"Z", kZMm}, {"T", kStation3}}, {}});
  const std::vector<Eigen::Isometry3d> poses = LinkPoses(m, backend.JointPositions());
  ASSERT_EQ(m.probes.size(), 2u);  // the radial T3, then the axial T7
  const ProbeStylus& s = m.probes[0];
  const Eigen::Vector3d c =
      poses[m.LinkIndex("spindle")].inverse() * poses[s.link] * s.spheres[0].centre_m;
  EXPECT_NEAR(std::hypot(c.x(), c.y()) - s.spheres[0].radius_m, 45 * kMm, 1e-9);
  EXPECT_NEAR(c.y(), 0, 1e-9);  // the approach in X is radial
  EXPECT_GT(c.z(), 100 * kMm);
  EXPECT_LT(c.z(), 180 * kMm);
  EXPECT_DOUBLE_EQ(s.pre_travel_m, 0.005 * kMm);
  EXPECT_DOUBLE_EQ(s.over_travel_m, 1 * kMm);
}

// Far from the part a tick is shown quiet from the joints' motion alone, without posing a link:
// across rapid approaches, a turning spindle and a turning turret the switches and the crashes
// are those of posing every tick (a fresh SetPart poses the next tick).
TEST(StylusContactsTest, TicksShownQuietFromTheJointsAloneAreThoseOfPosingEveryTick) {
  const MachineModel& m = Lathe();
  const auto q_at = [&](double x_mm, double t) {
    return KinematicBackend(m, {{{"X", x_mm}, {"Z", kZMm}, {"T", t}}, {}}).JointPositions();
  };
  const std::vector<double> far = q_at(45, kStation3), deep = q_at(28.5, kStation3);
  const size_t spindle = static_cast<size_t>(m.JointIndex("spindle"));
  const size_t turret = static_cast<size_t>(m.JointIndex("turret"));
  StylusContacts quick(m), posed(m);
  quick.SetPart(kShaft);
  ProbeWiring quick_wiring(m), posed_wiring(m);
  std::vector<uint8_t> inputs(m.io.size(), 1);  // every ready message on
  std::vector<uint8_t> quick_shown(m.io.size()), posed_shown(m.io.size());
  std::vector<double> q_before = far;
  int contact_ticks = 0;
  for (int tick = 0; tick < 6000; ++tick) {
    // In at a rapid, out, in at a feed; the turret swings away and back on the way in.
    const double phase = tick < 2000   ? tick / 2000.0
                         : tick < 3000 ? (3000 - tick) / 1000.0
                                       : (tick - 3000) / 3000.0;
    std::vector<double> q = far;
    for (size_t j = 0; j < q.size(); ++j)
      q[j] = far[j] + std::min(1.0, 1.2 * phase) * (deep[j] - far[j]);
    q[spindle] = 0.07 * tick;
    if (tick > 200 && tick < 600) q[turret] += 0.3 * std::sin((tick - 200) * M_PI / 400);
    const double t = tick * kDriveTickS;
    quick.Step(q_before, q, inputs, t, quick_wiring);
    posed.SetPart(kShaft);
    posed.Step(q_before, q, inputs, t, posed_wiring);
    quick_wiring.ShowInputs(quick_shown);
    posed_wiring.ShowInputs(posed_shown);
    ASSERT_EQ(quick_shown, posed_shown) << "tick " << tick;
    contact_ticks +=
        quick_shown[m.probes[0].contact_input] != (m.probes[0].normally_closed ? 1 : 0);
    q_before = q;
  }
  EXPECT_GT(contact_ticks, 100);  // the ruby did touch
  const std::vector<StylusOverTravel> quick_crashes = quick.TakeOverTravels();
  const std::vector<StylusOverTravel> posed_crashes = posed.TakeOverTravels();
  ASSERT_EQ(quick_crashes.size(), posed_crashes.size());
  ASSERT_FALSE(quick_crashes.empty());  // 1.5 mm deep: beyond the over-travel
  for (size_t i = 0; i < quick_crashes.size(); ++i) {
    EXPECT_EQ(quick_crashes[i].t_s, posed_crashes[i].t_s);
    EXPECT_EQ(quick_crashes[i].point_m, posed_crashes[i].point_m);
  }
}

class StylusContactsBackendTest : public ::testing::TestWithParam<BackendKind> {};

TEST_P(StylusContactsBackendTest, TheDriveLatchesXWhereThePreTravelIsReached) {
  StylusRig rig(GetParam());
  rig.probe() = {pc::kProbeCycleActive, pc::kProbe1Positive, false, false};
  rig.bench.Run(kDriveTickS);  // S-0-0170 = 3 first ...
  rig.probe().probe1_enable = true;  // ... then the enable's 0-1 arms probe 1
  const double feed = 600;  // mm/min: 2.5 µm per tick
  double x_before_trip = 1e9;
  rig.FeedX(feed, 29.9, [&] {
    if (!rig.bench.Input("IPROBE_CONTACT")) x_before_trip = rig.bench.Feedback("X").position;
  });
  ASSERT_TRUE(rig.bench.Input("IPROBE_CONTACT"));
  ASSERT_TRUE(rig.status().positive.latched);
  EXPECT_FALSE(rig.status().negative.latched);
  // The exact instant: the ruby's lowest point at r 29.995, not at r 30 (the pre-travel).
  const double tol = GetParam() == BackendKind::kKinematic ? 1e-6 : 1e-5;  // mm
  EXPECT_NEAR(rig.status().positive.exact_position, kContactXMm, tol);
  // The measured value: the actual position of the tick that sampled the edge, within one
  // tick's travel and half an encoder increment beyond the contact.
  const double tick_travel = feed / 60 * kDriveTickS;
  EXPECT_LE(rig.status().positive.measured_value, kContactXMm + 0.00005);
  EXPECT_GE(rig.status().positive.measured_value, kContactXMm - tick_travel - 0.00005);
  // Until the pre-travel the switch stays open: the last position read with it open lies
  // above the trip point.
  EXPECT_GT(x_before_trip, kContactXMm - 0.00005);
  EXPECT_TRUE(rig.backend->TakeStylusOverTravels().empty());
}

TEST_P(StylusContactsBackendTest, AnEnableSetBeforeTheProbeFunctionDoesNotArm) {
  StylusRig rig(GetParam());
  rig.probe() = {0, pc::kProbe1Positive, true, false};
  rig.bench.Run(kDriveTickS);
  rig.probe().probe_cycle_command = pc::kProbeCycleActive;  // S-0-0170 = 3 after the enable
  rig.FeedX(600, 29.9);
  EXPECT_TRUE(rig.bench.Input("IPROBE_CONTACT"));
  EXPECT_TRUE(rig.status().level);  // S-0-0401 shows the contact ...
  EXPECT_FALSE(rig.status().positive.latched);  // ... but nothing latched it
}

TEST_P(StylusContactsBackendTest, DrivenBeyondTheOverTravelTheStylusCrashes) {
  StylusRig rig(GetParam());
  // The tick in which X passed r 29 (the lowest point 1 mm deep): its start and end.
  double t_start = -1, t_end = -1, t_last = rig.backend->time_s();
  rig.FeedX(1200, 28.8, [&] {
    if (t_end < 0 && rig.bench.Feedback("X").position <= kOverTravelXMm) {
      t_start = t_last;
      t_end = rig.backend->time_s();
    }
    t_last = rig.backend->time_s();
  });
  const std::vector<StylusOverTravel> crashes = rig.backend->TakeStylusOverTravels();
  ASSERT_EQ(crashes.size(), 1u);
  const StylusOverTravel& o = crashes[0];
  EXPECT_EQ(o.t_number, 3);
  EXPECT_EQ(o.sphere, 0);
  EXPECT_EQ(o.sphere_part, "probe_ruby");
  EXPECT_EQ(o.part, "workpiece");
  // On the shaft's surface (world and spindle frames share the axis on lathe-c1 at C 0).
  const MachineModel& m = Lathe();
  const Eigen::Isometry3d X_WS = LinkPoses(m, rig.backend->JointPositions())[m.LinkIndex("spindle")];
  const Eigen::Vector3d p = X_WS.inverse() * o.point_m;
  EXPECT_NEAR(std::hypot(p.x(), p.y()), 30 * kMm, 1e-9);
  // Within the tick X passed r 29 (a tick either side for the encoder's quantisation).
  EXPECT_GE(o.t_s, t_start - kDriveTickS);
  EXPECT_LE(o.t_s, t_end + kDriveTickS);
  EXPECT_TRUE(rig.backend->TakeStylusOverTravels().empty());  // taken once
  rig.FeedX(1200, 28.6);
  EXPECT_TRUE(rig.backend->TakeStylusOverTravels().empty());  // damaged once per run
}

TEST_P(StylusContactsBackendTest, WithoutAWorkpieceNothingTouches) {
  std::unique_ptr<MachineBackend> backend =
      MakeBackend(GetParam(), Lathe(), {{{"X", kStartXMm}, {"Z", kZMm}, {"T", kStation3}}, {}});
  Bench bench(*backend);
  bench.Output("QPROBE_ON", true);
  bench.Run(0.6);
  bench.Command("X", DriveMode::kPosition, 28.5);
  bench.Run(0.5);
  EXPECT_FALSE(bench.Input("IPROBE_CONTACT"));
  EXPECT_TRUE(backend->TakeStylusOverTravels().empty());
}

INSTANTIATE_TEST_SUITE_P(Backends, StylusContactsBackendTest,
                         ::testing::Values(BackendKind::kKinematic, BackendKind::kPhysics),
                         [](const auto& info) { return std::string(ToString(info.param)); });

}  // namespace
}  // namespace vmt::sim
