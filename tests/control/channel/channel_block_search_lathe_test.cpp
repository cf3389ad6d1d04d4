// Block search on a lathe (twincat-cnc-block-search-de.md): a continue position inside a
// finishing pass under tool nose radius compensation G42 (the search runs the compensation, so
// the position is on the tip path the uninterrupted run machines, and machining goes on there
// with the compensation on), every search type and type 1's end position under G42 (3.1), and a
// region programmed only with G91 (8). #CAX TRACK: channel_cax_track_test.cpp.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <tuple>

#include "block_search_steps.hpp"
#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using testing::Machine;
using testing::WithOffsetsAndTools;

/// The stepped shaft's finishing pass (scenes/nc/stepped_shaft.mtc): G42 with T1 D1 (r 0.8,
/// cutting edge position 3), two fillets tangent to the lines.
constexpr const char* kFinishing =
    "N0010 G90 G18 G94 G00 X40 Z158\n"
    "N0140 G42 G48 T1 D1 G01 X19 F600\n"
    "N0150 Z138\n"
    "N0160 G02 X23 Z134 I4 K0\n"
    "N0170 G01 Z118\n"
    "N0180 G03 X27 Z114 I0 K-4\n"
    "N0190 G01 Z95\n"
    "N0200 G40 G00 X40\n"
    "N0210 Z158\n"
    "N0220 RET\n";

/// A shoulder with sharp corners under G42: the inner one at its foot is trimmed, the outer one
/// at its top gets a corner arc, which the compensation runs before N0170.
constexpr const char* kShoulder =
    "N0010 G90 G18 G94 G00 X40 Z158\n"
    "N0140 G42 T1 D1 G01 X19 F600\n"
    "N0150 Z138\n"
    "N0160 X23\n"
    "N0170 Z118\n"
    "N0180 X27\n"
    "N0190 Z95\n"
    "N0200 G40 G00 X40\n"
    "N0210 Z158\n"
    "N0220 RET\n";

struct Lathe : testing::BlockSearchSteps<Machine> {
  explicit Lathe(const std::string& program, double x = 60, double z = 200)
      : BlockSearchSteps(program, x, z, WithOffsetsAndTools) {}
};

/// The uninterrupted run's (X, Z) at `mm` from program start: the breakpoint (3.5) holds the
/// path there.
std::pair<double, double> NormalRunAt(const char* program, double mm, double x = 60,
                                      double z = 200) {
  Lathe m(program, x, z);
  BlockSearchParameters p;
  p.type = BlockSearchType::kBreakpointOnly;
  p.breakpoint_position = mm * 1e4;  // 0.1 um
  m.Search(p);
  EXPECT_TRUE(m.RunUntil([&] {
    return m.channel->block_search().stop_conditions & stop_condition::kBreakpointStop || m.Ended();
  }));
  EXPECT_FALSE(m.Ended()) << "the breakpoint at " << mm << " mm did not stop the run";
  for (int i = 0; i < 8; ++i) m.Tick();  // the fine interpolation reaches the hold point
  return {m.X(), m.Z()};
}

/// Whether the drive tick just run ends an NC cycle: its setpoint is then the cycle's point,
/// which lies on the path exactly (the ticks between are chords of the fine interpolation).
bool CyclePoint(const Machine& m) { return std::lround(m.t / 250e-6) % 4 == 3; }

/// The uninterrupted run's path: its NC cycle points at 10 % feed override, 1 um apart at
/// F600, so that the chords between them cut a corner by less than half a micrometre.
std::vector<std::pair<double, double>> NormalRunPath(const char* program) {
  Lathe m(program);
  m.channel->SetFeedOverride(0.1);
  m.channel->Start();
  std::vector<std::pair<double, double>> path;
  while (!m.Ended() && m.channel->state() != ChannelState::kError && m.t < 600) {
    m.Tick();
    if (CyclePoint(m)) path.emplace_back(m.X(), m.Z());
  }
  EXPECT_TRUE(m.Ended()) << m.channel->error();
  return path;
}

/// Distance of (x, z) from the polyline `path`, mm. Both runs go forward along the path:
/// `from` is where the last point was found (-1: search it all) and moves on with it.
double FromPath(const std::vector<std::pair<double, double>>& path, double x, double z,
                long& from) {
  double best = std::numeric_limits<double>::infinity();
  const long n = static_cast<long>(path.size());
  const long lo = from < 0 ? 1 : std::max(1L, from - 100);
  const long hi = from < 0 ? n : std::min(n, from + 20000);
  long found = from;
  for (long i = lo; i < hi; ++i) {
    const auto [x0, z0] = path[static_cast<size_t>(i - 1)];
    const auto [x1, z1] = path[static_cast<size_t>(i)];
    const double dx = x1 - x0, dz = z1 - z0, l2 = dx * dx + dz * dz;
    const double u = l2 > 0 ? std::clamp(((x - x0) * dx + (z - z0) * dz) / l2, 0.0, 1.0) : 0;
    const double d = std::hypot(x - (x0 + u * dx), z - (z0 + u * dz));
    if (d < best) best = d, found = i;
  }
  from = found;
  return best;
}

