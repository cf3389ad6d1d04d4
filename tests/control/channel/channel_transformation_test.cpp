// G31 face transformation in the channel (coordinate_transformation.hpp; REPOS manual 5.2,
// 6.1, 8.3): X1/Y1 moves interpolated on a straight line or (G02/G03) an arc of the face plane
// and transformed to X and C every cycle within C's rate limit; rotary axis mode required; a
// line or arc through the centre refused; PathGuard's chords within 1 um of the line;
// repositioning with G77 X1=0 Y1=0 back along a Cartesian line, the fictive axes on the REPOS
// screen and X's window for them; the handwheel of X1/Y1.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "control/channel/channel.hpp"
#include "control/nc/coordinate_transformation.hpp"
#include "headstock_lathe.hpp"
#include "tests/control/channel/block_search_steps.hpp"

namespace vmt::control::channel {
namespace {

using axes::HeadstockMode;
using headstock_test::kTick;
using headstock_test::Lathe;
using ::testing::HasSubstr;

constexpr size_t kX = 0, kZ = 1, kC = 2;
constexpr int kDriveX = 0, kDriveC = 2;  // section 2: C is the spindle's own drive

void RunFor(Lathe& m, double s) { m.Ticks(static_cast<int>(s / kTick)); }

nc::FictivePoint FaceOf(const Lathe& m) {
  return nc::MachineToFace(m.at.feedback[kDriveX].position, m.at.feedback[kDriveC].position);
}

// Distance of p from the segment a-b.
double OffSegment(nc::FictivePoint p, nc::FictivePoint a, nc::FictivePoint b) {
  const double dx = b.x1 - a.x1, dy = b.y1 - a.y1, l2 = dx * dx + dy * dy;
  const double u =
      l2 > 0 ? std::clamp(((p.x1 - a.x1) * dx + (p.y1 - a.y1) * dy) / l2, 0.0, 1.0) : 0;
  return std::hypot(p.x1 - a.x1 - u * dx, p.y1 - a.y1 - u * dy);
}

TEST(ChannelTransformation, FaceLinesAreStraightInTheFacePlane) {
  Lathe m("N1 G00 X20 Z5 C0\nN2 G31 G01 X1=20 Y1=20 F600\nN3 X1=-20\nN4 G30\nN5 RET\n");
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->line() == 2; }));
  double worst = 0, max_c_speed = 0;
  int samples = 0;
  while (m.channel->state() == ChannelState::kRunning && m.t < 20) {
    m.Tick();
    const nc::FictivePoint p = FaceOf(m);
    worst = std::max(
        worst, std::min(OffSegment(p, {20, 0}, {20, 20}), OffSegment(p, {20, 20}, {-20, 20})));
    max_c_speed = std::max(max_c_speed, std::abs(m.at.feedback[kDriveC].velocity));
    ++samples;
  }
  m.Ticks(8);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_GT(samples, 4000);
  // The NC cycle's points lie on the lines; the drive ticks between them are linear in X and
  // C (fine interpolation): 10 um chords err by ~1e-6 mm.
  EXPECT_LT(worst, 1e-5);
  EXPECT_NEAR(m.at.feedback[kDriveX].position, std::hypot(20, 20), 1e-9);
  EXPECT_NEAR(m.at.feedback[kDriveC].position, 135, 1e-9);
  EXPECT_LE(max_c_speed, 3600);
  // The path feed is F in the face plane: 40 mm at 10 mm/s in about 4 s.
}

TEST(ChannelTransformation, PathFeedNearTheCentreKeepsCWithinItsRapidRate) {
  // d = 0.5 mm: at F 6000 (100 mm/s) C would turn 11459 deg/s past the centre; its limit is 3600.
  Lathe m("N1 G00 X20 Z5 C1.4321\nN2 G31 G01 X1=-20 Y1=0.5 F6000\nN3 RET\n");
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->line() == 2; }));
  double max_c_speed = 0, worst = 0;
  const nc::FictivePoint a = nc::MachineToFace(20, 1.4321), b{-20, 0.5};
  while (m.channel->state() == ChannelState::kRunning && m.t < 20) {
    m.Tick();
    // The drives' velocity over one tick: the fine interpolation's.
    max_c_speed = std::max(max_c_speed, std::abs(m.at.feedback[kDriveC].velocity));
    worst = std::max(worst, OffSegment(FaceOf(m), a, b));
  }
  m.Ticks(8);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  // Limited by C's acceleration here (v^2 th'' <= 36000 deg/s^2 / 2: ~11 mm/s at d 0.5 mm, C at
  // ~1260 deg/s past the centre), within its rate in any case.
  EXPECT_LE(max_c_speed, 3600 * 1.001);
  EXPECT_GT(max_c_speed, 1000);  // limited, not crawling
  EXPECT_LT(worst, 1e-3);        // chords of the fine interpolation where C turns fast
  EXPECT_NEAR(m.at.feedback[kDriveC].position, 180 - std::atan2(0.5, 20) * 180 / std::numbers::pi,
              1e-6);
}

