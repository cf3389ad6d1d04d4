// Backward travel (twincat-cnc-block-search-de.md 4.3): while held, the channel travels the
// path of its last blocks in reverse, and forward again to the interruption point, from where the
// program goes on; after block search along the blocks the search decoded. On the ideal X/Z
// machine of the channel tests.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "block_search_steps.hpp"
#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using ::testing::HasSubstr;
using Lathe = testing::BlockSearchSteps<testing::Machine>;

/// A turning pass: approach at rapid, face down, turn along Z, an arc up, out. Program X/Z.
constexpr const char* kPass =
    "N10 G00 X50 Z10\n"
    "N20 G01 X40 Z0 F600\n"
    "N30 Z-30\n"
    "N40 G02 X50 Z-40 I10 K0\n"
    "N50 G01 X60\n"
    "N60 M30\n";

/// The pass as points of its path (X, Z), the quarter arc around X50 Z-30 as 200 chords
/// (within 10 (1 - cos(pi / 800)) < 1e-4 mm of it): for "on the path" checks.
std::vector<std::pair<double, double>> PassPolyline() {
  std::vector<std::pair<double, double>> p = {{0, 0}, {50, 10}, {40, 0}, {40, -30}};
  for (int i = 1; i <= 200; ++i) {
    const double a = std::numbers::pi / 2 * i / 200;
    p.push_back({50 - 10 * std::cos(a), -30 - 10 * std::sin(a)});
  }
  p.push_back({60, -40});
  return p;
}

double DistanceToPolyline(double x, double z, const std::vector<std::pair<double, double>>& p) {
  double best = 1e9;
  for (size_t i = 1; i < p.size(); ++i) {
    const double ax = p[i - 1].first, az = p[i - 1].second;
    const double dx = p[i].first - ax, dz = p[i].second - az;
    const double l2 = dx * dx + dz * dz;
    const double u = l2 > 0 ? std::clamp(((x - ax) * dx + (z - az) * dz) / l2, 0.0, 1.0) : 0;
    best = std::min(best, std::hypot(x - ax - u * dx, z - az - u * dz));
  }
  return best;
}

/// Runs until the axes have stood still for 20 ms (or `limit` s); the largest distance from
/// the path on the way.
double RunToRest(Lathe& m, const std::vector<std::pair<double, double>>& path, double limit = 30) {
  double off = 0, still = 0, x = m.X(), z = m.Z();
  const double end = m.t + limit;
  while (m.t < end && still < 0.02) {
    m.Tick();
    off = std::max(off, DistanceToPolyline(m.X(), m.Z(), path));
    still = m.X() == x && m.Z() == z ? still + 250e-6 : 0;
    x = m.X(), z = m.Z();
  }
  return off;
}

/// Feed hold, then RunToRest along `path`: the largest distance from it while braking.
double HoldToRest(Lathe& m, const std::vector<std::pair<double, double>>& path) {
  m.channel->Stop();
  return RunToRest(m, path);
}

/// Backward travel on, and the start key: the legs go back from where the axes stand.
void StartBackward(Lathe& m) {
  m.channel->SetBackward(true);
  m.channel->Start();
}

/// Backward travel off, and the start key: forward again (or the program goes on).
void StartForward(Lathe& m) {
  m.channel->SetBackward(false);
  m.channel->Start();
}

/// Started, held in N30 at Z-15 and braked to rest.
void HoldInN30(Lathe& m) {
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.Z() < -15; }));
  HoldToRest(m, PassPolyline());
  ASSERT_EQ(m.channel->state(), ChannelState::kHold);
}

TEST(ChannelBackward, RetracesTheBlocksThenForwardGoesOnFromTheInterruptionPoint) {
  Lathe m(kPass);
  HoldInN30(m);
  const double hold_x = m.X(), hold_z = m.Z();
  EXPECT_NEAR(hold_x, 40, 1e-9);
  StartBackward(m);
  // Back through N30, N20 and the G00 of N10 to where the program started, on the path all
  // the way.
  EXPECT_LT(RunToRest(m, PassPolyline()), 1e-6);
  EXPECT_NEAR(m.X(), 0, 1e-9);
  EXPECT_NEAR(m.Z(), 0, 1e-9);
  EXPECT_TRUE(m.channel->travelling_back());
  EXPECT_EQ(m.channel->blocks_back(), 2u);  // standing on N10, two blocks behind N30
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  // Forward: along the path to the interruption point, and the program goes on to its end.
  StartForward(m);
  ASSERT_TRUE(m.RunUntil([&] { return !m.channel->travelling_back(); }));
  EXPECT_EQ(m.channel->position(0), hold_x);  // exactly: the block goes on from there
  EXPECT_EQ(m.channel->position(1), hold_z);
  EXPECT_EQ(m.channel->state(), ChannelState::kRunning);
  EXPECT_LT(RunToRest(m, PassPolyline()), 1e-4);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_NEAR(m.X(), 60, 1e-9);
  EXPECT_NEAR(m.Z(), -40, 1e-9);
}

