// The rotary axis' position across changeovers in the channel (C-axis manual 1.2, 2.3): block
// preparation waits until the changeover ends, and rotary axis mode starts where the spindle
// stopped, in program coordinates with the rotary axis' zero offsets back; the position
// indication shows 0..360. On a main spindle with rotary axis capability (section 2: C on the
// spindle's drive), an ideal drive (position: actual = command; velocity: the speed at once) and
// a PLC that acknowledges every changeover at once.

#include <gtest/gtest.h>

#include "headstock_lathe.hpp"

namespace vmt::control::channel {
namespace {

using headstock_test::HeadstockMode;

// The section 2 lathe of the operating-state tests (C on S1's drive 2), G54 shifting C by +30.
struct Headstock : headstock_test::Lathe {
  explicit Headstock(const std::string& program)
      : Lathe(program, false, [](ChannelConfig& c) {
          c.zero_offsets.g54_to_g59[0] = {0, 0, 30};
        }) {}
  // Single block: starts the next block and runs it to its end (the channel holds after it).
  void Step() { Block(20); }
};

// C-axis manual 1.2 and 2.3: after M3 / M5 the spindle stands somewhere the program does not
// know; G91 C10 right after the changeover counts from there, in program coordinates with G54's
// C offset (re-activated by rotary axis mode), and so does the interpreter for the next blocks.
TEST(ChannelHeadstockPositions, IncrementAfterChangeoverStartsWhereTheSpindleStopped) {
  Headstock m(
      "N1 G54 G90 G01 C10 F36000\n"
      "N2 M03 S100\n"
      "N3 G04 F0.37\n"
      "N4 M05\n"
      "N5 G91 G01 C10 F3600\n"
      "N6 C-5\n"
      "N7 G90 C0\n"
      "N8 G91 C-20\n"
      "N9 RET\n");
  m.channel->SetSingleBlock(true);
  for (int block = 1; block <= 4; ++block) m.Step();
  // 100 rpm for 0.37 s after C10 (machine 40): the spindle stopped near 40 + 222 = 262 deg.
  const double stopped = m.at.feedback[2].position;
  EXPECT_NEAR(stopped, 262, 5);
  m.Step();
  EXPECT_EQ(m.channel->headstock()->mode(), HeadstockMode::kRotary);
  EXPECT_NEAR(m.channel->position(2), stopped + 10, 1e-9);
  EXPECT_NEAR(m.channel->HeadstockPosition(), stopped + 10 - 30, 1e-9);  // program coordinates
  m.Step();
  EXPECT_NEAR(m.channel->position(2), stopped + 5, 1e-9);
  m.Step();
  EXPECT_NEAR(m.channel->position(2), 30, 1e-9);  // G90 C0 with G54's +30
  m.Step();
  EXPECT_NEAR(m.channel->position(2), 10, 1e-9);
  EXPECT_NEAR(m.at.feedback[2].position, 10, 1e-9);
  m.Step();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
}

// 2.3 Position Indication: C in the representation of a rotary axis, 0..360, though the
// program runs it past a turn (the manual's C-270, 1.2).
TEST(ChannelHeadstockPositions, IndicationShowsZeroToThreeSixty) {
  Headstock m("N1 G54 G90 G01 C-270 F72000\nN2 G04 F0.1\nN3 G53 C-400\nN4 RET\n");
  m.channel->SetSingleBlock(true);
  m.Step();
  EXPECT_EQ(m.channel->HeadstockAxisName(), "C");
  EXPECT_NEAR(m.channel->position(2), -240, 1e-9);        // machine: G54's +30
  EXPECT_NEAR(m.channel->HeadstockPosition(), 90, 1e-9);  // -270 in program coordinates
  m.Step();
  m.Step();
  EXPECT_NEAR(m.channel->position(2), -400, 1e-9);
  EXPECT_NEAR(m.channel->HeadstockPosition(), 320, 1e-9);
  m.Step();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
}

}  // namespace
}  // namespace vmt::control::channel