TEST(ChannelTransformation, LineThroughTheCentreIsRefused) {
  Lathe m("N1 G00 X20 Z5 C0\nN2 G31 G01 X1=-20 Y1=0 F600\nN3 RET\n");
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgTransformation);
  EXPECT_THAT(m.channel->error(), HasSubstr("p.mtc:2:"));
  EXPECT_THAT(m.channel->error(), HasSubstr("passes the centre"));
}

TEST(ChannelTransformation, SpindleModeIsAnError) {
  Lathe m("N1 G00 X20 Z5\nN2 M3 S100\nN3 G31 G01 X1=10 Y1=10 F600\nN4 RET\n");
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
  EXPECT_EQ(m.channel->error_number(), kMsgTransformation);
  EXPECT_THAT(m.channel->error(), HasSubstr("p.mtc:3:"));
  EXPECT_THAT(m.channel->error(), HasSubstr("rotary axis mode"));
}

// ---- G02/G03 in the face ----

double OffCircle(nc::FictivePoint p, nc::FictivePoint centre, double radius) {
  return std::abs(std::hypot(p.x1 - centre.x1, p.y1 - centre.y1) - radius);
}

TEST(ChannelTransformation, FaceArcsRunOnTheirCircles) {
  // Half a circle about the centre (C 0 -> 180), a full circle about it (C 180 -> 540), then a
  // small clockwise arc beside it (C back to 540), R30 clockwise (as the interpreter's test).
  Lathe m(
      "N1 G00 X20 Z5 C0\nN2 G31 G03 X1=-20 Y1=0 I-20 J0 F3000\nN3 X1=-20 Y1=0 I20\n"
      "N4 G02 X1=-10 Y1=0 I5\nN5 G30 RET\n");
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->line() == 2; }));
  double worst[3] = {0, 0, 0}, max_c_speed = 0;
  int samples[3] = {0, 0, 0};
  while (m.channel->state() == ChannelState::kRunning && m.t < 30) {
    m.Tick();
    const int line = m.channel->line();
    if (line < 2 || line > 4) continue;
    const nc::FictivePoint p = FaceOf(m);
    // A block's first tick may still finish the one before it: the nearer circle counts.
    const double off = std::min(OffCircle(p, {0, 0}, 20), OffCircle(p, {-15, 0}, 5));
    worst[line - 2] = std::max(worst[line - 2], off);
    ++samples[line - 2];
    max_c_speed = std::max(max_c_speed, std::abs(m.at.feedback[kDriveC].velocity));
    if (line == 3) {
      // Never unwound back (the block's first ticks may still finish the half circle).
      EXPECT_GT(m.at.feedback[kDriveC].position, 179);
    }
  }
  m.Ticks(8);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  for (int k = 0; k < 3; ++k) EXPECT_GT(samples[k], 200) << k;
  // NC cycle points on the circle; drive ticks linear in X and C between them: at 50 mm/s a
  // 1 ms cycle is a 50 um chord, which sags L^2 / 8R from a circle of radius R (1.6e-5 mm at R
  // 20, 6.3e-5 mm at R 5) plus what X and C's curvature adds.
  EXPECT_LT(worst[0], 5e-5);
  EXPECT_LT(worst[1], 5e-5);
  EXPECT_LT(worst[2], 2e-4);
  EXPECT_LE(max_c_speed, 3600 * 1.001);
  EXPECT_NEAR(m.at.feedback[kDriveX].position, 10, 1e-9);
  EXPECT_NEAR(m.at.feedback[kDriveC].position, 540, 1e-9);
}

TEST(ChannelTransformation, FaceArcNearTheCentreKeepsCWithinItsRates) {
  // A circle of radius 5.2 about X1 5 Y1 0: round the centre, passing it 0.2 mm away; at F 6000
  // C would turn 100 / 0.2 rad/s there: the path feed is limited by C's rate and acceleration.
  Lathe m("N1 G00 X10.2 Z5 C0\nN2 G31 G03 X1=10.2 Y1=0 I-5.2 F6000\nN3 G30 RET\n");
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->line() == 2; }));
  double max_c_speed = 0, worst = 0;
  while (m.channel->state() == ChannelState::kRunning && m.t < 30) {
    m.Tick();
    max_c_speed = std::max(max_c_speed, std::abs(m.at.feedback[kDriveC].velocity));
    if (m.channel->line() == 2) worst = std::max(worst, OffCircle(FaceOf(m), {5, 0}, 5.2));
  }
  m.Ticks(8);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_LE(max_c_speed, 3600 * 1.001);
  EXPECT_GT(max_c_speed, 500);  // limited, not crawling
  EXPECT_LT(worst, 1e-3);
  EXPECT_NEAR(m.at.feedback[kDriveC].position, 360, 1e-9);  // the circle goes round the centre
}

