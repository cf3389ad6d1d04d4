// A channel is a value: a copy taken at any NC cycle, given the same inputs, runs on bit for bit
// as the original does, and the two share nothing that changes (the interpreter's variables and
// callbacks, the tool list TLD writes, look-ahead and tool radius compensation included).

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

// A loop over @ variables (the interpreter's variable cache), TLD writes (its data access into
// the channel's tool list), an event the program sets and tests (its event source), feed moves
// blended by the look-ahead, G42 with an arc, a dwell and the spindle.
const char* const kProgram =
    "N10 G54 G00 X20 Z10 M03 S500\n"
    "N20 @1 = 0\n"
    ".LOOP\n"
    "N30 @1 = @1 + 1\n"
    "N40 @2 = 20 - @1\n"
    "N50 @4 = 0 - @1\n"
    "N60 G01 X@2 Z@4 F3000\n"
    "N70 TLD(1,2,,1,11,) = TLD(1,2,,1,11,) + 0.01\n"
    "N80 @3 = @1 - 5\n"
    "N90 BLT .LOOP\n"
    "N100 SE 29\n"
    "N110 BES .SET 29\n"
    "N120 G00 X50\n"
    ".SET\n"
    "N130 G42 T1 D1 G01 X30 Z0 F6000\n"
    "N140 Z-20\n"
    "N150 G02 X35 Z-25 I5 K0\n"
    "N160 G01 X40\n"
    "N170 G40 G00 X60 Z20 M05\n"
    "N180 G04 F0.05\n"
    "N190 G48 T2 D1 G00 X10 Z5\n"
    "N200 RET\n";

/// A channel on its own ideal bus; the program store stays in the Machine it was made from.
struct ChannelRun {
  test_support::IdealDriveBus bus;
  Channel channel;
  void Tick() {
    channel.Tick(bus.at, bus.mdt);
    bus.Answer();
  }
  bool Running() const {
    return channel.state() != ChannelState::kEnded && channel.state() != ChannelState::kError;
  }
};

ChannelRun Copy(const Machine& m) {
  return {static_cast<const test_support::IdealDriveBus&>(m), *m.channel};
}

uint64_t Bits(double v) { return std::bit_cast<uint64_t>(v); }

/// What a channel gives out after a tick: the telegram it wrote and what it shows.
struct Outputs {
  MasterTelegram mdt;
  ChannelState state = ChannelState::kIdle;
  std::string error;
  uint32_t line = 0, aux_strobe = 0;
  bool holds = false;
  std::vector<double> positions, translations;
  double programmed_rpm = 0;
};

Outputs Of(const MasterTelegram& mdt, const Channel& c) {
  Outputs o{mdt,
            c.state(),
            c.error(),
            c.line(),
            c.aux_strobe(),
            c.holds_positions(),
            {},
            {},
            c.spindle_status().programmed_rpm};
  for (size_t axis = 0; axis < 2; ++axis) {
    o.positions.push_back(c.position(axis));
    o.translations.push_back(c.Translation(axis));
  }
  return o;
}
Outputs Of(const ChannelRun& r) { return Of(r.bus.mdt, r.channel); }

