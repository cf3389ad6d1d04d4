// Block search through a spindle / rotary axis changeover (twincat-cnc-block-search-de.md 2,
// mtc200-c-axis.md 1.2, 2.3): the changeover of the skipped part runs as in a run (its request
// to the PLC and the PLC's acknowledgement), no axis moves, C counts from where the changeover
// found it (RebaseRotaryAxis), and the return to the contour takes C to its continue position
// in rotary axis mode. Compared with the uninterrupted run, block by block. The lathe of the
// headstock tests, section 3 (a separate C servo, drive 3), G54 shifting C by +30.
#include <gtest/gtest.h>

#include "tests/control/channel/block_search_steps.hpp"
#include "tests/control/channel/headstock_lathe.hpp"

namespace vmt::control::channel {
namespace {

using headstock_test::HeadstockMode;

// Turning, a changeover to rotary axis mode (C programmed), two blocks that interpolate X and C,
// M03 back to spindle mode, turning again.
constexpr const char* kProgram =
    "N1 G54 G90 G00 X50 Z10\n"
    "N2 M03 S100\n"
    "N3 G01 Z5 F600\n"
    "N4 M05\n"
    "N5 G00 C90\n"
    "N6 G01 X30 C-90 F3000\n"
    "N7 G01 X20 C-180\n"
    "N8 M03 S200\n"
    "N9 G01 Z0 F600\n"
    "N10 M05\n"
    "N11 RET\n";

struct Headstock : testing::BlockSearchSteps<headstock_test::Lathe> {
  explicit Headstock(const std::string& program = kProgram)
      : BlockSearchSteps(program, true, [](ChannelConfig& c) {
          c.zero_offsets.g54_to_g59[0] = {0, 0, 30};
        }) {
    at.feedback[0].position = 80;   // X
    at.feedback[1].position = 40;   // Z
    at.feedback[3].position = 200;  // where the C servo stands before the start
  }
  double X() const { return at.feedback[0].position; }
  double Z() const { return at.feedback[1].position; }
  double C() const { return at.feedback[3].position; }
};

/// The uninterrupted run in single blocks: (X, Z, C) at the end of each block, 1-based.
std::vector<std::array<double, 3>> RunBlockEnds(const std::string& program = kProgram) {
  Headstock m(program);
  m.channel->SetSingleBlock(true);
  std::vector<std::array<double, 3>> ends{{m.X(), m.Z(), m.C()}};
  for (int n = 0; n < 40 && m.channel->state() != ChannelState::kEnded; ++n) {
    m.Block(20);
    EXPECT_NE(m.channel->state(), ChannelState::kError) << m.channel->error();
    ends.push_back({m.X(), m.Z(), m.C()});
  }
  return ends;
}

TEST(ChannelBlockSearchHeadstock, ContinueInRotaryAxisModeChangesOverAndReturnsC) {
  const auto run = RunBlockEnds();
  Headstock m;
  m.Search(testing::BlockNumberSearch(7, 500));
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
  // The changeover ran during the search; no axis moved.
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  EXPECT_EQ(m.X(), 80);
  EXPECT_EQ(m.Z(), 40);
  EXPECT_EQ(m.C(), 200);
  // Halfway through N7, as the uninterrupted run has it: X and C interpolate linearly.
  const auto& st = m.channel->block_search();
  ASSERT_EQ(st.continue_position.size(), 3u);
  EXPECT_NEAR(st.continue_position[0], (run[6][0] + run[7][0]) / 2, 1e-9);
  EXPECT_NEAR(st.continue_position[2], (run[6][2] + run[7][2]) / 2, 1e-9);
  EXPECT_NEAR(st.continue_position[2], -135 + 30, 1e-9);  // program C-135, G54's +30
  m.channel->Start();
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForContinueContour)) << m.channel->error();
  m.Ticks(8);
  EXPECT_NEAR(m.X(), (run[6][0] + run[7][0]) / 2, 1e-9);
  EXPECT_NEAR(m.Z(), run[7][1], 1e-9);
  EXPECT_NEAR(m.C(), (run[6][2] + run[7][2]) / 2, 1e-9);  // the return took C there
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kSpindle);  // N8's changeover back ran
  EXPECT_NEAR(m.X(), run.back()[0], 1e-9);
  EXPECT_NEAR(m.Z(), run.back()[1], 1e-9);
}

TEST(ChannelBlockSearchHeadstock, ContinueAfterTheChangeoverBackIsInSpindleMode) {
  // Both changeovers run in the search; at the contour the spindle turns at N8's S200 and C,
  // not positioned in spindle mode, does not move with the return.
  const auto run = RunBlockEnds();
  Headstock m;
  m.Search(testing::BlockNumberSearch(9, 500));
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
  const double c_before = m.C();
  m.channel->Start();
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForContinueContour)) << m.channel->error();
  m.Ticks(8);
  EXPECT_NEAR(m.Drive2Velocity(), 200 * 6, 1e-9);
  EXPECT_NEAR(m.X(), run[9][0], 1e-9);
  EXPECT_NEAR(m.Z(), (run[8][1] + run[9][1]) / 2, 1e-9);
  EXPECT_EQ(m.C(), c_before);
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), run.back()[0], 1e-9);
  EXPECT_NEAR(m.Z(), run.back()[1], 1e-9);
}

TEST(ChannelBlockSearchHeadstock, TheSearchWaitsForThePlcsAcknowledgementOfTheChangeover) {
  Headstock m;
  m.acknowledge = false;
  m.Search(testing::BlockNumberSearch(7, 500));
  m.RunUntil([&] { return m.hs().busy(); }, 1);
  m.Ticks(2000);  // 0.5 s without ROTMOD_Q
  EXPECT_EQ(m.State(), BlockSearchState::kActive);
  EXPECT_TRUE(m.hs().busy());
  EXPECT_TRUE(m.channel->block_search().stop_conditions & stop_condition::kWaitTechnoAck);
  EXPECT_EQ(m.C(), 200);
  m.acknowledge = true;
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kRotary);
}

TEST(ChannelBlockSearchHeadstock, AnIncrementAfterTheChangeoverCountsFromWhereCStands) {
  // C-axis manual 1.2 / RebaseRotaryAxis: G91 C10 right after the changeover counts from where
  // the changeover found C; the search moved nothing, so that is where C stood before the start
  // (200, machine). The uninterrupted run counts from where its spindle stopped.
  const std::string program =
      "N1 G54 G90 G00 X50 Z10\n"
      "N2 G91 G01 C10 F3000\n"
      "N3 G01 X-10 C20\n"
      "N4 G90 X30\n"
      "N5 RET\n";
  Headstock m(program);
  m.Search(testing::BlockNumberSearch(3, 500));
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
  const auto& st = m.channel->block_search();
  ASSERT_EQ(st.continue_position.size(), 3u);
  EXPECT_NEAR(st.continue_position[2], 200 + 10 + 10, 1e-9);
  EXPECT_NEAR(st.continue_position[0], 45, 1e-9);
  ASSERT_TRUE(m.ToContour()) << m.channel->error();
  m.Ticks(8);
  EXPECT_NEAR(m.C(), 220, 1e-9);
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.C(), 230, 1e-9);  // the interpreter went on from the rebased C
  EXPECT_NEAR(m.X(), 30, 1e-9);
}

}  // namespace
}  // namespace vmt::control::channel