TEST(ChannelTransformation, FaceArcThroughTheCentreIsRefused) {
  // Centre X1 10 Y1 0, radius 10: three quarters counter-clockwise pass X1 0 Y1 0.
  Lathe m("N1 G00 X20 Z5 C0\nN2 G31 G03 X1=10 Y1=-10 I-10 F600\nN3 RET\n");
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgTransformation);
  EXPECT_THAT(m.channel->error(), HasSubstr("p.mtc:2:"));
  EXPECT_THAT(m.channel->error(), HasSubstr("the arc"));
  EXPECT_THAT(m.channel->error(), HasSubstr("passes the centre"));
  EXPECT_NEAR(m.at.feedback[kDriveX].position, 20, 1e-9);  // nothing moved
  // The quarter that stops short of the centre runs.
  Lathe ok("N1 G00 X20 Z5 C0\nN2 G31 G03 X1=10 Y1=10 I-10 F600\nN3 G30 RET\n");
  ok.channel->Start();
  ok.RunUntilEnd();
  EXPECT_EQ(ok.channel->state(), ChannelState::kEnded) << ok.channel->error();
  EXPECT_NEAR(ok.at.feedback[kDriveC].position, 45, 1e-9);
}

TEST(ChannelTransformation, BlockSearchIntoAFaceArcFindsCUnwound) {
  // A full circle about the centre (C 0 -> 360), then half of one (C 360 -> 540): searching N3
  // at 500 per mille stands at X1 0 Y1 20 with C at 450, as the run has it.
  using Rig = testing::BlockSearchSteps<Lathe>;
  const std::string program =
      "N1 G00 X20 Z5 C0\nN2 G31 G03 X1=20 Y1=0 I-20 F3000\nN3 X1=-20 Y1=0 I-20\n"
      "N4 G30 G01 Z0 F600\nN5 RET\n";
  Rig m(program);
  m.Search(testing::BlockNumberSearch(3, 500));
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
  const auto& st = m.channel->block_search();
  ASSERT_EQ(st.continue_position.size(), 3u);
  EXPECT_NEAR(st.continue_position[kX], 20, 1e-9);
  EXPECT_NEAR(st.continue_position[kC], 450, 1e-9);
  m.channel->Start();
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForContinueContour)) << m.channel->error();
  m.Ticks(8);
  EXPECT_NEAR(m.at.feedback[kDriveC].position, 450, 1e-9);
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.at.feedback[kDriveX].position, 20, 1e-9);
  EXPECT_NEAR(m.at.feedback[kDriveC].position, 540, 1e-9);
}

TEST(ChannelTransformation, BlockSearchUnderG31ReturnsOnALineOfTheFace) {
  // N3 at 500 per mille continues at X1 0 Y1 20 (X 20, C 90). The axes stand at X 50 C 0
  // (X1 50 Y1 0): the automatic return runs on the face's line between the two points, as
  // G77 X1=0 Y1=0 does, not on the spiral a move straight in X and C sweeps (13 mm off the line
  // half-way).
  using Rig = testing::BlockSearchSteps<Lathe>;
  Rig m("N1 G00 X20 Z5 C0\nN2 G31 G01 X1=20 Y1=20 F600\nN3 X1=-20\nN4 G30 G01 Z0\nN5 RET\n");
  m.at.feedback[kDriveX].position = 50;
  m.Search(testing::BlockNumberSearch(3, 500));
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
  const nc::FictivePoint from = FaceOf(m);
  ASSERT_NEAR(from.x1, 50, 1e-9);
  ASSERT_NEAR(from.y1, 0, 1e-9);
  m.channel->Start();
  double worst = 0;
  int samples = 0;
  ASSERT_TRUE(m.RunUntil([&] {
    worst = std::max(worst, OffSegment(FaceOf(m), from, {0, 20}));
    ++samples;
    return m.State() == BlockSearchState::kWaitForContinueContour ||
           m.channel->state() == ChannelState::kError;
  })) << m.channel->error();
  ASSERT_EQ(m.State(), BlockSearchState::kWaitForContinueContour) << m.channel->error();
  EXPECT_GT(samples, 100);
  // On the line at every NC cycle; the drive ticks between are straight in X and C, which at
  // the return's rapid rate (not the 10 mm/s of the lines above) errs by ~0.25 um.
  EXPECT_LT(worst, 1e-3);
  m.Ticks(8);
  EXPECT_NEAR(m.at.feedback[kDriveX].position, 20, 1e-9);
  EXPECT_NEAR(m.at.feedback[kDriveC].position, 90, 1e-9);
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
}