/// Searches `number` at `permille`, returns, and machines to the end. The continue position
/// is the uninterrupted run's point at the same distance from program start, within 1 um;
/// every point machined after the continue lies on the uninterrupted run's path (the
/// compensation is still on), within 1 um.
void ContinuesOnTheCompensatedPath(const char* program, uint32_t number, double permille, double x,
                                   double z) {
  SCOPED_TRACE("N" + std::to_string(number) + " at " + std::to_string(permille) + " per mille");
  Lathe m(program);
  m.Search(testing::BlockNumberSearch(number, permille));
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
  const BlockSearchStatus& st = m.channel->block_search();
  ASSERT_EQ(st.continue_position.size(), 2u);
  EXPECT_NEAR(st.continue_position[0], x, 1e-9);
  EXPECT_NEAR(st.continue_position[1], z, 1e-9);
  const double mm = st.dist_prog_start;
  m.channel->Start();
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForContinueContour)) << m.channel->error();
  EXPECT_NEAR(m.X(), x, 1e-9);
  EXPECT_NEAR(m.Z(), z, 1e-9);
  const auto [nx, nz] = NormalRunAt(program, mm);
  EXPECT_NEAR(m.X(), nx, 1e-3);  // 1 um; it is the same point to the nanometre
  EXPECT_NEAR(m.Z(), nz, 1e-3);
  EXPECT_NEAR(m.X(), nx, 1e-6);
  EXPECT_NEAR(m.Z(), nz, 1e-6);

  const auto path = NormalRunPath(program);
  m.channel->Start();
  double worst = 0;
  long along = -1;
  ASSERT_TRUE(m.RunUntil([&] {
    if (CyclePoint(m)) worst = std::max(worst, FromPath(path, m.X(), m.Z(), along));
    return m.Ended() || m.channel->state() == ChannelState::kError;
  }));
  EXPECT_TRUE(m.Ended()) << m.channel->error();
  EXPECT_LT(worst, 1e-3);
  EXPECT_NEAR(m.X(), 40, 1e-9);
  EXPECT_NEAR(m.Z(), 158, 1e-9);
}

TEST(ChannelBlockSearchLathe, G42ContinuePositionInALineIsOnTheTipPath) {
  // N0150 under G42, r 0.8, edge 3: the nose centre runs at X19.8, the tip 0.8 mm further in
  // -X and -Z (TipFromCentre): from Z157.2 to Z137.2 at X19; 300 per mille is Z151.2.
  ContinuesOnTheCompensatedPath(kFinishing, 150, 300, 19, 151.2);
}

TEST(ChannelBlockSearchLathe, G42ContinuePositionInAnArcIsOnTheTipPath) {
  // N0160 G02 about X23 Z138 (R4): the nose centre on R4 - 0.8 = 3.2 (G42 on the inside of
  // the clockwise arc), half way at 45 deg, the tip (-0.8, -0.8) from it.
  const double c = 3.2 / std::sqrt(2.0);
  ContinuesOnTheCompensatedPath(kFinishing, 160, 500, 23 - c - 0.8, 138 - c - 0.8);
}

TEST(ChannelBlockSearchLathe, G42ContinuePositionAfterAnInsertedCornerArc) {
  // The shoulder's top corner (X23 Z138): the compensation inserts an arc about it before
  // N0170; the per mille lies in N0170's own piece, the centre at X23.8 from Z138 to Z118.8
  // (N0180 X27 rises: an inner corner trims it 0.8 mm short of Z118).
  ContinuesOnTheCompensatedPath(kShoulder, 170, 0, 23.0, 138 - 0.8);
  ContinuesOnTheCompensatedPath(kShoulder, 170, 500, 23.0, 138 - 0.8 - 0.5 * 19.2);
}

TEST(ChannelBlockSearchLathe, InsertedCornerShowsZeroPerMilleOfItsBlock) {
  // While the corner arc runs, the block in work is N0170 at 0 per mille: a search with what
  // the HLI shows lands where N0170's own path begins.
  Lathe m(kShoulder);
  m.channel->Start();
  double seen_on_arc = -1;
  ASSERT_TRUE(m.RunUntil([&] {
    // The tip on the corner arc: from X22.2 Z138 to X23 Z137.2.
    const bool on_arc =
        m.Z() > 137.2 + 1e-6 && m.Z() < 138 - 1e-6 && m.X() > 22.2 + 1e-6 && m.X() < 23 - 1e-6;
    if (on_arc && seen_on_arc < 0) seen_on_arc = m.channel->block_search().covered_distance;
    return m.Ended();
  }));
  EXPECT_EQ(seen_on_arc, 0);
}

