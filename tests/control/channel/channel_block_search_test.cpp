// Block search in the channel (twincat-cnc-block-search-de.md), with the manual's examples on
// an ideal X/Y/Z machine (they are milling programs): types 1, 3, 4 and 5, the position inside
// a block by per mille and by distance from program start, the breakpoint, locked regions, the
// continue position not found, the automatic return (PathGuard first) and the manual one with
// its deviation, the PLC handshake and the technology of the skipped part.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <tuple>

#include "block_search_steps.hpp"
#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using testing::Axis;
using ::testing::HasSubstr;

/// Manual 9.1.1 / 9.2.1: a square drawn with a loop. N100 runs five times (X12 -> X2).
constexpr const char* kSquare =
    "%t_sv_number.nc\n"
    "N00 G00 G90 X2 Y2\n"
    "P1 = 0\n"
    "N80 G01 G91 X10 F500\n"
    "N095 Y10\n"
    "\n"
    "$FOR P1 = 1, 5, 1\n"
    "N100 X-2\n"
    "$ENDFOR\n"
    "\n"
    "N120 Y-10\n"
    "N130 M30\n";

/// Manual 9.1.2: the same square with one N100 of 10 mm.
constexpr const char* kSquareOneBlock =
    "%t_sv_number.nc\n"
    "N00 G00 G90 X2 Y2\n"
    "P1 = 0\n"
    "N80 G01 G91 X10 F500\n"
    "N95 Y10\n"
    "N100 X-10\n"
    "N120 Y-10\n"
    "N130 M30\n";

/// X, Y, Z on an ideal machine (actual = setpoint), a spindle on drive 3 that ramps to its
/// speed at 6000 deg/s^2 and reports at-speed when there (its own answer: it reaches the
/// command exactly, with no standstill bit and no position).
struct MillRig : test_support::IdealDriveBus {
  explicit MillRig(const std::string& text, std::vector<double> start = {0, 0, 0},
                   const std::function<void(ChannelConfig&)>& configure = {})
      : IdealDriveBus(4) {
    parsed = nc::ParseProgram(text, "t_sv_number.nc", nc::Dialect::kIsg);
    EXPECT_TRUE(parsed.ok()) << nc::Format(parsed.errors[0], parsed.program.files);
    ChannelConfig config;
    config.axes = {Axis("X", 0, 100), Axis("Y", 1, 100), Axis("Z", 2, 100)};
    config.spindle_drive = 3;
    config.initial.plane = nc::Plane::kXY;
    if (configure) configure(config);
    channel = std::make_unique<Channel>(config, std::vector<const nc::Program*>{&parsed.program});
    for (int d = 0; d < 3; ++d) {
      drives[d] = test_support::IdealDrive::Follow();
      at.feedback[d].position = start[d];
    }
  }
  void Tick() {
    channel->Tick(at, mdt);
    for (int d = 0; d < 3; ++d)
      if (mdt.setpoints[d].mode == DriveMode::kPosition &&
          at.feedback[d].position != mdt.setpoints[d].value)
        moved = true;
    Answer();
    DriveFeedback& s = at.feedback[3];
    const double want = mdt.setpoints[3].mode == DriveMode::kVelocity ? mdt.setpoints[3].value : 0;
    const double step = 6000 * 250e-6;
    s.velocity = std::abs(want - s.velocity) <= step
                     ? want
                     : s.velocity + std::copysign(step, want - s.velocity);
    s.status = drive_status::kReady | (s.velocity == want ? drive_status::kAtSpeed : 0u) |
               (mdt.setpoints[3].mode == DriveMode::kPosition ? drive_status::kInPosition : 0u);
    t += 250e-6;
  }
  double X() const { return at.feedback[0].position; }
  double Y() const { return at.feedback[1].position; }
  double Z() const { return at.feedback[2].position; }

  nc::ParseResult parsed;
  std::unique_ptr<Channel> channel;
  double t = 0;
  bool moved = false;
};
using Mill = testing::BlockSearchSteps<MillRig>;