// ---- Repositioning under G31 ----

// Records every chord PathGuard is asked about; all clear.
struct Recorder : PathGuard {
  PathCheck CheckMove(const std::vector<double>& from, const std::vector<double>& to) override {
    chords.push_back({from, to});
    PathCheck c;
    c.min_clearance = 5;
    return c;
  }
  std::vector<std::pair<std::vector<double>, std::vector<double>>> chords;
};

const std::string kFace =
    "N1 G00 X20 Z5 C0\n"
    "N2 G31 G01 X1=20 Y1=30 F600\n"
    "N3 X1=-20\n"
    "N4 G30 RET\n"
    ".REPOS\n"
    "N10 @100=G(17)-31 BEQ .TRANSF\n"
    "N11 G77 X0 C0 F3000 RTS\n"
    ".TRANSF\n"
    "N12 G77 X1=0 Y1=0 F3000\n"
    "N13 G77 Z0 F2000 RTS\n";

void Windows(ChannelConfig& c) {
  c.axes[kX].repos_window = 0.5;  // Cxx.086 of X [mm]: the fictive axes' (6.1)
  c.axes[kZ].repos_window = 0.5;
  c.axes[kC].repos_window = 1.5;  // [deg]: not used under G31
}

void Interrupt(Lathe& m, double s) {
  m.channel->Start();
  RunFor(m, s);
  m.channel->Stop();
  RunFor(m, 0.2);
  ASSERT_EQ(m.channel->state(), ChannelState::kHold);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
}

void Press(Lathe& m, size_t axis, int direction, int times) {
  for (int k = 0; k < times; ++k) {
    m.channel->Jog(axis, direction);
    RunFor(m, 0.05);
    m.channel->Jog(axis, 0);
    RunFor(m, 0.05);
  }
}

const ReposAxisStatus& Axis(const ReposStatus& s, const std::string& name) {
  for (const ReposAxisStatus& a : s.axes)
    if (a.name == name) return a;
  ADD_FAILURE() << "no axis " << name;
  return s.axes.at(0);
}

TEST(ChannelTransformation, TheXWindowCountsForTheFictivePoint) {
  Lathe m(kFace, false, Windows);
  Interrupt(m, 5.0);  // in N3, Y1 30
  const nc::FictivePoint stop = FaceOf(m);
  ASSERT_NEAR(stop.y1, 30, 1e-6);
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));  // 1 deg a press
  Press(m, kC, +1, 1);
  m.channel->SetReposition(true, false);
  RunFor(m, 0.01);
  ReposStatus s = m.channel->repos_status();
  // C is 1 deg off, within its own 1.5 deg; at radius ~31 that is ~0.55 mm > X's 0.5 mm.
  EXPECT_FALSE(m.channel->conditions_restored());
  EXPECT_TRUE(Axis(s, "C").adjust);
  EXPECT_TRUE(Axis(s, "X1").adjust);
  EXPECT_NEAR(Axis(s, "X1").final_value, stop.x1, 1e-6);
  EXPECT_NEAR(Axis(s, "Y1").final_value, 30, 1e-6);
  const nc::FictivePoint now = FaceOf(m);
  EXPECT_NEAR(Axis(s, "Y1").command_value, now.y1, 1e-6);
  EXPECT_NEAR(Axis(s, "X1").distance_to_go, stop.x1 - now.x1, 1e-6);
  // Half a degree back is ~0.27 mm: within X's window.
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement100));  // 0.1 deg a press
  Press(m, kC, -1, 5);
  s = m.channel->repos_status();
  EXPECT_FALSE(Axis(s, "Y1").adjust);
  EXPECT_FALSE(Axis(s, "C").adjust);
  EXPECT_TRUE(m.channel->conditions_restored());
}

