// The purely modal G codes and a channel's start-up words: one table for the interpreter and
// the scene's `nc: initial:`.
#include "control/nc/modal_g_codes.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace vmt::control::nc {
namespace {

using ::testing::HasSubstr;

TEST(ModalGCodes, EachSelectsItsGroup) {
  ModalState m;
  EXPECT_TRUE(SetModalG(55, m));
  EXPECT_EQ(m.zero_offset, 55);
  EXPECT_TRUE(SetModalG(48, m));
  EXPECT_EQ(m.tool_length, ToolLength::kAdd);
  EXPECT_TRUE(SetModalG(16, m));
  EXPECT_TRUE(m.diameter);
  EXPECT_TRUE(SetModalG(95, m));
  EXPECT_TRUE(m.feed_per_revolution);
  EXPECT_TRUE(SetModalG(91, m));
  EXPECT_TRUE(m.incremental);
  EXPECT_TRUE(SetModalG(6, m));
  EXPECT_TRUE(m.low_lag);
  EXPECT_TRUE(SetModalG(17, m));
  EXPECT_EQ(m.plane, Plane::kXY);
  EXPECT_TRUE(SetModalG(42, m));
  EXPECT_EQ(m.compensation, Compensation::kRight);
  // Motions, transformations that need a position and one-block functions are not modal-only.
  for (int g : {0, 1, 4, 31, 32, 33, 74, 77, 92, 100, 60}) EXPECT_FALSE(SetModalG(g, m)) << g;
}

TEST(ModalGCodes, StartUpWordsSetTheChannelsInitialState) {
  ModalState m;
  for (const char* w : {"G54", "G48", "G16", "G95", "G06", "T12", "D3"})
    EXPECT_EQ(ApplyInitialWord(w, m), "") << w;
  EXPECT_EQ(m.zero_offset, 54);
  EXPECT_EQ(m.tool_length, ToolLength::kAdd);
  EXPECT_TRUE(m.diameter);
  EXPECT_TRUE(m.feed_per_revolution);
  EXPECT_TRUE(m.low_lag);
  EXPECT_EQ(m.tool, 12);
  EXPECT_EQ(m.correction, 3);
}

TEST(ModalGCodes, StartUpWordsThatCannotStartAChannelAreRefused) {
  ModalState m;
  EXPECT_THAT(ApplyInitialWord("G01", m), HasSubstr("expected a modal G code"));
  EXPECT_THAT(ApplyInitialWord("G41", m), HasSubstr("starts with a move"));
  EXPECT_THAT(ApplyInitialWord("T99999999999", m), HasSubstr("T99999999999: the number is too large"));
  EXPECT_THAT(ApplyInitialWord("T", m), HasSubstr("expected"));
  EXPECT_THAT(ApplyInitialWord("T-1", m), HasSubstr("expected"));
  EXPECT_THAT(ApplyInitialWord("G54.5", m), HasSubstr("expected"));
  EXPECT_THAT(ApplyInitialWord("X10", m), HasSubstr("expected"));
  EXPECT_THAT(ApplyInitialWord("", m), HasSubstr("expected"));
  EXPECT_EQ(m.zero_offset, 53);  // nothing refused was applied
  EXPECT_EQ(m.tool, 0);
}

}  // namespace
}  // namespace vmt::control::nc
