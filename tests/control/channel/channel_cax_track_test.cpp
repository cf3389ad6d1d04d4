// #CAX TRACK in the channel (cax_track.hpp): C follows the tangent of the path in a normal run,
// turning alone first where a corner exceeds ANGLIMIT; block search simulates the same, and the
// return to the contour aligns C to the tangent at the continue position before the other axes
// return (twincat-cnc-block-search-de.md 4.2.2, the manual's program word for word:
// tests/control/nc/seed_programs/blocksearch_cax_track.isg).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>
#include <tuple>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using ::testing::HasSubstr;

/// A coordinate in a program, to the last digit.
std::string Num(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::string ManualExample() {
  std::ifstream in(std::string(VMT_SOURCE_DIR) +
                   "/tests/control/nc/seed_programs/blocksearch_cax_track.isg");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_THAT(text.str(), HasSubstr("N40 X20"));
  return text.str();
}

/// X, Y, Z and C on an ideal machine (the drives follow their setpoints) in G17, no spindle.
struct CaxMill : test_support::IdealDriveBus {
  CaxMill(const std::string& program, std::array<double, 4> start) : IdealDriveBus(4) {
    parsed = nc::ParseProgram(program, "block-search-cax-track.isg", nc::Dialect::kIsg);
    EXPECT_TRUE(parsed.ok()) << nc::Format(parsed.errors[0], parsed.program.files);
    ChannelConfig config;
    config.axes = {testing::Axis("X", 0, 400), testing::Axis("Y", 1, 400),
                   testing::Axis("Z", 2, 400), testing::Axis("C", 3, 3600)};
    config.axes[3].rotary = true;
    config.spindle_drive = -1;
    config.initial.plane = nc::Plane::kXY;
    channel = std::make_unique<Channel>(config, std::vector<const nc::Program*>{&parsed.program});
    for (size_t d = 0; d < 4; ++d) {
      drives[d] = test_support::IdealDrive::Follow();
      at.feedback[d].position = start[d];
    }
  }
  void Tick() {
    channel->Tick(at, mdt);
    Answer();
  }
  bool Until(const std::function<bool()>& done, const std::function<void()>& each = {}) {
    for (int i = 0; i < 800000; ++i) {
      if (done()) return true;
      Tick();
      if (each) each();
    }
    return false;
  }
  bool Waits(BlockSearchState s, const std::function<void()>& each = {}) {
    return Until(
               [&] {
                 return channel->block_search().state == s ||
                        channel->state() == ChannelState::kError ||
                        channel->state() == ChannelState::kEnded;
               },
               each) &&
           channel->block_search().state == s;
  }
  /// Runs until the channel ends or fails; each tick's (X, Y, C).
  std::vector<std::array<double, 3>> RunToStop(const std::function<void()>& each = {}) {
    std::vector<std::array<double, 3>> path;
    Until(
        [&] {
          return channel->state() == ChannelState::kEnded ||
                 channel->state() == ChannelState::kError;
        },
        [&] {
          path.push_back({X(), Y(), C()});
          if (each) each();
        });
    return path;
  }
  /// Runs to the end; each tick's (X, Y, C).
  std::vector<std::array<double, 3>> RunToEnd(const std::function<void()>& each = {}) {
    auto path = RunToStop(each);
    EXPECT_EQ(channel->state(), ChannelState::kEnded) << channel->error();
    return path;
  }
  double X() const { return at.feedback[0].position; }
  double Y() const { return at.feedback[1].position; }
  double C() const { return at.feedback[3].position; }
  nc::ParseResult parsed;
  std::unique_ptr<Channel> channel;
};

TEST(ChannelCaxTrack, CFollowsTheTangentInANormalRun) {
  // The manual's program run through: C stands at each block's direction while the block
  // runs, 45 deg along N30, 0 along N40 and N60, 180 along N70, -90 along N80 (reached the
  // short way from 180, so C counts on to 270). Each corner exceeds ANGLIMIT 3: C turns while
  // X and Y stand, before the block moves.
  CaxMill m(ManualExample(), {0, 0, 0, 0});
  m.channel->Start();
  // While C turns alone before N40, N40 has not begun: 0 per mille, and the distance from
  // program start is N20's and N30's (4.1).
  bool turning_seen = false;
  const auto path = m.RunToEnd([&] {
    if (m.X() == 10 && m.Y() == 10 && m.C() > 1e-6 && m.C() < 45 - 1e-6) {
      turning_seen = true;
      EXPECT_EQ(m.channel->block_search().covered_distance, 0);
      EXPECT_NEAR(m.channel->block_search().dist_prog_start, 2 * std::hypot(5.0, 5.0), 1e-9);
    }
  });
  EXPECT_TRUE(turning_seen);
  bool n30 = false, n40 = false, n70 = false, n80 = false;
  for (size_t i = 1; i < path.size(); ++i) {
    const auto [x, y, c] = path[i];
    const auto [px, py, pc] = path[i - 1];
    const bool path_moves = x != px || y != py;
    if (c != pc && path_moves && px >= 5)
      ADD_FAILURE() << "C turned with the path at X" << x << " Y" << y;
    if (!path_moves) continue;
    if (x > 5 + 1e-9 && x < 10 - 1e-9 && std::abs(x - y) < 1e-9) {
      EXPECT_NEAR(c, 45, 1e-9);
      n30 = true;
    } else if (y == 10 && x > 10 + 1e-9 && x < 40 - 1e-9 && x > px) {
      EXPECT_NEAR(c, 0, 1e-9);
      n40 = true;
    } else if (y == 10 && x < px) {
      EXPECT_NEAR(c, 180, 1e-9);
      n70 = true;
    } else if (x == 30 && y < py) {
      EXPECT_NEAR(c, 270, 1e-9);
      n80 = true;
    }
  }
  EXPECT_TRUE(n30 && n40 && n70 && n80);
  EXPECT_NEAR(m.X(), 30, 1e-9);
  EXPECT_NEAR(m.Y(), 0, 1e-9);
  EXPECT_NEAR(m.C(), 270, 1e-9);  // -90 deg: tracking ends with N90, C stays
}

TEST(ChannelCaxTrack, ManualExampleReturnAlignsCToTheTangentAtN40) {
  // 4.2.2: search to N40 with tracking on; C turns first to N40's tangent, 0 deg (the manual's
  // example), while X and Y stand, then X and Y return in a straight line, then the run goes
  // on tracking. C starts at 90 deg so that the alignment is a move.
  CaxMill m(ManualExample(), {50, 50, 0, 90});
  BlockSearchParameters p;
  p.type = BlockSearchType::kBlockNumber;
  p.block_number = 40;
  p.auto_return = true;
  std::string error;
  ASSERT_TRUE(m.channel->SetBlockSearch(p, &error)) << error;
  m.channel->Start();
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
  const BlockSearchStatus& st = m.channel->block_search();
  ASSERT_EQ(st.continue_position.size(), 4u);
  EXPECT_NEAR(st.continue_position[0], 10, 1e-9);
  EXPECT_NEAR(st.continue_position[1], 10, 1e-9);
  EXPECT_NEAR(st.continue_position[3], 0, 1e-9);
  std::vector<std::array<double, 3>> path;
  m.channel->Start();
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForContinueContour, [&] {
    path.push_back({m.X(), m.Y(), m.C()});
  })) << m.channel->error();
  EXPECT_NEAR(m.X(), 10, 1e-9);
  EXPECT_NEAR(m.Y(), 10, 1e-9);
  EXPECT_NEAR(m.C(), 0, 1e-9);
  bool c_aligned = false;
  for (const auto& [x, y, c] : path) {
    if (!c_aligned) {
      EXPECT_EQ(x, 50);  // nothing but C moves before C is aligned
      EXPECT_EQ(y, 50);
      c_aligned = c == 0;
    } else {
      EXPECT_EQ(c, 0);                    // then C stands
      EXPECT_NEAR(x - 10, y - 10, 1e-9);  // and X and Y go straight (both 40 mm off)
    }
  }
  EXPECT_TRUE(c_aligned);
  // Tracking goes on: N70 turns C to 180, N80 to 270.
  m.channel->Start();
  const auto rest = m.RunToEnd();
  EXPECT_NEAR(m.C(), 270, 1e-9);
}