TEST(ChannelTransformation, G77X1Y1ReturnsOnACartesianLineCheckedInChords) {
  Lathe m(kFace, false, Windows);
  Recorder guard;
  m.channel->SetPathGuard(&guard);
  Interrupt(m, 5.0);
  const nc::FictivePoint stop = FaceOf(m);
  const double z_stop = m.at.feedback[1].position;
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));
  Press(m, kZ, +1, 5);
  Press(m, kC, +1, 20);
  Press(m, kX, +1, 8);
  const nc::FictivePoint away = FaceOf(m);
  ASSERT_GT(std::hypot(away.x1 - stop.x1, away.y1 - stop.y1), 10);
  m.channel->SetReposition(true, false);
  RunFor(m, 0.01);
  guard.chords.clear();
  (void)m.channel->TakeGuardRecords();  // the jogs'
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  // N12 G77 X1=0 Y1=0: X and C on the straight line back; Z waits for N13.
  double worst = 0;
  while (m.channel->repos_status().subroutine_running && m.t < 30) {
    m.Tick();
    if (std::abs(m.at.feedback[1].position - (z_stop + 5)) < 1e-9)
      worst = std::max(worst, OffSegment(FaceOf(m), away, stop));
  }
  // Cycle points on the line; drive ticks linear in X and C between them (50 mm/s: 50 um
  // chords err by some 1e-5 mm).
  EXPECT_LT(worst, 5e-5);
  // PathGuard: the G77 curve as chords, each within 1 um of the line (brute force), from the
  // jogged point to the interruption point.
  ASSERT_GT(guard.chords.size(), 10u);
  double chord_worst = 0;
  size_t face_chords = 0;
  for (const auto& [from, to] : guard.chords) {
    if (from[kDriveX] == to[kDriveX] && from[kDriveC] == to[kDriveC]) continue;  // Z
    ++face_chords;
    for (int j = 0; j <= 32; ++j) {
      const double t = j / 32.0;
      const nc::FictivePoint q =
          nc::MachineToFace(from[kDriveX] + (to[kDriveX] - from[kDriveX]) * t,
                            from[kDriveC] + (to[kDriveC] - from[kDriveC]) * t);
      chord_worst = std::max(chord_worst, OffSegment(q, away, stop));
    }
  }
  EXPECT_GT(face_chords, 10u);
  EXPECT_LT(chord_worst, 1e-3);
  const std::vector<GuardRecord> records = m.channel->TakeGuardRecords();
  ASSERT_FALSE(records.empty());
  EXPECT_EQ(records.front().move, "G77");
  EXPECT_EQ(records.front().checks, static_cast<int>(face_chords));
  // The program goes on from the interruption point to its end.
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  const nc::FictivePoint end = FaceOf(m);
  EXPECT_NEAR(end.x1, -20, 1e-6);
  EXPECT_NEAR(end.y1, 30, 1e-6);
}

// ---- The handwheel of X1/Y1 ----