TEST(ChannelBlockSearch, Type4FindsTheBlockWithoutMovingAndReturnsToItsStart) {
  // 9.1.1: block number 100, pass 1. The continue position is the start of the first N100
  // (X12 Y12), where its motion begins for real; the manual's "X = 10 Y = 12" is where that
  // block ends, the first point reached after the continue.
  Mill m(kSquare, {50, 40, 5});
  m.Search(testing::BlockNumberSearch(100));
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour));
  EXPECT_FALSE(m.moved);  // the search moves no axis
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  const BlockSearchStatus& st = m.channel->block_search();
  ASSERT_EQ(st.continue_position.size(), 3u);
  EXPECT_NEAR(st.continue_position[0], 12, 1e-9);
  EXPECT_NEAR(st.continue_position[1], 12, 1e-9);
  EXPECT_NEAR(st.continue_position[2], 5, 1e-9);  // Z stays where it stood: never programmed
  EXPECT_NEAR(st.path_deviation, std::hypot(38, 28), 1e-9);
  EXPECT_EQ(st.block_count, 8u);  // the first N100's line count (9.2.1)
  m.channel->Start();
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForContinueContour));
  EXPECT_NEAR(m.X(), 12, 1e-9);
  EXPECT_NEAR(m.Y(), 12, 1e-9);
  EXPECT_NEAR(m.Z(), 5, 1e-9);
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  m.channel->Start();  // "nach dem Fortsetzen wird der restliche Teil des Quadrates gefahren"
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kEnded; }));
  EXPECT_NEAR(m.X(), 2, 1e-9);
  EXPECT_NEAR(m.Y(), 2, 1e-9);
  EXPECT_EQ(m.State(), BlockSearchState::kInactive);
}

TEST(ChannelBlockSearch, Type4PassCounterCountsTheLoop) {
  // 9.1.1 with pass 4: the fourth N100 starts at X6.
  Mill m(kSquare);
  m.Search(testing::BlockNumberSearch(100, 0, 4));
  ASSERT_TRUE(m.ToContour());
  EXPECT_NEAR(m.X(), 6, 1e-9);
  EXPECT_NEAR(m.Y(), 12, 1e-9);
  // Section 10: a pass count below 2 takes the first occurrence.
  Mill first(kSquare);
  first.Search(testing::BlockNumberSearch(100, 0, 0));
  ASSERT_TRUE(first.ToContour());
  EXPECT_NEAR(first.X(), 12, 1e-9);
}

TEST(ChannelBlockSearch, PassBeyondTheLoopIsNotFoundAndTheProgramEndsInSearchMode) {
  // Section 10: pass 6 of five: P-ERR-20704, a warning; the whole program ran without motion.
  Mill m(kSquare, {50, 40, 5});
  m.Search(testing::BlockNumberSearch(100, 0, 6));
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kEnded; }));
  EXPECT_FALSE(m.moved);
  EXPECT_EQ(m.State(), BlockSearchState::kInactive);
  ASSERT_EQ(m.channel->block_search().warnings.size(), 1u);
  EXPECT_THAT(m.channel->block_search().warnings[0], HasSubstr("P-ERR-20704"));
  // An unknown block number: the same.
  Mill unknown(kSquare);
  unknown.Search(testing::BlockNumberSearch(777));
  ASSERT_TRUE(unknown.RunUntil([&] { return unknown.channel->state() == ChannelState::kEnded; }));
  EXPECT_FALSE(unknown.moved);
  EXPECT_EQ(unknown.channel->block_search().warnings.size(), 1u);
}

TEST(ChannelBlockSearch, CoveredDistanceSplitsTheBlock) {
  // 9.1.2: N100 X-10 at 0, 300, 800 and 1000 per mille: the continue positions X12, X9, X4, X2.
  for (const auto& [permille, x] :
       {std::pair{0.0, 12.0}, {300.0, 9.0}, {800.0, 4.0}, {1000.0, 2.0}}) {
    Mill m(kSquareOneBlock);
    BlockSearchParameters p = testing::BlockNumberSearch(100);
    p.covered_distance = permille;
    m.Search(p);
    ASSERT_TRUE(m.ToContour()) << permille;
    EXPECT_NEAR(m.X(), x, 1e-9) << permille;
    EXPECT_NEAR(m.Y(), 12, 1e-9) << permille;
    // The rest of the square from there.
    m.channel->Start();
    bool went_back = false;
    ASSERT_TRUE(m.RunUntil([&] {
      went_back = went_back || m.X() > x + 1e-9;
      return m.channel->state() == ChannelState::kEnded;
    }));
    EXPECT_FALSE(went_back) << permille;
    EXPECT_NEAR(m.X(), 2, 1e-9);
    EXPECT_NEAR(m.Y(), 2, 1e-9);
  }
}