/// Every output of two runs after the same tick, compared bit for bit.
void ExpectSame(const Outputs& a, const Outputs& b, int tick) {
  SCOPED_TRACE("tick " + std::to_string(tick));
  ASSERT_EQ(a.mdt.setpoints.size(), b.mdt.setpoints.size());
  for (size_t d = 0; d < a.mdt.setpoints.size(); ++d) {
    const DriveSetpoint& x = a.mdt.setpoints[d];
    const DriveSetpoint& y = b.mdt.setpoints[d];
    ASSERT_EQ(x.mode, y.mode) << "drive " << d;
    ASSERT_EQ(Bits(x.value), Bits(y.value)) << "drive " << d;
    ASSERT_EQ(Bits(x.velocity_feedforward), Bits(y.velocity_feedforward)) << "drive " << d;
    ASSERT_EQ(x.parameter_set, y.parameter_set) << "drive " << d;
    ASSERT_EQ(x.interpolated, y.interpolated) << "drive " << d;
    ASSERT_EQ(x.probe.probe_cycle_command, y.probe.probe_cycle_command) << "drive " << d;
    ASSERT_EQ(x.probe.probe_control_parameter, y.probe.probe_control_parameter) << "drive " << d;
  }
  ASSERT_EQ(a.mdt.outputs, b.mdt.outputs);
  ASSERT_EQ(a.state, b.state);
  ASSERT_EQ(a.error, b.error);
  ASSERT_EQ(a.line, b.line);
  ASSERT_EQ(a.aux_strobe, b.aux_strobe);
  ASSERT_EQ(a.holds, b.holds);
  for (size_t axis = 0; axis < a.positions.size(); ++axis) {
    ASSERT_EQ(Bits(a.positions[axis]), Bits(b.positions[axis])) << "axis " << axis;
    ASSERT_EQ(Bits(a.translations[axis]), Bits(b.translations[axis])) << "axis " << axis;
  }
  ASSERT_EQ(Bits(a.programmed_rpm), Bits(b.programmed_rpm));
}

/// The run that is never copied: what every copy must reproduce, tick for tick.
std::vector<Outputs> Reference() {
  Machine m(kProgram, 0, 0, WithOffsetsAndTools);
  m.channel->Start();
  std::vector<Outputs> after;  // after each tick
  while (m.channel->state() != ChannelState::kEnded && m.channel->state() != ChannelState::kError &&
         m.t < 30) {
    m.Tick();
    after.push_back(Of(m.mdt, *m.channel));
  }
  return after;
}

TEST(ChannelCopyTest, TheProgramRunsToItsEnd) {
  Machine m(kProgram, 0, 0, WithOffsetsAndTools);
  m.channel->Start();
  m.RunUntilEnd(30);
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  // G54 (X+5, Z+100), G48 with T2 D1, whose wear L1 (along Z) the loop raised five times.
  EXPECT_NEAR(m.X(), 5 + 10 - 1.5, 1e-9);
  EXPECT_NEAR(m.Z(), 100 + 5 - (-4 + 0.05), 1e-9);
}

TEST(ChannelCopyTest, ACopyAtAnyCycleRunsOnBitForBitLikeTheOriginal) {
  Machine first(kProgram, 0, 0, WithOffsetsAndTools);
  first.channel->Start();
  std::vector<ChannelRun> copies;
  int tick = 0;
  // Copies taken every 40 NC cycles: in the loop, during look-ahead, under G42, in the dwell.
  while (first.channel->state() == ChannelState::kRunning && first.t < 30) {
    if (tick % 160 == 0) copies.push_back(Copy(first));
    first.Tick();
    ++tick;
  }
  ASSERT_EQ(first.channel->state(), ChannelState::kEnded) << first.channel->error();
  ASSERT_GT(copies.size(), 10u);
  const std::vector<Outputs> reference = Reference();
  const int reference_ticks = static_cast<int>(reference.size());
  ASSERT_EQ(reference_ticks, tick);
  for (size_t k = 0; k < copies.size(); ++k) {
    SCOPED_TRACE("copied at tick " + std::to_string(k * 160));
    // The copy and a second copy of it, run side by side with the same inputs.
    ChannelRun a = copies[k];
    ChannelRun b = a;
    for (int t = static_cast<int>(k) * 160; t < tick; ++t) {
      a.Tick();
      b.Tick();
      const Outputs out = Of(a);
      ExpectSame(out, Of(b), t);
      ExpectSame(out, reference[static_cast<size_t>(t)], t);
      if (HasFatalFailure()) return;
    }
    EXPECT_FALSE(a.Running());
  }
}