TEST(ChannelTransformation, HandwheelCountsOfY1AndX1MoveOnLinesOfTheFace) {
  Lathe m(kFace, false, Windows);
  Recorder guard;
  m.channel->SetPathGuard(&guard);
  Interrupt(m, 5.0);  // in N3, Y1 30
  const nc::FictivePoint stop = FaceOf(m);
  const double z = m.at.feedback[1].position;
  m.channel->SetJogMode(static_cast<int>(JogMode::kHandwheel));
  (void)m.channel->TakeGuardRecords();
  // 500 counts of 0.01 mm: Y1 5 mm down, X1 stays; X and C follow transformed (the real axes'
  // handwheel does not pull them back).
  ASSERT_TRUE(m.channel->HandwheelFictive(1, -500));
  const nc::FictivePoint y_end{stop.x1, 25};
  double worst = 0, fastest = 0;
  nc::FictivePoint last = FaceOf(m);
  for (int i = 0; i < static_cast<int>(1.0 / kTick); ++i) {
    m.Tick();
    const nc::FictivePoint p = FaceOf(m);
    worst = std::max(worst, OffSegment(p, stop, y_end));
    fastest = std::max(fastest, std::hypot(p.x1 - last.x1, p.y1 - last.y1) / kTick);
    last = p;
  }
  EXPECT_NEAR(FaceOf(m).x1, stop.x1, 1e-6);
  EXPECT_NEAR(FaceOf(m).y1, 25, 1e-6);
  EXPECT_NEAR(m.at.feedback[1].position, z, 1e-12);
  // Cycle points on the line, the drive ticks linear in X and C between them.
  EXPECT_LT(worst, 5e-5);
  // At most X's jogging rapid (rapid / 2 = 200 mm/s here) along the fictive axis, as the real
  // axes' handwheel; C's jogging rapid (1800 deg/s) allows ~800 mm/s at radius 25. The 5 mm,
  // accelerated and braked at 4000 mm/s², peak at sqrt(4000 * 5) ~ 141 mm/s.
  EXPECT_LE(fastest, std::sqrt(4000 * 5.0) * 1.05);
  EXPECT_GT(fastest, 120);
  // PathGuard checked the way to the handwheel's target ahead, in chords of the line.
  bool checked = false;
  for (const GuardRecord& r : m.channel->TakeGuardRecords())
    checked = checked || r.move == "handwheel X1/Y1";
  EXPECT_TRUE(checked);
  ASSERT_FALSE(guard.chords.empty());
  for (const auto& [from, to] : guard.chords)
    EXPECT_LE(to[kDriveX], std::hypot(stop.x1, 30) + 1e-9);  // never past Y1 30 .. 25
  // Then X1: 300 counts along Y1 = 25.
  ASSERT_TRUE(m.channel->HandwheelFictive(0, 300));
  worst = 0, fastest = 0;
  last = FaceOf(m);
  for (int i = 0; i < static_cast<int>(1.0 / kTick); ++i) {
    m.Tick();
    const nc::FictivePoint p = FaceOf(m);
    worst = std::max(worst, OffSegment(p, y_end, {stop.x1 + 3, 25}));
    fastest = std::max(fastest, std::hypot(p.x1 - last.x1, p.y1 - last.y1) / kTick);
    last = p;
  }
  // Cycle points on the line; the drive ticks between them, linear in X and C, turn about the
  // centre and err by the sagitta h²/8r of the cycle's chord h (some 6e-5 mm at the ~110 mm/s
  // the 3 mm reach, radius >= 25).
  const double h = fastest * 4 * kTick;
  EXPECT_LT(worst, h * h / (8 * 25) + 1e-6);
  EXPECT_NEAR(FaceOf(m).x1, stop.x1 + 3, 1e-6);
  EXPECT_NEAR(FaceOf(m).y1, 25, 1e-6);
  // Counts of a real axis afterwards move it alone: X and C stay where X1/Y1 took them.
  const double c = m.at.feedback[kDriveC].position;
  m.channel->Handwheel(kZ, 100);
  RunFor(m, 0.5);
  EXPECT_NEAR(m.at.feedback[1].position, z + 1, 1e-9);
  EXPECT_NEAR(FaceOf(m).x1, stop.x1 + 3, 1e-6);
  EXPECT_NEAR(m.at.feedback[kDriveC].position, c, 1e-9);
  // Outside handwheel mode the counts of X1/Y1 are refused.
  m.channel->SetJogMode(static_cast<int>(JogMode::kContinuous));
  EXPECT_FALSE(m.channel->HandwheelFictive(0, 100));
}

TEST(ChannelTransformation, HandwheelOfX1StaysWithinTheReposZone) {
  Lathe m(kFace, false, Windows);
  Interrupt(m, 5.0);
  const nc::FictivePoint stop = FaceOf(m);
  m.channel->SetJogMode(static_cast<int>(JogMode::kHandwheel));
  // Away in Y1 first (no REPOS function called: no zone), then repositioning called: Y1 may go
  // back to 30 but not past it (3.2), X1 not away from its target at all.
  ASSERT_TRUE(m.channel->HandwheelFictive(1, -400));
  RunFor(m, 1.0);
  ASSERT_NEAR(FaceOf(m).y1, 26, 1e-6);
  m.channel->SetReposition(true, false);
  RunFor(m, 0.01);
  ASSERT_TRUE(m.channel->HandwheelFictive(1, 1000));
  ASSERT_TRUE(m.channel->HandwheelFictive(0, 500));
  RunFor(m, 1.5);
  EXPECT_NEAR(FaceOf(m).y1, 30, 1e-6);
  EXPECT_NEAR(FaceOf(m).x1, stop.x1, 1e-6);
}

TEST(ChannelTransformation, HandwheelOfX1StopsShortOfTheCentre) {
  // G31 stays active after the program's end (no G30): manual mode jogs in the face.
  Lathe m("N1 G00 X20 Z5 C0\nN2 G31 G01 X1=0.5 Y1=0.05 F3000\nN3 RET\n");
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->SetJogMode(static_cast<int>(JogMode::kHandwheel));
  // X1 to -0.5 would pass the centre 0.05 mm away: the point stops 0.1 mm short of it.
  ASSERT_TRUE(m.channel->HandwheelFictive(0, -100));
  RunFor(m, 1.0);
  const nc::FictivePoint p = FaceOf(m);
  EXPECT_GT(p.x1, 0);
  EXPECT_NEAR(p.y1, 0.05, 1e-6);
  EXPECT_GE(std::hypot(p.x1, p.y1), 0.1 - 1e-9);
  EXPECT_LT(std::hypot(p.x1, p.y1), 0.11);
  // The target is dropped there: new counts start from where the point stands.
  ASSERT_TRUE(m.channel->HandwheelFictive(0, 10));
  RunFor(m, 0.5);
  EXPECT_NEAR(FaceOf(m).x1, p.x1 + 0.1, 1e-6);
}