TEST(ChannelBlockSearch, Type3BlockCounterCountsEveryDecodedLine) {
  // 9.2.1: BC 8 is the first N100, BC 16 the fifth.
  for (const auto& [count, x] : {std::pair{8u, 12.0}, {16u, 4.0}, {19u, 2.0}}) {
    Mill m(kSquare);
    BlockSearchParameters p;
    p.type = BlockSearchType::kBlockCounter;
    p.intern_block_count = count;
    p.auto_return = true;
    m.Search(p);
    ASSERT_TRUE(m.ToContour()) << count;
    EXPECT_NEAR(m.X(), x, 1e-9) << count;
    EXPECT_NEAR(m.Y(), 12, 1e-9) << count;
    EXPECT_EQ(m.channel->block_search().block_count, count);
  }
}

TEST(ChannelBlockSearch, Type1FileOffsetWithPassAndEndPosition) {
  // 3.1: the continue position by the offset of its line in the file, in the third pass; the
  // end position at N120's line: the program ends there at once (N120 does not run).
  const std::string text = kSquare;
  Mill m(text);
  BlockSearchParameters p;
  p.type = BlockSearchType::kFileOffset;
  p.start.offset = static_cast<int64_t>(text.find("N100"));
  p.start.name = "t_sv_number.nc";
  p.start.count = 3;
  p.end.offset = static_cast<int64_t>(text.find("N120"));
  p.auto_return = true;
  m.Search(p);
  ASSERT_TRUE(m.ToContour());
  EXPECT_NEAR(m.X(), 8, 1e-9);
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kEnded; }));
  EXPECT_NEAR(m.X(), 2, 1e-9);
  EXPECT_NEAR(m.Y(), 12, 1e-9);  // N120 Y-10 never ran
  // A name that is not the started file: not found.
  Mill other(text);
  p.start.name = "other.nc";
  other.Search(p);
  ASSERT_TRUE(other.RunUntil([&] { return other.channel->state() == ChannelState::kEnded; }));
  EXPECT_FALSE(other.moved);
  EXPECT_EQ(other.channel->block_search().warnings.size(), 1u);
}

TEST(ChannelBlockSearch, Type5DecodesToTheProgramEndWithoutMotion) {
  Mill m(kSquare, {50, 40, 5});
  BlockSearchParameters p;
  p.type = BlockSearchType::kProgramEnd;
  m.Search(p);
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kEnded; }));
  EXPECT_FALSE(m.moved);
  EXPECT_TRUE(m.channel->block_search().warnings.empty());
  EXPECT_EQ(m.channel->block_search().block_count, 20u);  // N130, the last line (9.2.1)
}

constexpr const char* kDistance =
    "%distance\n"
    "N10 G01 X0 Y0 F1000\n"
    "N20 X10\n"
    "N30 X20 Y10\n"
    "N40 X30\n"
    "N50 X430\n"
    "N60 G74 X1\n"
    "N70 X0\n"
    "N999 M30\n";

TEST(ChannelBlockSearch, DistanceFromProgramStartMovesTheContinuePositionForward) {
  // Figures 15 and 16: block number 30, then 16 mm from program start lies in N30 (10 + 6 of
  // its 14.14 mm), 234.79 mm in N50 (34.14 + 200.65).
  for (const auto& [mm, x, y] : {std::tuple{16.0, 10 + 6 / std::sqrt(2.0), 6 / std::sqrt(2.0)},
                                 {234.79, 30 + (234.79 - 20 - std::hypot(10.0, 10.0)), 10.0}}) {
    Mill m(kDistance);
    BlockSearchParameters p = testing::BlockNumberSearch(30);
    p.distance_prog_start = mm * 1e4;  // 0.1 um
    m.Search(p);
    ASSERT_TRUE(m.ToContour()) << mm << " " << m.channel->error();
    EXPECT_NEAR(m.X(), x, 1e-6) << mm;
    EXPECT_NEAR(m.Y(), y, 1e-6) << mm;
    EXPECT_TRUE(m.channel->block_search().warnings.empty());
    EXPECT_NEAR(m.channel->block_search().dist_prog_start, mm, 1e-6);
  }
}