TEST(ChannelBackward, FeedHoldStopsOnThePathAndTheFeedOfEachBlockHolds) {
  Lathe m(kPass);
  HoldInN30(m);
  StartBackward(m);
  // N30 backwards at its F600 (10 mm/s): after 0.5 s about 5 mm of Z.
  const double z0 = m.Z();
  m.RunUntil([] { return false; }, 0.5);
  EXPECT_NEAR(m.Z() - z0, 5, 0.1);
  EXPECT_LT(HoldToRest(m, PassPolyline()), 1e-6);
  const double z1 = m.Z();
  EXPECT_GT(z1, z0 + 5);
  EXPECT_LT(z1, 0);  // braked inside N30
  EXPECT_NEAR(m.X(), 40, 1e-9);
  // Back again from there, then forward to the end.
  m.channel->Start();
  RunToRest(m, PassPolyline());
  EXPECT_NEAR(m.Z(), 0, 1e-9);
  StartForward(m);
  EXPECT_LT(RunToRest(m, PassPolyline()), 1e-4);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
}

TEST(ChannelBackward, AfterTheArcRetracesItBackwards) {
  Lathe m(kPass);
  m.channel->Start();
  // Held in N50, after the arc.
  ASSERT_TRUE(m.RunUntil([&] { return m.X() > 52; }));
  HoldToRest(m, PassPolyline());
  StartBackward(m);
  double off = 0;
  ASSERT_TRUE(m.RunUntil([&] {
    off = std::max(off, DistanceToPolyline(m.X(), m.Z(), PassPolyline()));
    return m.Z() > -29;
  }));
  EXPECT_LT(off, 1e-4);  // the chords of PassPolyline
  HoldToRest(m, PassPolyline());
  StartForward(m);
  EXPECT_LT(RunToRest(m, PassPolyline()), 1e-4);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
}

TEST(ChannelBackward, ManualModeAfterTravellingBackLeavesTheContourAtTheInterruptionPoint) {
  Lathe m(kPass);
  HoldInN30(m);
  StartBackward(m);
  ASSERT_TRUE(m.RunUntil([&] { return m.Z() > -10; }));
  HoldToRest(m, PassPolyline());
  // Manual mode: the interruption point is where the program stopped, which the axes have
  // left; continuing needs repositioning first (REPOS manual 2.1).
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  EXPECT_FALSE(m.channel->travelling_back());
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  StartForward(m);
  m.Tick();
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgLeftContour);
}

TEST(ChannelBackward, ModeChangeIsRefusedWhileALegMoves) {
  Lathe m(kPass);
  HoldInN30(m);
  StartBackward(m);
  m.RunUntil([] { return false; }, 0.1);
  EXPECT_FALSE(m.channel->SetMode(ChannelMode::kManual));
}

/// Records every check; a wall at Z > 8 stops what crosses it.
struct WallAtZ8 : PathGuard {
  PathCheck CheckMove(const std::vector<double>& from, const std::vector<double>& to) override {
    moves.push_back({from, to});
    PathCheck c;
    c.min_clearance = 8 - std::max(from[1], to[1]);
    if (c.min_clearance >= 0) return c;
    c.clear = false;
    c.part_a = "tool", c.part_b = "wall";
    c.position = from;
    c.min_clearance = 0;
    return c;
  }
  std::vector<std::pair<std::vector<double>, std::vector<double>>> moves;
};

TEST(ChannelBackward, TheWayBackOfATravelledPathIsNotChecked) {
  // The axes went along it and the stock only got smaller since: clear by what happened (a
  // check would find the tool's own cut where a retract starts).
  Lathe m(kPass);
  HoldInN30(m);
  WallAtZ8 wall;  // N10 came from Z10 over the wall
  m.channel->SetPathGuard(&wall);
  StartBackward(m);
  RunToRest(m, PassPolyline());
  EXPECT_TRUE(wall.moves.empty());
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  EXPECT_NEAR(m.X(), 0, 1e-9);
  EXPECT_NEAR(m.Z(), 0, 1e-9);
}

/// ISG: the block search of the manual on the lathe.
constexpr const char* kSearchPass =
    "N10 G00 G90 X20 Z5\n"
    "N20 G01 X10 F600\n"
    "N30 Z-10\n"
    "N40 X30\n"
    "N50 Z-20\n"
    "N60 M30\n";

TEST(ChannelBackward, AfterBlockSearchTravelsTheDecodedProgramBackwards) {
  // 4.3: "in Rückwärtsrichtung ab der Startposition aus dem Satzvorlauf das real programmierte
  // NC-Programm": from the continue position (N40's start, X10 Z-10) back along N30, N20 and
  // N10, which the axes never travelled, to where the program started (X50 Z50).
  Lathe m(kSearchPass, 50, 50, {}, nc::Dialect::kIsg);
  m.Search(testing::BlockNumberSearch(40));
  ASSERT_TRUE(m.ToContour());
  EXPECT_NEAR(m.X(), 10, 1e-9);
  EXPECT_NEAR(m.Z(), -10, 1e-9);
  const std::vector<std::pair<double, double>> path = {{50, 50},  {20, 5},   {10, 5},
                                                       {10, -10}, {30, -10}, {30, -20}};
  StartBackward(m);
  EXPECT_LT(RunToRest(m, path), 1e-6);
  EXPECT_NEAR(m.X(), 50, 1e-9);
  EXPECT_NEAR(m.Z(), 50, 1e-9);
  // Forward to the continue position, where the program goes on as after the search.
  StartForward(m);
  EXPECT_LT(RunToRest(m, path), 1e-6);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_NEAR(m.X(), 30, 1e-9);
  EXPECT_NEAR(m.Z(), -20, 1e-9);
}

