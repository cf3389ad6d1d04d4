// Which drives the channel writes: none before its first start, then each of its own (feed
// axes, main spindle, further spindles) and never another's, so that the scene's timeline
// writes the rest.

#include <gtest/gtest.h>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

TEST(ChannelDrivesTest, TheChannelWritesItsDrivesFromItsStartOn) {
  constexpr int kS2 = 3, kOther = 4;
  Machine m("N1 G01 X10 F600\nN2 RET\n", 0, 0, [](ChannelConfig& c) {
    c.spindles = {{2, kS2, "S2"}};
  });
  for (size_t d = 0; d <= kOther; ++d) EXPECT_FALSE(m.channel->WritesDrive(d)) << d;
  for (size_t d = 0; d <= kS2; ++d) EXPECT_TRUE(m.channel->MayWriteDrive(d)) << d;
  EXPECT_FALSE(m.channel->MayWriteDrive(kOther));
  m.channel->Start();
  // The start is taken at the next tick, which writes them: the channel owns them already.
  for (size_t d = 0; d <= kS2; ++d) EXPECT_TRUE(m.channel->WritesDrive(d)) << d;
  EXPECT_FALSE(m.channel->WritesDrive(kOther));
}

TEST(ChannelDrivesTest, ItKeepsWritingThemAfterTheProgramEnds) {
  Machine m("N1 G01 X10 F600\nN2 RET\n");
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  for (size_t d = 0; d < 3; ++d) EXPECT_TRUE(m.channel->WritesDrive(d)) << d;
  // It holds the axis where the program left it.
  EXPECT_EQ(m.mdt.setpoints[0].mode, DriveMode::kPosition);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[0].value, 10);
}

}  // namespace
}  // namespace vmt::control::channel