TEST(ChannelBlockSearch, DistanceBeforeTheBlockWarnsAndContinuesAtItsStart) {
  // Figure 18: block 30 with 2 mm, which lies in N20: never back; a warning, N30's start.
  Mill m(kDistance);
  BlockSearchParameters p = testing::BlockNumberSearch(30);
  p.distance_prog_start = 2e4;
  m.Search(p);
  ASSERT_TRUE(m.ToContour());
  EXPECT_NEAR(m.X(), 10, 1e-9);
  EXPECT_NEAR(m.Y(), 0, 1e-9);
  ASSERT_EQ(m.channel->block_search().warnings.size(), 1u);
  EXPECT_THAT(m.channel->block_search().warnings[0], HasSubstr("lies before the block"));
}

TEST(ChannelBlockSearch, VectorOffsetIsRefusedAtItsWordInARunAndInASearch) {
  // 4.2.3: vmt has no orientation angles for #VECTOR OFFSET to correct; it refuses the command
  // where it stands rather than pass it.
  const std::string program =
      "%t_sv_number.nc\n"
      "N10 G00 G90 X2 Y2\n"
      "N20 #VECTOR OFFSET ON [ DS=1 DE=1 ANC=0.5 DRC=0.2]\n"
      "N30 G01 X10 F500\n"
      "N40 M30\n";
  const std::string refusal =
      "t_sv_number.nc:3:5: error: #VECTOR OFFSET (path-dependent angle correction, block "
      "search 4.2.3) is not supported by vmt (docs/conformance.md)";
  Mill run(program);
  run.channel->Start();
  run.RunUntil([&] { return run.channel->state() != ChannelState::kRunning; });
  ASSERT_EQ(run.channel->state(), ChannelState::kError);
  EXPECT_THAT(run.channel->error(), HasSubstr(refusal));
  EXPECT_EQ(run.X(), 2);  // N30 never ran
  Mill search(program);
  search.Search(testing::BlockNumberSearch(30));
  search.RunUntil([&] { return search.channel->state() == ChannelState::kError; }, 5);
  ASSERT_EQ(search.channel->state(), ChannelState::kError);
  EXPECT_THAT(search.channel->error(), HasSubstr(refusal));
  EXPECT_FALSE(search.moved);
}

TEST(ChannelBlockSearch, G74BeyondTheBlockBoundaryIsAnError) {
  // Figure 17: searching on by distance past a G74 cannot simulate it.
  Mill m(kDistance);
  BlockSearchParameters p = testing::BlockNumberSearch(30);
  p.distance_prog_start = 900 * 1e4;  // beyond N50's end (434.14)
  m.Search(p);
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kError; }));
  EXPECT_EQ(m.channel->error_number(), kMsgBlockSearch);
  EXPECT_THAT(m.channel->error(), HasSubstr("G74"));
  EXPECT_FALSE(m.moved);
}

TEST(ChannelBlockSearch, ABlockWithoutMotionIsNotSplit) {
  // Section 10: continue in N100 P100 = 1 at 10 %: N100 has no motion; machining goes on with
  // N110 from N095's end.
  Mill m(
      "%t_sv_p.nc\n"
      "N907090 G01 X0 Y0 Z0 F1000\n"
      "N070 Y10\n"
      "N095 X2.1 Y2.2 Z2.3\n"
      "N100 P100 = 1\n"
      "N110 G00 G91 X10\n"
      "N120 G90 X3.1 Y3.2 Z3.3\n"
      "N907091 M30\n",
      {20, 20, 20});
  BlockSearchParameters p = testing::BlockNumberSearch(100);
  p.covered_distance = 100;
  m.Search(p);
  ASSERT_TRUE(m.ToContour());
  EXPECT_NEAR(m.X(), 2.1, 1e-9);
  EXPECT_NEAR(m.Y(), 2.2, 1e-9);
  EXPECT_NEAR(m.Z(), 2.3, 1e-9);
  m.channel->Start();
  double furthest = 0;
  ASSERT_TRUE(m.RunUntil([&] {
    furthest = std::max(furthest, m.X());
    return m.channel->state() == ChannelState::kEnded;
  }));
  EXPECT_NEAR(furthest, 12.1, 1e-9);  // N110 ran whole
  EXPECT_NEAR(m.X(), 3.1, 1e-9);
}

