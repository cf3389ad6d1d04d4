// The manual return through a JogOfPath channel (twincat-cnc-block-search-de.md 4.2.1): the PLC
// lends the block search channel's axes to a second channel (HLI.channel.SuspendAxisOutput),
// which runs its own approach program while the search decodes; the automatic return then
// moves only the rest of the way. The axes change hands at standstill only, without a step of
// their setpoints, and the JogOfPath channel's moves are checked by PathGuard.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "block_search_steps.hpp"
#include "channel_test_support.hpp"
#include "control/channel/jog_of_path.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

/// The ideal machine of channel_test_support.hpp with a JogOfPath channel running
/// `manual_return`, both ticked as vmt's runner ticks them: the axes handed over each NC cycle,
/// the channel holding them writing their setpoints last.
struct JogOfPathMachine : Machine {
  JogOfPathMachine(const std::string& program, const std::string& manual_return)
      : Machine(program) {
    manual = nc::ParseProgram(manual_return, "return.mtc", nc::Dialect::kMtc200);
    EXPECT_TRUE(manual.ok());
    jog_of_path = std::make_unique<Channel>(JogOfPathConfig(channel_config),
                                            std::vector<const nc::Program*>{&manual.program});
  }
  void Tick() {
    if (ticks++ % channel_config.ticks_per_cycle == 0) HandOverAxes(*channel, *jog_of_path);
    const bool holds = !jog_of_path->output_suspended();
    if (!holds) jog_of_path->Tick(at, mdt);
    channel->Tick(at, mdt);
    if (holds) jog_of_path->Tick(at, mdt);
    for (int d = 0; d < 2; ++d)
      if (mdt.setpoints[d].mode == DriveMode::kPosition && ticks > 1)
        largest_step =
            std::max(largest_step, std::abs(mdt.setpoints[d].value - at.feedback[d].position));
    Answer();
    t += 250e-6;
  }
  void RunFor(double s) {
    for (int i = 0; i < s / 250e-6; ++i) Tick();
  }
  nc::ParseResult manual;
  std::unique_ptr<Channel> jog_of_path;
  int64_t ticks = 0;
  double largest_step = 0;  ///< mm: the largest change of a setpoint between two ticks
};
using Rig = BlockSearchSteps<JogOfPathMachine>;

// X to 100, Z to -50, X back to 0; the search continues N3 half way, at X50 Z-50.
const char kProgram[] = "N1 G01 X100 F6000\nN2 G01 Z-50\nN3 G01 X0\nN4 RET\n";
const char kManualReturn[] = "N10 G00 Z-40\nN20 X40\nN30 RET\n";

// 4.2.1's sequence: axes to the JogOfPath channel, the search started, the manual return run
// meanwhile, the axes back, the automatic return of the rest, machining on.
TEST(ChannelJogOfPath, TheManualReturnRunsWhileTheSearchDecodesTheAutomaticOneDoesTheRest) {
  Rig m(kProgram, kManualReturn);
  m.channel->SetSuspendOutput(true);
  m.RunFor(0.01);
  EXPECT_TRUE(m.channel->output_suspended());
  EXPECT_FALSE(m.jog_of_path->output_suspended());
  m.Search(BlockNumberSearch(3, 500));  // N3 half way: X50 Z-50
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
  EXPECT_EQ(m.X(), 0);  // the search moved nothing
  m.jog_of_path->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.jog_of_path->state() != ChannelState::kRunning; }));
  EXPECT_EQ(m.jog_of_path->state(), ChannelState::kEnded) << m.jog_of_path->error();
  EXPECT_NEAR(m.X(), 40, 1e-9);
  EXPECT_NEAR(m.Z(), -40, 1e-9);
  // The start of the return while the axes are lent: it waits for them.
  m.channel->Start();
  m.RunFor(0.5);
  EXPECT_EQ(m.State(), BlockSearchState::kWaitReturnToContour);
  EXPECT_NEAR(m.X(), 40, 1e-9);
  m.channel->SetSuspendOutput(false);
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForContinueContour)) << m.channel->error();
  EXPECT_FALSE(m.channel->output_suspended());
  EXPECT_TRUE(m.jog_of_path->output_suspended());
  EXPECT_NEAR(m.X(), 50, 1e-9);  // the rest of the way, to the continue position
  EXPECT_NEAR(m.Z(), -50, 1e-9);
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.Ended(); })) << m.channel->error();
  EXPECT_NEAR(m.X(), 0, 1e-9);
  // No setpoint jumped at either hand-over: at most a tick at the rapid (400 mm/s).
  EXPECT_LE(m.largest_step, 400 * 250e-6 + 1e-9);
}