TEST(ChannelBlockSearchLathe, G42ByDistanceFromProgramStartMatchesTheRun) {
  // 4.1.2: the distance counts the tip path the run counts, so a distance lands where the
  // uninterrupted run was at that distance.
  Lathe m(kFinishing);
  BlockSearchParameters p = testing::BlockNumberSearch(140, 0);
  p.distance_prog_start = 60 * 1e4;
  m.Search(p);
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
  EXPECT_NEAR(m.channel->block_search().dist_prog_start, 60, 1e-9);
  m.channel->Start();
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForContinueContour));
  const auto [nx, nz] = NormalRunAt(kFinishing, 60);
  EXPECT_NEAR(m.X(), nx, 1e-6);
  EXPECT_NEAR(m.Z(), nz, 1e-6);
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.Ended() || m.channel->state() == ChannelState::kError; }));
  EXPECT_TRUE(m.Ended()) << m.channel->error();
}

/// Block search type 1 (3.1) in kFinishing: from N0150's line to the end position at
/// `end_block`'s line (no end position if empty).
BlockSearchParameters FileOffsetSearch(const std::string& text, const char* start,
                                       const char* end_block) {
  BlockSearchParameters p;
  p.type = BlockSearchType::kFileOffset;
  p.start.offset = static_cast<int64_t>(text.find(start));
  if (end_block) p.end.offset = static_cast<int64_t>(text.find(end_block));
  p.auto_return = true;
  return p;
}

/// The channel searches with `p`, returns, machines on to its end; the lowest Z it reached.
double MachinesTo(Lathe& m, const BlockSearchParameters& p) {
  m.Search(p);
  EXPECT_TRUE(m.ToContour()) << m.channel->error();
  m.channel->Start();
  double lowest_z = m.Z();
  EXPECT_TRUE(m.RunUntil([&] {
    lowest_z = std::min(lowest_z, m.Z());
    return m.Ended() || m.channel->state() == ChannelState::kError;
  }));
  EXPECT_TRUE(m.Ended()) << m.channel->error();
  return lowest_z;
}

TEST(ChannelBlockSearchLathe, Type1EndPositionEndsTheCompensatedPathToo) {
  // 3.1: machining ends at the end position (N0190's line), before N0190 runs, with G42 on as
  // without it. The compensation's read-ahead meets the end as it meets the text's end: the tip
  // path closes after N0180's arc, at Z114 less the nose's offset, and never goes on along
  // N0190 to Z95 or back out with N0200.
  for (const bool compensated : {true, false}) {
    SCOPED_TRACE(compensated ? "G42" : "G40");
    std::string text = kFinishing;
    if (!compensated) text.replace(text.find("G42 "), 4, "");
    Lathe m(text);
    const double lowest_z = MachinesTo(m, FileOffsetSearch(text, "N0150", "N0190"));
    EXPECT_GT(lowest_z, 113);
    EXPECT_LT(m.X(), 29);
    if (!compensated) {
      EXPECT_NEAR(m.X(), 27, 1e-9);
      EXPECT_NEAR(m.Z(), 114, 1e-9);
    }
  }
  // Without an end position the same search machines to the end of the program.
  Lathe whole(kFinishing);
  EXPECT_LT(MachinesTo(whole, FileOffsetSearch(kFinishing, "N0150", nullptr)), 96);  // N0190
  EXPECT_NEAR(whole.X(), 40, 1e-9);
  EXPECT_NEAR(whole.Z(), 158, 1e-9);
}

TEST(ChannelBlockSearchLathe, Type1EndBeforeTheContinuePositionUnderG42) {
  // The end position (N0170) comes before the continue position (N0190), inside the region
  // the compensation reads ahead: the program ends in search mode, nothing moves.
  Lathe m(kFinishing);
  m.Search(FileOffsetSearch(kFinishing, "N0190", "N0170"));
  ASSERT_TRUE(m.RunUntil([&] { return m.Ended() || m.channel->state() == ChannelState::kError; }));
  EXPECT_TRUE(m.Ended()) << m.channel->error();
  EXPECT_EQ(m.X(), 60);
  EXPECT_EQ(m.Z(), 200);
  EXPECT_THAT(m.channel->block_search().warnings,
              ::testing::ElementsAre("the end position came before the continue position"));
}