TEST(ChannelBackward, TheDecodedRapidLegsAreAskedOfPathGuardFirst) {
  // After block search the axes go back along blocks they never travelled: the stock the search
  // skipped may be there. N10's G00 (X20 Z5 <- X50 Z50) crosses the wall; N30 and N20 are feed
  // legs, the program's cuts, and go back unchecked.
  Lathe m(kSearchPass, 50, 50, {}, nc::Dialect::kIsg);
  m.Search(testing::BlockNumberSearch(40));
  ASSERT_TRUE(m.ToContour());
  WallAtZ8 wall;
  m.channel->SetPathGuard(&wall);
  m.channel->TakeGuardRecords();
  StartBackward(m);
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kError; }));
  EXPECT_EQ(m.channel->error_number(), kMsgCollision);
  EXPECT_THAT(m.channel->error(),
              HasSubstr("collision ahead (backward travel): tool would touch wall"));
  ASSERT_EQ(wall.moves.size(), 1u);  // stopped before it moved: at N10's end
  EXPECT_EQ(m.channel->position(0), 20);
  EXPECT_EQ(m.channel->position(1), 5);
  const auto records = m.channel->TakeGuardRecords();
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].move, "backward travel");
  EXPECT_TRUE(records[0].stopped);
}

TEST(ChannelBackward, NotPossibleWithTheOffsetOfAManualReturn) {
  // 4.2: "Bei einem Offset > 0 ist Rückwärtsfahren nicht möglich!"
  BlockSearchParameters p = testing::BlockNumberSearch(40);
  p.auto_return = false;
  p.deviation_max = 5000;  // 0.5 mm
  Lathe m(kSearchPass, 10.2, -10.1, {}, nc::Dialect::kIsg);
  p.no_hold_at_restart = false;
  m.Search(p);
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour));
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.X() > 15; }));
  HoldToRest(m, {{10.2, -10.1}, {30.2, -10.1}});
  const double x = m.X();
  StartBackward(m);
  m.RunUntil([] { return false; }, 0.1);
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);  // a message, the program still held
  EXPECT_EQ(m.channel->error_number(), kMsgBackward);
  EXPECT_THAT(m.channel->error(), HasSubstr("offset"));
  EXPECT_EQ(m.X(), x);
  StartForward(m);
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kEnded; }));
  EXPECT_EQ(m.channel->error_number(), 0);
  EXPECT_NEAR(m.X(), 30.2, 1e-9);
}

TEST(ChannelBackward, TheStartOfTheOldestBlockIsAsFarAsItGoes) {
  Lathe m("N10 G01 X10 F600\nN20 M30\n");
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.X() > 0; }));
  HoldToRest(m, {{0, 0}, {10, 0}});
  StartBackward(m);
  m.Tick();
  // Inside the first block there is its start behind the axes: that much goes back.
  RunToRest(m, {{0, 0}, {10, 0}});
  EXPECT_NEAR(m.X(), 0, 1e-9);
  m.channel->Start();  // at the start of the oldest block: nowhere further back
  m.Tick();
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  EXPECT_NEAR(m.X(), 0, 1e-9);
}

TEST(ChannelBackward, APathBreakIsAsFarBackAsItGoes) {
  // G74 breaks the path (the axes were homed, there is no way back through it): backward travel
  // ends at the start of the block after it, whatever the memory held before the break.
  Lathe m(
      "N10 G00 X50 Z10\n"
      "N20 G01 X40 Z0 F600\n"
      "N30 G74 X1\n"
      "N40 G01 Z-30 F600\n"
      "N50 X60\n"
      "N60 M30\n");
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.Z() < -15; }));
  ASSERT_NEAR(m.X(), 0, 1e-9);  // homed to its reference position
  const std::vector<std::pair<double, double>> n40 = {{0, 0}, {0, -30}};
  HoldToRest(m, n40);
  StartBackward(m);
  EXPECT_LT(RunToRest(m, n40), 1e-9);  // along N40 only
  EXPECT_NEAR(m.X(), 0, 1e-9);
  EXPECT_NEAR(m.Z(), 0, 1e-9);
  EXPECT_EQ(m.channel->blocks_back(), 0u);
  m.channel->Start();  // at the break: nowhere further back
  for (int i = 0; i < 40; ++i) m.Tick();
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  EXPECT_NEAR(m.Z(), 0, 1e-9);
  StartForward(m);  // and on through N50's corner, within the look-ahead's corner deviation
  EXPECT_LT(RunToRest(m, {{0, 0}, {0, -30}, {60, -30}}), kCornerDeviation);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_NEAR(m.X(), 60, 1e-9);
}

}  // namespace
}  // namespace vmt::control::channel