// "grundsätzlich im Stillstand der Achsen": the channel lets its axes go only when they stand,
// and gets them back only when the JogOfPath channel's stand.
TEST(ChannelJogOfPath, TheAxesChangeHandsAtStandstillOnly) {
  Rig m("N1 G01 X100 F600\nN2 RET\n", "N10 G01 Z20 F600\nN20 RET\n");
  m.channel->Start();
  m.RunFor(1.0);
  m.channel->SetSuspendOutput(true);
  m.RunFor(0.5);
  EXPECT_FALSE(m.channel->output_suspended());  // still moving
  EXPECT_TRUE(m.jog_of_path->output_suspended());
  m.channel->Stop();
  m.RunFor(0.1);
  EXPECT_TRUE(m.channel->output_suspended());  // held: at rest
  EXPECT_FALSE(m.jog_of_path->output_suspended());
  const double x = m.X();
  m.jog_of_path->Start();
  m.RunFor(0.5);
  m.channel->SetSuspendOutput(false);
  m.RunFor(0.5);
  EXPECT_TRUE(m.channel->output_suspended());  // the JogOfPath channel's Z still moves
  EXPECT_FALSE(m.jog_of_path->output_suspended());
  ASSERT_TRUE(m.RunUntil([&] { return m.jog_of_path->state() == ChannelState::kEnded; }));
  m.RunFor(0.01);
  EXPECT_FALSE(m.channel->output_suspended());
  EXPECT_TRUE(m.jog_of_path->output_suspended());
  EXPECT_EQ(m.X(), x);
  EXPECT_NEAR(m.Z(), 20, 1e-9);
  EXPECT_LE(m.largest_step, 400 * 250e-6 + 1e-9);
  // The held program's axes were moved off its path: as after jogging in manual mode, a start
  // does not jump back to it.
  m.channel->Start();
  m.RunFor(0.1);
  EXPECT_EQ(m.channel->error_number(), kMsgLeftContour);
  EXPECT_NEAR(m.Z(), 20, 1e-9);
}

/// Z may not go below 5 while X is below 30 (a shoulder).
struct Shoulder : PathGuard {
  PathCheck CheckMove(const std::vector<double>& from, const std::vector<double>& to) override {
    ++checks;
    PathCheck c;
    c.min_clearance = 1;
    if (!(to[1] < 5 && std::min(from[0], to[0]) < 30)) return c;
    c.clear = false;
    c.part_a = "tool", c.part_b = "shoulder";
    c.position = from;
    c.min_clearance = 0;
    return c;
  }
  int checks = 0;
};

// The JogOfPath channel's moves are approach moves: each is checked before it starts, and one
// that would collide is refused with the JogOfPath channel's error; the axes stay where they are.
TEST(ChannelJogOfPath, PathGuardChecksTheManualReturnsMoves) {
  Rig m(kProgram, "N10 G00 Z10\nN20 X20\nN30 G01 Z0 F1000\nN40 RET\n");
  Shoulder guard;
  m.jog_of_path->SetPathGuard(&guard);
  m.channel->SetSuspendOutput(true);
  m.RunFor(0.01);
  m.jog_of_path->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.jog_of_path->state() != ChannelState::kRunning; }));
  EXPECT_EQ(m.jog_of_path->error_number(), kMsgCollision);
  EXPECT_THAT(m.jog_of_path->error(), ::testing::HasSubstr("collision ahead (JogOfPath)"));
  EXPECT_NEAR(m.X(), 20, 1e-9);
  EXPECT_NEAR(m.Z(), 10, 1e-9);
  const auto records = m.jog_of_path->TakeGuardRecords();
  ASSERT_EQ(records.size(), 3u);
  EXPECT_EQ(records[0].move, "JogOfPath");
  EXPECT_TRUE(records[2].stopped);
  EXPECT_EQ(m.channel->state(), ChannelState::kIdle);  // the block search channel untouched
}

// Without the PLC's request nothing is lent: the JogOfPath channel's program waits at its
// first move, and the block search channel moves as ever.
TEST(ChannelJogOfPath, WithoutTheRequestTheJogOfPathChannelMovesNothing) {
  Rig m("N1 G01 X10 F6000\nN2 RET\n", kManualReturn);
  m.jog_of_path->Start();
  m.RunFor(0.5);
  EXPECT_EQ(m.Z(), 0);
  EXPECT_TRUE(m.jog_of_path->output_suspended());
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.Ended(); }));
  EXPECT_NEAR(m.X(), 10, 1e-9);
  EXPECT_EQ(m.Z(), 0);
}

// The JogOfPath channel has the feed axes only: not the headstock's C, which rides on the
// spindle, and with C the column of C goes from the zero offsets and the tool lengths.
TEST(ChannelJogOfPath, ItsAxesAreTheFeedAxesWithoutTheHeadstocksC) {
  ChannelConfig c;
  c.axes = {Axis("X", 0, 400), Axis("C", 3, 360), Axis("Z", 1, 500)};
  c.spindle_drive = 2;
  c.headstock = axes::HeadstockConfig{};
  c.rotary_axis = 1;
  c.zero_offsets.g54_to_g59[0] = {1, 2, 3};
  c.tools.edges.push_back({.tool = 1, .edge = 1, .length = {10, 20, 30}});
  const ChannelConfig j = JogOfPathConfig(c);
  ASSERT_EQ(j.axes.size(), 2u);
  EXPECT_EQ(j.axes[0].name, "X");
  EXPECT_EQ(j.axes[1].name, "Z");
  EXPECT_EQ(j.zero_offsets.g54_to_g59[0], (std::vector<double>{1, 3}));
  EXPECT_EQ(j.tools.edges[0].length, (std::vector<double>{10, 30}));
  EXPECT_FALSE(j.headstock);
  EXPECT_EQ(j.rotary_axis, -1);
  EXPECT_EQ(j.spindle_drive, -1);
  EXPECT_TRUE(j.output_suspended_at_start);
  EXPECT_TRUE(j.approach_program);
}

}  // namespace
}  // namespace vmt::control::channel
