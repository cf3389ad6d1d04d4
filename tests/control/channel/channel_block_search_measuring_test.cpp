// Block search through measuring instructions (twincat-cnc-block-search-de.md 2 and 8,
// mtc200-fast-measurement.md 2.1): the search cannot measure without motion. SETTING runs as in
// a run (its Q function to the PLC), PROBE is simulated as its programmed path without
// measuring (its page keeps its former value, a warning names the block), and a continue
// position in a measuring block is refused. The MeasuringLathe of the measuring tests.
#include <gtest/gtest.h>

#include <algorithm>

#include "tests/control/channel/block_search_steps.hpp"
#include "tests/control/channel/measuring_lathe.hpp"

namespace vmt::control::channel::testing {
namespace {

// 5.2 example 1's P1 with escape (the stylus back at its start), then an increment from there.
constexpr const char* kProgram =
    "N1 SETTING(X,Z,,18,48,15,1)\n"
    "N2 PROBE(1,1,30,5,,X,-2,100,1,1,0)\n"
    "N3 G91 G01 X4 Z-2 F600\n"
    "N4 G90 G01 X60 F600\n"
    "N5 RET\n";

struct Search {
  explicit Search(uint32_t block, int permille = 500) : l(kProgram, 30.0) {
    std::string error;
    EXPECT_TRUE(l.m.channel->SetBlockSearch(testing::BlockNumberSearch(block, permille), &error))
        << error;
    l.m.channel->Start();
  }
  bool Waits(BlockSearchState s) {
    for (int i = 0; i < 400000; ++i) {
      if (l.m.channel->block_search().state == s) return true;
      if (l.m.channel->state() == ChannelState::kError ||
          l.m.channel->state() == ChannelState::kEnded)
        return false;
      l.Tick();
    }
    return false;
  }
  MeasuringLathe l;
};

TEST(ChannelBlockSearchMeasuring, ProbeBeforeTheContinuePositionIsSimulatedWithoutMeasuring) {
  // The uninterrupted run: PROBE measures and escapes to X50 Z5; N3 goes on from there.
  MeasuringLathe run(kProgram, 30.0);
  run.m.channel->SetSingleBlock(true);
  std::vector<std::array<double, 2>> ends;
  for (int n = 0; n < 3; ++n) {
    run.m.channel->Start();
    run.RunUntilStopped();
    for (int i = 0; i < 8; ++i) run.Tick();  // the drives reach the last fine point
    ends.push_back({run.m.X(), run.m.Z()});
  }
  ASSERT_NE(run.pages.Point(0, 1), nullptr);
  EXPECT_NEAR(run.pages.Point(0, 1)->value.actual, 30, 1e-9);

  Search s(3);
  // A former measurement of P1 (0.1 mm undersize) on the page.
  measure::PointPage* page = s.l.pages.Point(0, 1);
  ASSERT_NE(page, nullptr);
  page->value.command = 30;
  page->value.actual = 29.9;
  page->measuring_axis = 'X';
  ASSERT_TRUE(s.Waits(BlockSearchState::kWaitReturnToContour)) << s.l.m.channel->error();
  // Nothing measured, nothing written, the measuring block's events never set.
  EXPECT_EQ(s.l.pages.Point(0, 1)->value.actual, 29.9);
  EXPECT_EQ(std::find(s.l.raised.begin(), s.l.raised.end(), 30), s.l.raised.end());
  // SETTING ran as in a run: its setting and its Q9992 to the PLC.
  ASSERT_TRUE(s.l.m.channel->measuring_setting());
  ASSERT_FALSE(s.l.q_functions.empty());
  EXPECT_EQ(s.l.q_functions.front(), 9992);
  // The operator is told.
  const auto& st = s.l.m.channel->block_search();
  ASSERT_EQ(st.warnings.size(), 1u);
  EXPECT_NE(st.warnings[0].find("p.mtc:2:"), std::string::npos) << st.warnings[0];
  EXPECT_NE(st.warnings[0].find("PROBE simulated without measuring"), std::string::npos);
  // The increment counts from where the PROBE's path ends, as in the run: halfway through N3.
  ASSERT_EQ(st.continue_position.size(), 2u);
  EXPECT_NEAR(st.continue_position[0], (ends[1][0] + ends[2][0]) / 2, 1e-9);
  EXPECT_NEAR(st.continue_position[1], (ends[1][1] + ends[2][1]) / 2, 1e-9);
  s.l.m.channel->Start();
  ASSERT_TRUE(s.Waits(BlockSearchState::kWaitForContinueContour)) << s.l.m.channel->error();
  s.l.m.channel->Start();
  s.l.RunUntilStopped();
  ASSERT_EQ(s.l.m.channel->state(), ChannelState::kEnded) << s.l.m.channel->error();
  EXPECT_NEAR(s.l.m.X(), 60, 1e-9);
  EXPECT_NEAR(s.l.m.Z(), ends[2][1], 1e-9);
  EXPECT_EQ(s.l.pages.Point(0, 1)->value.actual, 29.9);  // still the former value
}

TEST(ChannelBlockSearchMeasuring, ContinuePositionInAMeasuringBlockIsRefused) {
  Search s(2, 0);
  for (int i = 0; i < 4000 && s.l.m.channel->state() != ChannelState::kError; ++i) s.l.Tick();
  ASSERT_EQ(s.l.m.channel->state(), ChannelState::kError);
  EXPECT_NE(s.l.m.channel->error().find("p.mtc:2:"), std::string::npos) << s.l.m.channel->error();
  EXPECT_NE(s.l.m.channel->error().find("continue position lies in measuring instruction PROBE"),
            std::string::npos)
      << s.l.m.channel->error();
  EXPECT_EQ(s.l.m.X(), 50);  // nothing moved
  EXPECT_EQ(s.l.m.Z(), 5);
}

}  // namespace
}  // namespace vmt::control::channel::testing