TEST(ChannelCaxTrack, WithoutTrackingCReturnsWithTheOtherAxes) {
  // Before #CAXTRACK ON (the first N20) and after #CAXTRACK OFF (N90): one straight move of
  // all axes, C included, ending together; at N90 C is where tracking left it (270).
  for (const auto& [number, x, y, c] : {std::tuple{20u, 0.0, 0.0, 0.0}, {90u, 30.0, 0.0, 270.0}}) {
    SCOPED_TRACE("N" + std::to_string(number));
    CaxMill m(ManualExample(), {50, 50, 0, 90});
    BlockSearchParameters p;
    p.type = BlockSearchType::kBlockNumber;
    p.block_number = number;
    p.auto_return = true;
    std::string error;
    ASSERT_TRUE(m.channel->SetBlockSearch(p, &error)) << error;
    m.channel->Start();
    ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
    std::vector<std::array<double, 3>> path;
    m.channel->Start();
    ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForContinueContour, [&] {
      path.push_back({m.X(), m.Y(), m.C()});
    }));
    EXPECT_NEAR(m.X(), x, 1e-9);
    EXPECT_NEAR(m.Y(), y, 1e-9);
    EXPECT_NEAR(m.C(), c, 1e-9);
    bool together = false;  // C and X both between start and end at some tick
    for (const auto& q : path)
      together = together || (q[0] != 50 && q[0] != x && q[2] != 90 && q[2] != c);
    EXPECT_TRUE(together);
  }
}