TEST(ChannelBlockSearch, ALockedRegionRefusesTheContinuePosition) {
  // Section 6, example 2: LOCKED ... LOCKED ... RELEASED locks N40..N75.
  const std::string program =
      "%BLOCKSEARCH\n"
      "N10 G01 X0 Y0 Z0 F1000\n"
      "N20 X10\n"
      "N30 Y10\n"
      "N40 #BLOCKSEARCH LOCKED\n"
      "N50 X20\n"
      "N55 #BLOCKSEARCH LOCKED\n"
      "N60 Y20\n"
      "N70 Z20\n"
      "N75 #BLOCKSEARCH RELEASED\n"
      "N80 X30\n"
      "N100 #BLOCKSEARCH RELEASED\n"
      "N110 Y30\n"
      "N999 M30\n";
  for (const uint32_t locked : {40u, 60u, 75u}) {
    Mill m(program);
    m.Search(testing::BlockNumberSearch(locked));
    ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kError; })) << locked;
    EXPECT_EQ(m.channel->error_number(), kMsgBlockSearchLocked) << locked;
    EXPECT_THAT(m.channel->error(), HasSubstr("P-ERR-21399"));
  }
  Mill free(program);
  free.Search(testing::BlockNumberSearch(80));
  ASSERT_TRUE(free.ToContour());
  EXPECT_NEAR(free.X(), 20, 1e-9);
  EXPECT_NEAR(free.Z(), 20, 1e-9);
}

/// A wall at X = 20 for the tool (drive 0), as the path guard tests use it.
struct Wall : PathGuard {
  PathCheck CheckMove(const std::vector<double>& from, const std::vector<double>& to) override {
    ++checks;
    PathCheck c;
    c.min_clearance = std::min(from[0], to[0]) - 20;
    if (to[0] > 20 || from[0] < 20) return c;
    c.clear = false;
    c.part_a = "tool", c.part_b = "wall";
    c.position = from;
    const double u = (from[0] - 20) / (from[0] - to[0]);
    for (size_t d = 0; d < from.size(); ++d) c.position[d] = from[d] + (to[d] - from[d]) * u;
    c.min_clearance = 0;
    return c;
  }
  int checks = 0;
};

TEST(ChannelBlockSearch, ReturnThroughAnObstacleIsRefusedBeforeItMoves) {
  Wall wall;
  Mill m(kSquare, {50, 40, 0});
  m.channel->SetPathGuard(&wall);
  m.Search(testing::BlockNumberSearch(100));
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour));
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kError; }));
  EXPECT_EQ(m.channel->error_number(), kMsgCollision);
  EXPECT_THAT(m.channel->error(), HasSubstr("return to contour"));
  EXPECT_THAT(m.channel->error(), HasSubstr("tool would touch wall"));
  EXPECT_FALSE(m.moved);
  EXPECT_EQ(wall.checks, 1);
  const auto records = m.channel->TakeGuardRecords();
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].move, "return to contour");
}

TEST(ChannelBlockSearch, ManualReturnKeepsTheOffsetWithinTheAllowedDeviation) {
  // 4.2: without the automatic return the axes stay where the operator put them; within
  // mc_cmd_bs_deviation_max_w the program goes on offset by the difference.
  BlockSearchParameters p = testing::BlockNumberSearch(100);
  p.auto_return = false;
  p.deviation_max = 5000;  // 0.5 mm
  Mill m(kSquare, {12.3, 12.4, 0});
  m.Search(p);
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour));
  EXPECT_NEAR(m.channel->block_search().path_deviation, 0.5, 1e-9);
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kEnded; }));
  EXPECT_NEAR(m.X(), 2.3, 1e-9);  // the square's corner X2 Y2, offset
  EXPECT_NEAR(m.Y(), 2.4, 1e-9);
  // Beyond the allowed deviation: an error, nothing moves.
  p.deviation_max = 4999;
  Mill far(kSquare, {12.3, 12.4, 0});
  far.Search(p);
  ASSERT_TRUE(far.Waits(BlockSearchState::kWaitReturnToContour));
  far.channel->Start();
  ASSERT_TRUE(far.RunUntil([&] { return far.channel->state() == ChannelState::kError; }));
  EXPECT_EQ(far.channel->error_number(), kMsgBlockSearchDeviation);
  EXPECT_FALSE(far.moved);
}