// ---- Jog modes changed while X1/Y1 move (as for the feed axes, channel_jog_test.cpp) ----

// G31 left active at the program's end, manual mode: the point at X1 20, Y1 30.
void FaceInManual(Lathe& m) {
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  ASSERT_NEAR(FaceOf(m).x1, 20, 1e-6);
  ASSERT_NEAR(FaceOf(m).y1, 30, 1e-6);
}
const char kFaceAtRest[] = "N1 G00 X20 Z5 C0\nN2 G31 G01 X1=20 Y1=30 F3000\nN3 RET\n";

// X1 jogged continuously for 1 s at X's jogging speed (40 mm/s) and let go: where it stood.
nc::FictivePoint JogX1AndLetGo(Lathe& m) {
  EXPECT_TRUE(m.channel->JogFictive(0, +1));
  RunFor(m, 1.0);
  EXPECT_TRUE(m.channel->JogFictive(0, 0));
  return FaceOf(m);
}

// Holding still for `s`: X and C exactly where they were.
void ExpectStill(Lathe& m, double s) {
  const double x = m.at.feedback[kDriveX].position, c = m.at.feedback[kDriveC].position;
  RunFor(m, s);
  EXPECT_EQ(m.at.feedback[kDriveX].position, x);
  EXPECT_EQ(m.at.feedback[kDriveC].position, c);
}

// Increments selected right after X1's key was let go: the point brakes to a stop as it would
// have (no standstill within a cycle), and nothing of its speed is left over to move it when
// continuous jogging is selected again.
TEST(ChannelTransformation, IncrementsSelectedWhileX1BrakesLetItBrakeToAStop) {
  Lathe m(kFaceAtRest);
  FaceInManual(m);
  const nc::FictivePoint released = JogX1AndLetGo(m);
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));
  RunFor(m, 0.1);
  EXPECT_NEAR(FaceOf(m).x1, released.x1 + 40 * 40 / (2 * 4000.0), 0.05);  // its braking distance
  EXPECT_NEAR(FaceOf(m).y1, 30, 1e-6);
  m.channel->SetJogMode(static_cast<int>(JogMode::kContinuous));
  ExpectStill(m, 0.1);
  // The increments work from there on: one press, one millimetre.
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));
  const nc::FictivePoint before = FaceOf(m);
  ASSERT_TRUE(m.channel->JogFictive(0, +1));
  RunFor(m, 0.1);
  EXPECT_NEAR(FaceOf(m).x1, before.x1 + 1, 1e-6);
}

// The handwheel selected while X1 brakes: the same braking, and the counts count from where
// the point stopped.
TEST(ChannelTransformation, HandwheelSelectedWhileX1BrakesLetsItBrakeToAStop) {
  Lathe m(kFaceAtRest);
  FaceInManual(m);
  const nc::FictivePoint released = JogX1AndLetGo(m);
  m.channel->SetJogMode(static_cast<int>(JogMode::kHandwheel));
  RunFor(m, 0.1);
  const nc::FictivePoint stopped = FaceOf(m);
  EXPECT_NEAR(stopped.x1, released.x1 + 40 * 40 / (2 * 4000.0), 0.05);
  EXPECT_NEAR(stopped.y1, 30, 1e-6);
  ASSERT_TRUE(m.channel->HandwheelFictive(0, 100));
  RunFor(m, 0.2);
  EXPECT_NEAR(FaceOf(m).x1, stopped.x1 + 1, 1e-6);
  m.channel->SetJogMode(static_cast<int>(JogMode::kContinuous));
  ExpectStill(m, 0.1);
}

// An increment of X1 runs to its end when the handwheel is selected meanwhile, as it does when
// continuous jogging is (it neither stands still nor goes on later).
TEST(ChannelTransformation, AnIncrementOfX1RunsToItsEndWhenTheHandwheelIsSelected) {
  Lathe m(kFaceAtRest);
  FaceInManual(m);
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));
  ASSERT_TRUE(m.channel->JogFictive(0, +1));
  RunFor(m, 0.005);  // under way (1 mm takes some 35 ms)
  ASSERT_GT(FaceOf(m).x1, 20 + 1e-3);
  ASSERT_LT(FaceOf(m).x1, 21 - 1e-3);
  m.channel->SetJogMode(static_cast<int>(JogMode::kHandwheel));
  RunFor(m, 0.1);
  EXPECT_NEAR(FaceOf(m).x1, 21, 1e-6);
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));
  ExpectStill(m, 0.1);
}