TEST(ChannelCopyTest, TheCopyOutlivesTheOriginal) {
  // Nothing of the copy leads back into the original: the original is gone before the copy
  // runs (its interpreter's BES and TLD reach the copy).
  const std::vector<Outputs> reference = Reference();
  const int reference_ticks = static_cast<int>(reference.size());
  auto m = std::make_unique<Machine>(kProgram, 0, 0, WithOffsetsAndTools);
  m->channel->Start();
  for (int t = 0; t < 2000; ++t) m->Tick();
  ASSERT_EQ(m->channel->line(), 7u);  // N60 in the loop
  std::optional<ChannelRun> copy = Copy(*m);
  m->channel.reset();
  for (int t = 2000; copy->Running(); ++t) {
    ASSERT_LT(t, reference_ticks);
    copy->Tick();
    ExpectSame(Of(*copy), reference[static_cast<size_t>(t)], t);
    if (HasFatalFailure()) return;
  }
  EXPECT_EQ(copy->channel.state(), ChannelState::kEnded) << copy->channel.error();
}

TEST(ChannelCopyTest, TheOriginalIsUntouchedByWhatTheCopyIsGiven) {
  const std::vector<Outputs> reference = Reference();
  const int reference_ticks = static_cast<int>(reference.size());
  // Copied in the loop, before SE 29 / BES 29: the copy is told event 29 is clear, so it takes
  // N120 where the original skips it, and its TLD writes go to its own tool list.
  Machine m(kProgram, 0, 0, WithOffsetsAndTools);
  m.channel->Start();
  for (int t = 0; t < 2000; ++t) m.Tick();
  ASSERT_EQ(m.channel->line(), 7u);  // N60 in the loop
  // Copy-assigned over a channel of its own.
  Machine other("N1 G00 X1\nN2 RET\n");
  ChannelRun copy{static_cast<const test_support::IdealDriveBus&>(m), *other.channel};
  copy.channel = *m.channel;
  copy.channel.SetEventSource([](int) { return false; });
  copy.channel.SetFeedOverride(0.7);
  ChannelRun original = Copy(m);
  bool copy_took_n120 = false;
  for (int t = 2000; t < reference_ticks; ++t) {
    copy.Tick();
    original.Tick();
    ExpectSame(Of(original), reference[static_cast<size_t>(t)], t);
    if (HasFatalFailure()) return;
    copy_took_n120 = copy_took_n120 || copy.channel.line() == 13;
  }
  EXPECT_EQ(original.channel.state(), ChannelState::kEnded) << original.channel.error();
  // The copy ends later, at the same place: its own five wear increments, as the original's.
  for (int t = 0; copy.Running() && t < 100000; ++t) copy.Tick();
  EXPECT_EQ(copy.channel.state(), ChannelState::kEnded) << copy.channel.error();
  EXPECT_TRUE(copy_took_n120);
  EXPECT_NEAR(copy.bus.at.feedback[0].position, original.bus.at.feedback[0].position, 1e-9);
  EXPECT_NEAR(copy.bus.at.feedback[1].position, original.bus.at.feedback[1].position, 1e-9);
}

// The channel's data alone, taken mid-program and handed back to the same channel after it
// ran to the end: from there the channel runs the rest again, tick for tick as the first time.
TEST(ChannelCopyTest, RestoredDataRunsOnFromWhereItWasTaken) {
  const std::vector<Outputs> reference = Reference();
  Machine m(kProgram, 0, 0, WithOffsetsAndTools);
  m.channel->Start();
  constexpr int kTaken = 2000;
  for (int t = 0; t < kTaken; ++t) m.Tick();
  ASSERT_EQ(m.channel->line(), 7u);  // N60 in the loop
  const ChannelData data = m.channel->data();
  const test_support::IdealDriveBus bus = m;
  m.RunUntilEnd(30);
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();

  m.channel->Restore(data);
  static_cast<test_support::IdealDriveBus&>(m) = bus;
  EXPECT_EQ(m.channel->state(), ChannelState::kRunning);
  EXPECT_EQ(m.channel->line(), 7u);
  int t = kTaken;
  for (; m.channel->state() == ChannelState::kRunning; ++t) {
    ASSERT_LT(t, static_cast<int>(reference.size()));
    m.Tick();
    ExpectSame(Of(m.mdt, *m.channel), reference[static_cast<size_t>(t)], t);
    if (HasFatalFailure()) return;
  }
  EXPECT_EQ(t, static_cast<int>(reference.size()));
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
}

}  // namespace
}  // namespace vmt::control::channel