TEST(ChannelBlockSearch, NoHoldAtRestartGoesOnAfterTheReturn) {
  Mill m(kSquare, {30, 30, 0});
  BlockSearchParameters p = testing::BlockNumberSearch(100, 0, 5);
  p.no_hold_at_restart = true;
  m.Search(p);
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour));
  m.channel->Start();
  bool held = false;
  ASSERT_TRUE(m.RunUntil([&] {
    held = held || m.State() == BlockSearchState::kWaitForContinueContour;
    return m.channel->state() == ChannelState::kEnded;
  }));
  EXPECT_FALSE(held);
  EXPECT_NEAR(m.Y(), 2, 1e-9);
}

TEST(ChannelBlockSearch, HandshakeWithThePlcOnAndOff) {
  // 7: with enable_w the NC raises command_r and waits for the PLC's TRUE before it searches;
  // found, it drops command_r and waits for the PLC's FALSE.
  Mill m(kSquare);
  m.channel->SetBlockSearchPlc(true, false);
  m.Search(testing::BlockNumberSearch(100));
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_EQ(m.State(), BlockSearchState::kWaitForPlcOn);
  EXPECT_TRUE(m.channel->block_search().command);
  EXPECT_FALSE(m.channel->block_search().active());
  m.channel->SetBlockSearchPlc(true, true);
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForPlcOff));
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_EQ(m.State(), BlockSearchState::kWaitForPlcOff);
  EXPECT_TRUE(m.channel->block_search().active());
  EXPECT_FALSE(m.channel->block_search().command);
  m.channel->SetBlockSearchPlc(true, false);
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour));
  EXPECT_FALSE(m.channel->block_search().active());
}

TEST(ChannelBlockSearch, TechnologyOfTheSkippedPartGoesToThePlcAndTheSpindleRunsUpFirst) {
  // 2: the PLC gets every technology function of the search and acknowledges it; the spindle
  // has its speed back before the axes return.
  Mill m(
      "%tech\n"
      "N10 G01 X0 Y0 Z0 F1000 S1000 M3\n"
      "N20 M8\n"
      "N30 X10\n"
      "N40 Y10\n"
      "N50 M30\n",
      {0, 0, 0}, [](ChannelConfig& c) { c.aux_handshake = true; });
  m.Search(testing::BlockNumberSearch(40));
  std::vector<int> m_functions;
  ASSERT_TRUE(m.RunUntil([&] {
    if (!m.channel->aux_output().empty()) {
      for (const nc::AuxFunction& f : m.channel->aux_output())
        if (f.letter == 'M') m_functions.push_back(static_cast<int>(f.value));
      m.channel->AcknowledgeAux();
    }
    return m.State() == BlockSearchState::kWaitReturnToContour;
  }));
  EXPECT_THAT(m_functions, ::testing::ElementsAre(3, 8));
  EXPECT_EQ(m.at.feedback[3].velocity, 0);  // not before the start
  m.channel->Start();
  double spindle_when_moving = -1;
  ASSERT_TRUE(m.RunUntil([&] {
    if (spindle_when_moving < 0 && m.X() > 0) spindle_when_moving = m.at.feedback[3].velocity;
    return m.State() == BlockSearchState::kWaitForContinueContour;
  }));
  EXPECT_EQ(spindle_when_moving, 6000);  // 1000 rpm before the first axis moved
  EXPECT_NEAR(m.X(), 10, 1e-9);
}

TEST(ChannelBlockSearch, BreakpointStopsOnceLikeM0) {
  // 3.5.1: type 6, a breakpoint at 15 mm from program start, without a search.
  Mill m(kSquareOneBlock, {2, 2, 0});
  BlockSearchParameters p;
  p.type = BlockSearchType::kBreakpointOnly;
  p.breakpoint_position = 15 * 1e4;
  m.Search(p);
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kHold; }));
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_NEAR(m.X(), 12, 1e-9);  // 10 mm of N80, 5 of N95
  EXPECT_NEAR(m.Y(), 7, 1e-9);
  const BlockSearchStatus& st = m.channel->block_search();
  EXPECT_EQ(st.state, BlockSearchState::kWaitForContinueContour);
  EXPECT_TRUE(st.stop_conditions & stop_condition::kBreakpointStop);
  EXPECT_NEAR(st.dist_prog_start, 15, 1e-9);
  EXPECT_NEAR(st.covered_distance, 500, 1e-6);
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kEnded; }));
  EXPECT_NEAR(m.X(), 2, 1e-9);
  EXPECT_NEAR(m.Y(), 2, 1e-9);
  EXPECT_NEAR(m.channel->block_search().dist_prog_start, 40, 1e-9);
}