TEST(ChannelCaxTrack, WithinAnglimitCTurnsAlongWithTheBlock) {
  // A bend of 2 deg under ANGLIMIT 3: no C-only move, C turns from 0 to 2 deg while the block
  // runs (half way at mid-block). A bend of 10 deg: C turns first, then the block runs at 10.
  const double rise = 10 * std::tan(2 * std::numbers::pi / 180);
  CaxMill m(
      "N10 G01 G90 X0 Y0 C0 F3000\n"
      "N20 #CAX TRACK ON [ANGLIMIT=3 OFFSET=0]\n"
      "N30 X10\n"
      "N40 X20 Y" +
          Num(rise) +
          "\n"
          "N50 #CAX TRACK OFF\n"
          "M30\n",
      {0, 0, 0, 0});
  m.channel->Start();
  const auto path = m.RunToEnd();
  bool mid = false;
  for (size_t i = 1; i < path.size(); ++i) {
    const auto [x, y, c] = path[i];
    if (c != path[i - 1][2]) {
      EXPECT_NE(x, path[i - 1][0]) << "C turned alone at X" << x;
    }
    if (x > 10 && std::abs(x - 15) < 0.05) {
      EXPECT_NEAR(c, (x - 10) / 10 * 2, 0.02);
      mid = true;
    }
  }
  EXPECT_TRUE(mid);
  EXPECT_NEAR(m.C(), 2, 1e-6);

  CaxMill sharp(
      "N10 G01 G90 X0 Y0 C0 F3000\n"
      "N20 #CAX TRACK ON [ANGLIMIT 3]\n"
      "N30 X10\n"
      "N40 X20 Y" +
          Num(10 * std::tan(10 * std::numbers::pi / 180)) +
          "\n"
          "M30\n",
      {0, 0, 0, 0});
  sharp.channel->Start();
  const auto sharp_path = sharp.RunToEnd();
  for (size_t i = 1; i < sharp_path.size(); ++i)
    if (sharp_path[i][0] > 10 + 1e-9) {
      EXPECT_NEAR(sharp_path[i][2], 10, 1e-6);
    }
}

TEST(ChannelCaxTrack, CFollowsAnArcAndTheOffset) {
  // A half circle G03 from X10 Y0 about X0 Y0 to X-10 Y0: its tangent turns from 90 to 270
  // deg, C with it at every point (the angle of the radius + 90), plus OFFSET 30.
  CaxMill m(
      "N10 G01 G90 X10 Y0 C120 F3000\n"
      "N20 #CAX TRACK ON [ANGLIMIT 3, OFFSET 30]\n"
      "N30 G03 X-10 Y0 I-10 J0\n"
      "N40 #CAX TRACK OFF\n"
      "M30\n",
      {10, 0, 0, 120});
  m.channel->Start();
  const auto path = m.RunToEnd();
  int on_arc = 0;
  for (const auto& [x, y, c] : path) {
    if (y <= 1e-6) continue;
    const double radius_deg = std::atan2(y, x) * 180 / std::numbers::pi;
    EXPECT_NEAR(c, radius_deg + 90 + 30, 1e-6) << "X" << x << " Y" << y;
    ++on_arc;
  }
  EXPECT_GT(on_arc, 100);
  EXPECT_NEAR(m.C(), 300, 1e-9);
}

TEST(ChannelCaxTrack, ProgrammedCAndUnknownOptionsAreErrors) {
  // While tracking is on C is the tracking's: a block that programs it is refused.
  CaxMill programmed(
      "N10 G01 G90 X0 Y0 F3000\n"
      "N20 #CAX TRACK ON\n"
      "N30 X10 C20\n"
      "M30\n",
      {0, 0, 0, 0});
  programmed.channel->Start();
  programmed.RunToStop();
  EXPECT_EQ(programmed.channel->state(), ChannelState::kError);
  EXPECT_THAT(programmed.channel->error(), HasSubstr(":3:"));
  EXPECT_THAT(programmed.channel->error(), HasSubstr("cannot program it"));
  // An option vmt does not run is an error at its word, never passed over.
  CaxMill option(
      "N10 G01 G90 X0 Y0 F3000\n"
      "N20 #CAX TRACK ON [OPTALIGN 5]\n"
      "M30\n",
      {0, 0, 0, 0});
  option.channel->Start();
  option.RunToStop();
  EXPECT_EQ(option.channel->state(), ChannelState::kError);
  EXPECT_THAT(option.channel->error(), HasSubstr(":2:"));
  EXPECT_THAT(option.channel->error(), HasSubstr("OPTALIGN"));
}

}  // namespace
}  // namespace vmt::control::channel
