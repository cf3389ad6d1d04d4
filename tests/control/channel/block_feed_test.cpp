// The blocks after the one in work on their own, read from a list instead of an interpreter:
// the look-ahead reads early only while the path goes on at speed and hands those blocks back
// in order; under G41/G42 the pieces of the tip path come out offset with their blocks; a block
// read ahead that cannot be taken fails only when the channel reaches it; a missing plane axis
// or tool is an error at its block; the program's end closes the tip path.

#include "control/channel/block_feed.hpp"

#include <gtest/gtest.h>

#include <deque>
#include <vector>

#include "control/channel/channel_messages.hpp"

namespace vmt::control::channel {
namespace {

constexpr size_t kX = 0, kZ = 1;  // the channel's axes: X (radius), Z
constexpr double kNose = 0.8;     // mm, T1 D1

std::vector<axes::AxisParameters> Axes() {
  axes::AxisParameters x, z;
  x.name = "X";
  x.rapid_per_s = 400;
  x.acceleration = 4000;
  x.travel_min = -300;
  x.travel_max = 300;
  z = x;
  z.name = "Z";
  z.rapid_per_s = 500;
  z.acceleration = 2000;
  return {x, z};
}

axes::ToolTable Tools() {
  axes::ToolTable tools;
  axes::ToolEdge edge;
  edge.tool = 1;
  edge.edge = 1;
  edge.length = {0, 0};
  edge.nose_radius = kNose;
  tools.edges.push_back(edge);
  return tools;
}

// A G01 block number `n` to X `x` Z `z` at 6000 mm/min, with T1 D1 and the compensation `trc`.
nc::PreparedBlock Line(int32_t n, double x, double z,
                       nc::Compensation trc = nc::Compensation::kOff) {
  nc::PreparedBlock b;
  b.block = n;
  b.motion = nc::Motion::kLinear;
  b.target = {x, z};
  b.programmed = 3;
  b.modal.motion = nc::Motion::kLinear;
  b.modal.feed = 6000;
  b.modal.tool = 1;
  b.modal.correction = 1;
  b.modal.compensation = trc;
  return b;
}

nc::PreparedBlock End(int32_t n, double x, double z) {
  nc::PreparedBlock b = Line(n, x, z);
  b.motion = nc::Motion::kNone;
  b.programmed = 0;
  b.end = true;
  return b;
}

// The program as a list: each read takes the next block, false after the last one.
struct ListSource {
  std::deque<nc::PreparedBlock> blocks;
  int reads = 0;
  ReadBlock Reader() {
    return [this](nc::PreparedBlock& b) {
      if (blocks.empty()) return false;
      b = blocks.front();
      blocks.pop_front();
      ++reads;
      return true;
    };
  }
};

// The channel's block by block read (its ReadNext): what the look-ahead read early first.
ReadBlock ChannelReader(BlockFeed& feed, ListSource& source) {
  return [&feed, read = source.Reader()](nc::PreparedBlock& b) {
    switch (feed.TakeEarly(b)) {
      case BlockFeed::Early::kTaken:
        return true;
      case BlockFeed::Early::kEnded:
        return false;
      case BlockFeed::Early::kNone:
        break;
    }
    return read(b);
  };
}

struct LookAheadFixture {
  std::vector<axes::AxisParameters> axes = Axes();
  std::vector<double> translation = {0, 0};
  std::vector<bool> homed = {true, true};
  LookAheadView View() const {
    return {axes,
            translation,
            homed,
            0,
            0.001,
            [](const nc::PreparedBlock&) { return false; },
            [](const nc::PreparedBlock&) { return uint64_t{0}; }};
  }
  BlockMotion Plan(const nc::PreparedBlock& b, std::vector<double> from) const {
    BlockMotion m;
    EXPECT_FALSE(PlanBlockMotion(b, from, translation, axes, 0, m));
    return m;
  }
};

TEST(BlockFeed, LookAheadReadsOnlyWhileThePathGoesOnAndHandsTheBlocksBackInOrder) {
  const axes::ToolTable tools = Tools();
  const FeedContext ctx{tools, static_cast<int>(kZ), static_cast<int>(kX)};
  LookAheadFixture f;
  // 0.5 mm blocks at 100 mm/s: braking from there takes 2.5 mm, more than the path known
  // before the dwell, which the path must reach at rest.
  const nc::PreparedBlock in_work = Line(0, 10, 10.5);
  nc::PreparedBlock dwell = Line(3, 10, 12);
  dwell.dwell_s = 1;
  ListSource source{{Line(1, 10, 11), Line(2, 10.5, 11.5), dwell, Line(4, 10, 13)}};
  BlockFeed feed;
  nc::PreparedBlock b;
  EXPECT_EQ(feed.TakeEarly(b), BlockFeed::Early::kNone);
  std::vector<SpeedTarget> targets;
  EXPECT_TRUE(
      feed.PlanAhead(ctx, source.Reader(), in_work, f.Plan(in_work, {10, 10}), f.View(), targets));
  EXPECT_EQ(source.reads, 3);       // up to the dwell, not beyond it
  ASSERT_EQ(targets.size(), 3u);    // the ends of the block in work and of blocks 1 and 2
  EXPECT_GT(targets[0].corner, 0);  // collinear: the speed goes on into block 1
  EXPECT_EQ(targets[2].corner, 0);  // at rest before the dwell's block
  EXPECT_GT(targets[2].distance, targets[1].distance);
  EXPECT_TRUE(feed.read_early());
  for (int32_t n : {1, 2, 3}) {
    ASSERT_EQ(feed.TakeEarly(b), BlockFeed::Early::kTaken);
    EXPECT_EQ(b.block, n);
  }
  EXPECT_EQ(feed.TakeEarly(b), BlockFeed::Early::kNone);  // block 4: the channel reads it
}

TEST(BlockFeed, TheReadAheadThatMetTheEndSaysSoAfterItsBlocks) {
  const axes::ToolTable tools = Tools();
  const FeedContext ctx{tools, static_cast<int>(kZ), static_cast<int>(kX)};
  LookAheadFixture f;
  const nc::PreparedBlock in_work = Line(0, 10, 10.5);
  ListSource source{{Line(1, 10, 11)}};
  BlockFeed feed;
  std::vector<SpeedTarget> targets;
  EXPECT_TRUE(
      feed.PlanAhead(ctx, source.Reader(), in_work, f.Plan(in_work, {10, 10}), f.View(), targets));
  EXPECT_EQ(targets.back().corner, 0);  // the end of the program known: a stop
  nc::PreparedBlock b;
  ASSERT_EQ(feed.TakeEarly(b), BlockFeed::Early::kTaken);
  EXPECT_EQ(b.block, 1);
  EXPECT_EQ(feed.TakeEarly(b), BlockFeed::Early::kEnded);
  feed.Drop();  // a new start reads again
  EXPECT_EQ(feed.TakeEarly(b), BlockFeed::Early::kNone);
}

TEST(BlockFeed, AReversalEndsTheBlockInWorkAtRest) {
  const axes::ToolTable tools = Tools();
  const FeedContext ctx{tools, static_cast<int>(kZ), static_cast<int>(kX)};
  LookAheadFixture f;
  const nc::PreparedBlock in_work = Line(0, 10, 10.5);
  ListSource source{{Line(1, 10, 10), Line(2, 10, 9.5)}};
  BlockFeed feed;
  std::vector<SpeedTarget> targets = {SpeedTarget{}};
  EXPECT_FALSE(
      feed.PlanAhead(ctx, source.Reader(), in_work, f.Plan(in_work, {10, 10}), f.View(), targets));
  EXPECT_TRUE(targets.empty());
}

// Collects the pieces of the tip path until the compensation has given out everything.
struct Pieces {
  std::vector<nc::PreparedBlock> blocks;
  std::vector<TakenPiece> taken;
  BlockFeed::Fill last = BlockFeed::Fill::kPiece;
};

Pieces Drain(BlockFeed& feed, const FeedContext& ctx, ListSource& source) {
  Pieces p;
  const ReadBlock read = ChannelReader(feed, source);
  for (int guard = 0; guard < 100; ++guard) {
    p.last = feed.FillPiece(ctx, read);
    if (p.last == BlockFeed::Fill::kSourceEnded) {
      feed.EndOfSource();
      continue;
    }
    if (p.last != BlockFeed::Fill::kPiece) break;
    nc::PreparedBlock b;
    p.taken.push_back(feed.TakePiece(ctx, b));
    p.blocks.push_back(b);
  }
  return p;
}

TEST(BlockFeed, UnderG41ThePiecesRunOffsetAndG40ReturnsToTheContour) {
  const axes::ToolTable tools = Tools();
  const FeedContext ctx{tools, static_cast<int>(kZ), static_cast<int>(kX)};
  // Along +Z at X10: left of the motion (G41) is +X; the edge position 0 is the nose centre.
  const nc::PreparedBlock first = Line(1, 10, 10, nc::Compensation::kLeft);
  ListSource source{{Line(2, 10, 20, nc::Compensation::kLeft), Line(3, 10, 30), End(4, 10, 30)}};
  BlockFeed feed;
  ASSERT_TRUE(feed.StartCompensation(ctx, {10, 0}, {0, 0}, first));
  EXPECT_TRUE(feed.compensating());
  const Pieces p = Drain(feed, ctx, source);
  // After G40 the channel goes back to block by block: the end is its to read.
  EXPECT_EQ(p.last, BlockFeed::Fill::kDrained);
  EXPECT_FALSE(feed.compensating());
  EXPECT_FALSE(feed.source_done());
  EXPECT_EQ(source.blocks.size(), 1u);
  ASSERT_EQ(p.blocks.size(), 3u);
  EXPECT_EQ(p.blocks[0].block, 1);  // start-up: to the offset point of block 2's start
  EXPECT_NEAR(p.blocks[0].target[kZ], 10, 1e-9);
  EXPECT_NEAR(p.blocks[0].target[kX], 10 + kNose, 1e-9);
  EXPECT_EQ(p.blocks[1].block, 2);
  EXPECT_NEAR(p.blocks[1].target[kZ], 20, 1e-9);
  EXPECT_NEAR(p.blocks[1].target[kX], 10 + kNose, 1e-9);
  EXPECT_EQ(p.blocks[2].block, 3);  // G40: back onto the programmed end point
  EXPECT_NEAR(p.blocks[2].target[kZ], 30, 1e-9);
  EXPECT_NEAR(p.blocks[2].target[kX], 10, 1e-9);
  for (const TakenPiece& t : p.taken) EXPECT_FALSE(t.further);
}

TEST(BlockFeed, AnOuterCornerIsAFurtherPieceOfTheBlockAfterIt) {
  const axes::ToolTable tools = Tools();
  const FeedContext ctx{tools, static_cast<int>(kZ), static_cast<int>(kX)};
  // Along +Z, then down in X under G41 (nose on +X): the tool goes round the corner outside.
  const nc::PreparedBlock first = Line(1, 10, 10, nc::Compensation::kLeft);
  ListSource source{{Line(2, 10, 20, nc::Compensation::kLeft),
                     Line(3, 0, 20, nc::Compensation::kLeft), Line(4, 0, 30), End(5, 0, 30)}};
  BlockFeed feed;
  ASSERT_TRUE(feed.StartCompensation(ctx, {10, 0}, {0, 0}, first));
  const Pieces p = Drain(feed, ctx, source);
  EXPECT_EQ(p.last, BlockFeed::Fill::kDrained);
  int arcs = 0;
  for (size_t i = 0; i < p.blocks.size(); ++i) {
    if (p.blocks[i].motion != nc::Motion::kArcCw && p.blocks[i].motion != nc::Motion::kArcCcw)
      continue;
    ++arcs;
    EXPECT_TRUE(p.taken[i].element.inserted);
    EXPECT_TRUE(p.blocks[i].has_centre);
    // The arc of the nose radius round the programmed corner Z20 X10.
    EXPECT_NEAR(p.blocks[i].target[kZ], 20 + kNose, 1e-9);
    EXPECT_NEAR(p.blocks[i].target[kX], 10, 1e-9);
    ASSERT_LT(i + 1, p.blocks.size());
    EXPECT_EQ(p.blocks[i + 1].block, p.blocks[i].block);  // the same block goes on
    EXPECT_TRUE(p.taken[i + 1].further);
  }
  EXPECT_EQ(arcs, 1);
}

TEST(BlockFeed, ABlockTheCompensationCannotTakeFailsWhenTheChannelReachesIt) {
  const axes::ToolTable tools = Tools();
  const FeedContext ctx{tools, static_cast<int>(kZ), static_cast<int>(kX)};
  LookAheadFixture f;
  nc::PreparedBlock homing = Line(3, 10, 40, nc::Compensation::kLeft);
  homing.homing = true;  // G74 under G41
  const nc::PreparedBlock first = Line(1, 10, 10.5, nc::Compensation::kLeft);
  ListSource source{{Line(2, 10, 11, nc::Compensation::kLeft), homing}};
  BlockFeed feed;
  ASSERT_TRUE(feed.StartCompensation(ctx, {10, 10}, {0, 0}, first));
  const ReadBlock read = ChannelReader(feed, source);
  ASSERT_EQ(feed.FillPiece(ctx, read), BlockFeed::Fill::kPiece);
  nc::PreparedBlock in_work;
  feed.TakePiece(ctx, in_work);
  // The look-ahead (reading straight from the program) meets G74: no error yet, the path
  // known ends before it.
  std::vector<SpeedTarget> targets;
  feed.PlanAhead(ctx, source.Reader(), in_work, f.Plan(in_work, {10, 10}), f.View(), targets);
  EXPECT_TRUE(source.blocks.empty());
  EXPECT_TRUE(feed.compensating());
  // Block 2's piece is final only with the element after it: preparing it, the channel reaches
  // G74, and the error comes now.
  ASSERT_EQ(feed.FillPiece(ctx, read), BlockFeed::Fill::kFailed);
  EXPECT_EQ(feed.error().block, 3);
  EXPECT_EQ(feed.error().number, kMsgNotAvailable);
  EXPECT_NE(feed.error().text.find("G74"), std::string::npos);
}

TEST(BlockFeed, TheProgramsEndUnderG41ClosesTheTipPath) {
  const axes::ToolTable tools = Tools();
  const FeedContext ctx{tools, static_cast<int>(kZ), static_cast<int>(kX)};
  const nc::PreparedBlock first = Line(1, 10, 10, nc::Compensation::kLeft);
  ListSource source{{Line(2, 10, 20, nc::Compensation::kLeft)}};  // the text ends, no M30
  BlockFeed feed;
  ASSERT_TRUE(feed.StartCompensation(ctx, {10, 0}, {0, 0}, first));
  const Pieces p = Drain(feed, ctx, source);
  EXPECT_EQ(p.last, BlockFeed::Fill::kDrained);
  EXPECT_TRUE(feed.source_done());
  ASSERT_EQ(p.blocks.size(), 2u);
  // The last piece ends perpendicular at its end point: nothing follows it.
  EXPECT_EQ(p.blocks[1].block, 2);
  EXPECT_NEAR(p.blocks[1].target[kZ], 20, 1e-9);
  EXPECT_NEAR(p.blocks[1].target[kX], 10 + kNose, 1e-9);
}

TEST(BlockFeed, G41NeedsThePlaneAxesAndAToolOfTheList) {
  const axes::ToolTable tools = Tools();
  BlockFeed feed;
  const nc::PreparedBlock first = Line(7, 10, 10, nc::Compensation::kRight);
  EXPECT_FALSE(feed.StartCompensation({tools, -1, static_cast<int>(kX)}, {10, 0}, {0, 0}, first));
  EXPECT_EQ(feed.error().block, 7);
  EXPECT_EQ(feed.error().number, kMsgNotAvailable);
  EXPECT_FALSE(feed.compensating());

  nc::PreparedBlock unknown = first;
  unknown.modal.tool = 5;
  const FeedContext ctx{tools, static_cast<int>(kZ), static_cast<int>(kX)};
  EXPECT_FALSE(feed.StartCompensation(ctx, {10, 0}, {0, 0}, unknown));
  EXPECT_EQ(feed.error().number, kMsgToolNotInList);
  EXPECT_NE(feed.error().text.find("T5 D1"), std::string::npos);
}

}  // namespace
}  // namespace vmt::control::channel