TEST(ChannelBlockSearch, DistanceCommandsSteerTheCount) {
  // 4.1.2, figure 14: OFF for the approach, CLEAR, ON: only the part's moves count.
  Mill m(
      "%example\n"
      "N05 #DISTANCE PROG START OFF\n"
      "N10 G01 X0 Y0 F3000\n"
      "N15 #DISTANCE PROG START CLEAR\n"
      "N16 #DISTANCE PROG START ON\n"
      "N20 X10\n"
      "N30 X20 Y10\n"
      "M30\n",
      {40, 40, 0});
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kEnded; }));
  EXPECT_NEAR(m.channel->block_search().dist_prog_start, 10 + std::hypot(10.0, 10.0), 1e-9);
}

TEST(ChannelBlockSearch, EntryPointSkipsThePartBeforeIt) {
  // 3.6: type 4 from an entry point: the blocks before it are not evaluated (P1 stays 0).
  const std::string text = kSquare;
  Mill m(text);
  BlockSearchParameters p = testing::BlockNumberSearch(100, 0, 2);
  p.file_offset = static_cast<int64_t>(text.find("N095"));
  m.Search(p);
  ASSERT_TRUE(m.ToContour()) << m.channel->error();
  // N00 and N80 never ran: N095 Y10 is a G00 in the start's modal state (G90), and N100
  // X-2 absolute too; the second N100 starts where the first ended.
  EXPECT_NEAR(m.Y(), 10, 1e-9);
  EXPECT_NEAR(m.X(), -2, 1e-9);
  // Beyond the last block: an error at the start.
  Mill beyond(text);
  p.file_offset = static_cast<int64_t>(text.size()) + 10;
  beyond.Search(p);
  ASSERT_TRUE(beyond.RunUntil([&] { return beyond.channel->state() == ChannelState::kError; }));
  EXPECT_EQ(beyond.channel->error_number(), kMsgBlockSearch);
}

TEST(ChannelBlockSearch, ResetLeavesBlockSearchWithoutHandshake) {
  // 7: with the handshake enabled, a reset during the search leaves block search at once: it
  // does not wait for the PLC's FALSE, and the CNC clears both signals, so the next search
  // asks the PLC again and waits for its TRUE.
  Mill m(kSquare);
  m.channel->SetBlockSearchPlc(true, false);
  m.Search(testing::BlockNumberSearch(100));
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForPlcOn));
  m.channel->SetBlockSearchPlc(true, true);
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForPlcOff));
  for (int i = 0; i < 8; ++i) m.Tick();
  EXPECT_EQ(m.State(), BlockSearchState::kWaitForPlcOff);  // the PLC has not answered
  EXPECT_FALSE(m.channel->block_search().command);         // the NC asks it to switch off
  m.channel->Reset();  // the PLC still says TRUE
  for (int i = 0; i < 8; ++i) m.Tick();
  EXPECT_EQ(m.State(), BlockSearchState::kInactive);
  EXPECT_FALSE(m.channel->block_search().command);
  EXPECT_FALSE(m.channel->block_search().active());
  EXPECT_EQ(m.channel->state(), ChannelState::kIdle);
  EXPECT_FALSE(m.moved);
  // The next start asks again: command_r TRUE, and no search before the PLC's TRUE.
  m.Search(testing::BlockNumberSearch(100));
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_EQ(m.State(), BlockSearchState::kWaitForPlcOn);
  EXPECT_TRUE(m.channel->block_search().command);
  m.channel->SetBlockSearchPlc(true, true);
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForPlcOff));
  m.channel->SetBlockSearchPlc(true, false);
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour));
}

TEST(ChannelBlockSearch, G74InTheSkippedPartLeavesTheAxesWhereTheyWere) {
  // Section 8: G74 is left out during the search, so the axes stay where the program had them;
  // its values are the homing order (ISG), never positions: N30 and N40 go on from X20 Y30,
  // not from X1 Y2.
  Mill m(
      "%g74\n"
      "N10 G00 G90 X20 Y30 Z5\n"
      "N20 G74 X1 Y2\n"
      "N30 G01 Z-1 F500\n"
      "N40 X40\n"
      "M30\n");
  m.Search(testing::BlockNumberSearch(40));
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
  const BlockSearchStatus& st = m.channel->block_search();
  ASSERT_EQ(st.continue_position.size(), 3u);
  EXPECT_NEAR(st.continue_position[0], 20, 1e-9);
  EXPECT_NEAR(st.continue_position[1], 30, 1e-9);
  EXPECT_NEAR(st.continue_position[2], -1, 1e-9);
  m.channel->Start();
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForContinueContour));
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.Ended() || m.channel->state() == ChannelState::kError; }));
  EXPECT_TRUE(m.Ended()) << m.channel->error();
  EXPECT_NEAR(m.X(), 40, 1e-9);
  EXPECT_NEAR(m.Y(), 30, 1e-9);
  EXPECT_NEAR(m.Z(), -1, 1e-9);
}

