// #CAX TRACK's command and the C angle it gives a block (cax_track.hpp).

#include "control/channel/cax_track.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace vmt::control::channel {
namespace {

using ::testing::HasSubstr;

TEST(CaxTrack, ParsesBothSpellingsAndTheOptions) {
  // 4.2.2: the heading spells #CAX TRACK, the manual's program #CAXTRACK, options with a blank
  // and a comma; the programming manual writes NAME=value.
  std::string error;
  auto c = ParseCaxTrack("CAXTRACK ON [ANGLIMIT 3, OFFSET 0]", &error);
  ASSERT_TRUE(c);
  EXPECT_TRUE(c->on);
  EXPECT_EQ(c->anglimit_deg, 3);
  EXPECT_EQ(c->offset_deg, 0);
  c = ParseCaxTrack("CAX TRACK ON [ANGLIMIT=2.5 OFFSET=-90]", &error);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->anglimit_deg, 2.5);
  EXPECT_EQ(c->offset_deg, -90);
  c = ParseCaxTrack("cax track off", &error);
  ASSERT_TRUE(c);
  EXPECT_FALSE(c->on);
  EXPECT_TRUE(error.empty());
  EXPECT_EQ(ParseCaxTrack("BLOCKSEARCH LOCKED", &error), std::nullopt);
}

TEST(CaxTrack, RefusesWhatItDoesNotRun) {
  for (const char* text :
       {"CAX TRACK", "CAXTRACK ONE", "CAXTRACK ON [OPTALIGN 5]", "CAXTRACK OFF [ANGPOS 0]",
        "CAXTRACK ON [ANGLIMIT]", "CAXTRACK ON [ANGLIMIT 200]", "CAXTRACK ON ANGLIMIT 3"}) {
    std::string error;
    EXPECT_TRUE(ParseCaxTrack(text, &error).has_value()) << text;
    EXPECT_THAT(error, HasSubstr("#" + std::string(text))) << text;
  }
}

BlockMotion Line(double x0, double y0, double x1, double y1) {
  BlockMotion m;
  m.moves = true;
  m.start = {x0, y0, 0, 0};
  m.end = {x1, y1, 0, 0};
  m.length = std::hypot(x1 - x0, y1 - y0);
  return m;
}

TEST(CaxTrack, TheTangentTheShortWayRound) {
  CaxTrackCommand on{true, 3, 0};
  // N40 of the manual: from C45 along +X: beyond ANGLIMIT, C turns alone to 0.
  CaxTrackStep s = TrackStep(Line(10, 10, 20, 10), 0, 1, 45, on);
  EXPECT_TRUE(s.in_plane);
  EXPECT_TRUE(s.align);
  EXPECT_NEAR(s.start_deg, 0, 1e-12);
  EXPECT_NEAR(s.end_deg, 0, 1e-12);
  // N80 after N70 (180): -Y is -90, reached the short way, +90.
  s = TrackStep(Line(40, 10, 40, 0), 0, 1, 180, on);
  EXPECT_NEAR(s.end_deg, 270, 1e-12);
  // Within the limit: no C-only move.
  s = TrackStep(Line(0, 0, 10, 10 * std::tan(2 * std::numbers::pi / 180)), 0, 1, 0, on);
  EXPECT_FALSE(s.align);
  EXPECT_NEAR(s.end_deg, 2, 1e-9);
  // Out of the plane C stands.
  BlockMotion z = Line(0, 0, 0, 0);
  z.end[2] = 5;
  z.length = 5;
  s = TrackStep(z, 0, 1, 33, on);
  EXPECT_FALSE(s.in_plane);
  EXPECT_EQ(s.end_deg, 33);
}

}  // namespace
}  // namespace vmt::control::channel