TEST(ChannelBlockSearchLathe, EveryTypeUnderG42) {
  // Type 3 (the decoder's line count of N0160) lands where type 4 (N0160) does, on the tip
  // path; type 5 decodes the compensated program to its end without motion.
  Lathe by_number(kFinishing);
  by_number.Search(testing::BlockNumberSearch(160, 250));
  ASSERT_TRUE(by_number.Waits(BlockSearchState::kWaitReturnToContour));
  const BlockSearchStatus number = by_number.channel->block_search();
  Lathe by_count(kFinishing);
  BlockSearchParameters p = testing::BlockNumberSearch(0, 250);
  p.type = BlockSearchType::kBlockCounter;
  p.intern_block_count = number.block_count;
  by_count.Search(p);
  ASSERT_TRUE(by_count.Waits(BlockSearchState::kWaitReturnToContour)) << by_count.channel->error();
  const BlockSearchStatus& count = by_count.channel->block_search();
  ASSERT_EQ(count.continue_position.size(), 2u);
  EXPECT_NEAR(count.continue_position[0], number.continue_position[0], 1e-12);
  EXPECT_NEAR(count.continue_position[1], number.continue_position[1], 1e-12);
  EXPECT_NEAR(count.dist_prog_start, number.dist_prog_start, 1e-12);

  Lathe to_end(kFinishing);
  BlockSearchParameters end;
  end.type = BlockSearchType::kProgramEnd;
  to_end.Search(end);
  ASSERT_TRUE(to_end.RunUntil(
      [&] { return to_end.Ended() || to_end.channel->state() == ChannelState::kError; }));
  EXPECT_TRUE(to_end.Ended()) << to_end.channel->error();
  EXPECT_TRUE(to_end.channel->block_search().warnings.empty());
  EXPECT_EQ(to_end.X(), 60);
  EXPECT_EQ(to_end.Z(), 200);
}

/// Block search 8: "Enthält ein Programm innerhalb des Satzvorlaufbereichs nur relative G91
/// Positionierungen, so werden trotz Neustart des gleichen Programms im Satzvorlauf evtl.
/// unterschiedliche Positionen angefahren."
constexpr const char* kIncremental =
    "N10 G91 G01 X5 Z-10 F1000\n"
    "N20 X5\n"
    "N30 Z-10\n"
    "N40 X-3 Z-2\n"
    "N50 RET\n";

TEST(ChannelBlockSearchLathe, G91OnlyRegionContinuesRelativeToWhereTheSearchStarts) {
  // The search simulates every G91 block from where the axes stand at the start, as the run
  // would: the continue position is right for a run started there, so two starts from two
  // places give two positions (the manual's warning); the search does not know where the
  // interrupted run began.
  for (const auto& [x, z] : {std::pair{60.0, 200.0}, {50.0, 150.0}}) {
    SCOPED_TRACE("start X" + std::to_string(x) + " Z" + std::to_string(z));
    Lathe m(kIncremental, x, z);
    m.Search(testing::BlockNumberSearch(40, 0));
    ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
    const BlockSearchStatus& st = m.channel->block_search();
    ASSERT_EQ(st.continue_position.size(), 2u);
    EXPECT_NEAR(st.continue_position[0], x + 10, 1e-9);
    EXPECT_NEAR(st.continue_position[1], z - 20, 1e-9);
    EXPECT_NEAR(st.path_deviation, std::hypot(10.0, 20.0), 1e-9);
    // The uninterrupted run from the same place is there at the same distance.
    const auto [nx, nz] = NormalRunAt(kIncremental, st.dist_prog_start, x, z);
    EXPECT_NEAR(nx, x + 10, 1e-9);
    EXPECT_NEAR(nz, z - 20, 1e-9);
    m.channel->Start();
    ASSERT_TRUE(m.Waits(BlockSearchState::kWaitForContinueContour));
    m.channel->Start();
    ASSERT_TRUE(m.RunUntil([&] { return m.Ended(); }));
    EXPECT_NEAR(m.X(), x + 7, 1e-9);
    EXPECT_NEAR(m.Z(), z - 22, 1e-9);
  }
  // The manual's advice, one absolute positioning in the searched region: the same continue
  // position from anywhere.
  const std::string anchored = std::string("N05 G90 G01 X40 Z100 F1000\n") + kIncremental;
  for (const auto& [x, z] : {std::pair{60.0, 200.0}, {50.0, 150.0}}) {
    Lathe m(anchored.c_str(), x, z);
    m.Search(testing::BlockNumberSearch(40, 0));
    ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
    EXPECT_NEAR(m.channel->block_search().continue_position[0], 50, 1e-9);
    EXPECT_NEAR(m.channel->block_search().continue_position[1], 80, 1e-9);
  }
}

}  // namespace
}  // namespace vmt::control::channel