// Automatic mode selected while X1 brakes or an increment runs: the point brakes to a stop as
// it would have (the increment runs to its end), and back in manual mode nothing of the jog is
// left over to move it on its own.
TEST(ChannelTransformation, AJogOfX1LeftForAutomaticModeDoesNotGoOnLater) {
  Lathe m(kFaceAtRest);
  FaceInManual(m);
  const nc::FictivePoint let_go = JogX1AndLetGo(m);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  RunFor(m, 0.001);
  EXPECT_GT(FaceOf(m).x1, let_go.x1 + 0.02);  // still braking: 40 mm/s at 4000 mm/s^2
  RunFor(m, 0.02);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  EXPECT_NEAR(FaceOf(m).x1, let_go.x1 + 0.2, 0.02);  // its braking distance
  ExpectStill(m, 0.1);
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));
  const nc::FictivePoint from = FaceOf(m);
  ASSERT_TRUE(m.channel->JogFictive(0, +1));
  RunFor(m, 0.005);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  RunFor(m, 0.01);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  RunFor(m, 0.1);
  EXPECT_NEAR(FaceOf(m).x1, from.x1 + 1, 1e-6);
  EXPECT_NEAR(FaceOf(m).y1, from.y1, 1e-6);
  ExpectStill(m, 0.1);
}

// The handwheel of X1/Y1 runs at X's jogging rapid, as the real axes' handwheel does, C at
// most at its own jogging rapid (near the centre the point slows for it).
TEST(ChannelTransformation, HandwheelOfX1RunsAtTheJoggingRapid) {
  Lathe m(kFaceAtRest);
  FaceInManual(m);
  m.channel->SetJogMode(static_cast<int>(JogMode::kHandwheel));
  ASSERT_TRUE(m.channel->HandwheelFictive(0, 3000));  // 30 mm
  double fastest = 0;
  nc::FictivePoint last = FaceOf(m);
  for (int i = 0; i < static_cast<int>(0.5 / kTick); ++i) {
    m.Tick();
    const nc::FictivePoint p = FaceOf(m);
    fastest = std::max(fastest, std::hypot(p.x1 - last.x1, p.y1 - last.y1) / kTick);
    last = p;
  }
  EXPECT_NEAR(FaceOf(m).x1, 50, 1e-6);
  EXPECT_NEAR(FaceOf(m).y1, 30, 1e-6);
  // X's jogging rapid: half its rapid, 200 mm/s (its jogging speed would be 40).
  EXPECT_LE(fastest, 200 * 1.01);
  EXPECT_GT(fastest, 190);
  // The override scales it as it does the real axes' handwheel.
  m.channel->SetFeedOverride(0.5);
  ASSERT_TRUE(m.channel->HandwheelFictive(0, -3000));
  fastest = 0;
  last = FaceOf(m);
  for (int i = 0; i < static_cast<int>(0.5 / kTick); ++i) {
    m.Tick();
    const nc::FictivePoint p = FaceOf(m);
    fastest = std::max(fastest, std::hypot(p.x1 - last.x1, p.y1 - last.y1) / kTick);
    last = p;
  }
  EXPECT_NEAR(FaceOf(m).x1, 20, 1e-6);
  EXPECT_LE(fastest, 100 * 1.01);
  EXPECT_GT(fastest, 95);
}

TEST(ChannelTransformation, HandwheelOfX1NearTheCentreKeepsCWithinItsJoggingRapid) {
  Lathe m("N1 G00 X20 Z5 C0\nN2 G31 G01 X1=5 Y1=1 F3000\nN3 RET\n");
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->SetJogMode(static_cast<int>(JogMode::kHandwheel));
  ASSERT_TRUE(m.channel->HandwheelFictive(0, -1000));  // X1 5 -> -5, 1 mm from the centre
  double c_fastest = 0;
  double c_last = m.at.feedback[kDriveC].position;
  for (int i = 0; i < static_cast<int>(1.0 / kTick); ++i) {
    m.Tick();
    const double c = m.at.feedback[kDriveC].position;
    c_fastest = std::max(c_fastest, std::abs(c - c_last) / kTick);
    c_last = c;
  }
  EXPECT_NEAR(FaceOf(m).x1, -5, 1e-6);
  EXPECT_NEAR(FaceOf(m).y1, 1, 1e-6);
  // C's jogging rapid: half its rapid, 1800 deg/s (X's jogging rapid would ask ~11000 here).
  EXPECT_LE(c_fastest, 1800 * 1.02);
  EXPECT_GT(c_fastest, 1000);
}

}  // namespace
}  // namespace vmt::control::channel