TEST(ChannelBlockSearch, BreakpointBeforeTheContinuePositionIsAnError) {
  // 3.5: the breakpoint must lie after the continue position. At 15 mm it lies in N95, which
  // the search to N100 (20 mm) passes: the start is refused before any axis moves.
  Mill m(kSquareOneBlock, {2, 2, 0});
  BlockSearchParameters p = testing::BlockNumberSearch(100);
  p.breakpoint_position = 15 * 1e4;
  m.Search(p);
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kError || m.Ended(); }));
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgBlockSearch);
  EXPECT_THAT(m.channel->error(), HasSubstr("lies before the continue position"));
  EXPECT_THAT(m.channel->error(), HasSubstr("15.0000 mm"));
  EXPECT_FALSE(m.moved);
  // Inside the continue block, before the covered distance: refused too.
  Mill inside(kSquareOneBlock, {2, 2, 0});
  p = testing::BlockNumberSearch(100, 500);  // 25 mm
  p.breakpoint_position = 22 * 1e4;
  inside.Search(p);
  ASSERT_TRUE(inside.RunUntil([&] { return inside.channel->state() == ChannelState::kError; }));
  EXPECT_THAT(inside.channel->error(), HasSubstr("25.0000 mm"));
  EXPECT_FALSE(inside.moved);
}

TEST(ChannelBlockSearch, BreakpointAfterTheContinuePositionStopsThere) {
  // 3.5, figure 7: the search to N100 at 200 per mille (22 mm), then the breakpoint holds the
  // path once where it lies: in the rest of the continue block (25 mm, X7 Y12), or in a later
  // block (35 mm, N120 half way: X2 Y7).
  for (const auto& [mm, x, y] : {std::tuple{25.0, 7.0, 12.0}, {35.0, 2.0, 7.0}}) {
    SCOPED_TRACE(std::to_string(mm) + " mm");
    Mill m(kSquareOneBlock, {2, 2, 0});
    BlockSearchParameters p = testing::BlockNumberSearch(100, 200);
    p.breakpoint_position = mm * 1e4;
    m.Search(p);
    ASSERT_TRUE(m.ToContour()) << m.channel->error();
    EXPECT_NEAR(m.X(), 10, 1e-9);
    EXPECT_NEAR(m.Y(), 12, 1e-9);
    m.channel->Start();
    ASSERT_TRUE(m.RunUntil([&] {
      return m.channel->block_search().stop_conditions & stop_condition::kBreakpointStop ||
             m.Ended();
    }));
    EXPECT_FALSE(m.Ended());
    for (int i = 0; i < 400; ++i) m.Tick();
    EXPECT_NEAR(m.X(), x, 1e-9);
    EXPECT_NEAR(m.Y(), y, 1e-9);
    EXPECT_NEAR(m.channel->block_search().dist_prog_start, mm, 1e-9);
    EXPECT_EQ(m.State(), BlockSearchState::kWaitForContinueContour);
    m.channel->Start();
    ASSERT_TRUE(m.RunUntil([&] { return m.Ended(); }));
    EXPECT_NEAR(m.X(), 2, 1e-9);
    EXPECT_NEAR(m.Y(), 2, 1e-9);
  }
}

TEST(ChannelBlockSearch, BadParametersStopTheStart) {
  Mill m(kSquare);
  BlockSearchParameters p = testing::BlockNumberSearch(100);
  p.covered_distance = 1200;
  std::string error;
  EXPECT_FALSE(m.channel->SetBlockSearch(p, &error));
  EXPECT_THAT(error, HasSubstr("0.0 .. 1000.0"));
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.channel->state() == ChannelState::kError; }));
  EXPECT_EQ(m.channel->error_number(), kMsgBlockSearch);
  EXPECT_FALSE(m.moved);
}

}  // namespace
}  // namespace vmt::control::channel
