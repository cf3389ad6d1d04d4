// The plain data of block search (control/channel/block_search.*): the parameters' ranges
// (twincat-cnc-block-search-de.md 5.1-5.4), the matching of the continue position by file
// offset, line count and block number with passes and program name, and the path length the
// distance from program start counts (4.1.2).

#include "control/channel/block_search.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "control/nc/parser.hpp"

namespace vmt::control::channel {
namespace {

using ::testing::HasSubstr;

TEST(BlockSearchParameters, RangesOfTheCncObjects) {
  BlockSearchParameters p;
  EXPECT_EQ(CheckBlockSearch(p), "");
  p.type = static_cast<BlockSearchType>(2);
  EXPECT_THAT(CheckBlockSearch(p), HasSubstr("type 2 no longer exists"));
  p.type = BlockSearchType::kBlockNumber;
  p.covered_distance = 1000.5;
  EXPECT_THAT(CheckBlockSearch(p), HasSubstr("0.0 .. 1000.0"));
  p.covered_distance = 1000;
  EXPECT_EQ(CheckBlockSearch(p), "");
  p.type = BlockSearchType::kBlockCounter;
  EXPECT_THAT(CheckBlockSearch(p), HasSubstr("intern_block_count_w"));
  p.intern_block_count = 1;
  EXPECT_EQ(CheckBlockSearch(p), "");
  p.type = BlockSearchType::kFileOffset;
  EXPECT_THAT(CheckBlockSearch(p), HasSubstr("pos_start_offset_w"));
  p.start.offset = 0;
  p.start.count = 0;
  EXPECT_THAT(CheckBlockSearch(p), HasSubstr("1 .. MAX_SGN16"));
  p.start.count = 1;
  p.start.path = 2;
  EXPECT_THAT(CheckBlockSearch(p), HasSubstr("subprogram path"));
  p.start.path = 1;
  EXPECT_EQ(CheckBlockSearch(p), "");
  p.distance_prog_start = -1;
  EXPECT_THAT(CheckBlockSearch(p), HasSubstr("must not be negative"));
  EXPECT_FALSE(p.searches() && p.type == BlockSearchType::kBreakpointOnly);
  EXPECT_STREQ(ToString(BlockSearchState::kWaitForContinueContour),
               "HLI_BS_WAIT_FOR_CONTINUE_CONTOUR");
}

struct Blocks {
  explicit Blocks(const std::string& text, const std::string& file = "dir/prog.nc")
      : parsed(nc::ParseProgram(text, file, nc::Dialect::kIsg)) {}
  nc::PreparedBlock At(const std::string& number_text) const {
    nc::PreparedBlock b;
    const int n = std::stoi(number_text);
    for (size_t i = 0; i < parsed.program.blocks.size(); ++i)
      if (parsed.program.blocks[i].number == n) b.block = static_cast<int32_t>(i);
    return b;
  }
  nc::ParseResult parsed;
};

TEST(ContinueMatcher, BlockNumberWithPassAndProgramName) {
  Blocks b("%main\nN10 X1\nN20 X2\n");
  BlockSearchParameters p;
  p.type = BlockSearchType::kBlockNumber;
  p.block_number = 20;
  p.block_number_pass = 3;
  ContinueMatcher m(p);
  const nc::PreparedBlock n10 = b.At("10"), n20 = b.At("20");
  EXPECT_FALSE(m.Matches(n10, b.parsed.program, 0));
  EXPECT_FALSE(m.Matches(n20, b.parsed.program, 0));
  EXPECT_FALSE(m.Matches(n20, b.parsed.program, 0));
  EXPECT_TRUE(m.Matches(n20, b.parsed.program, 0));  // the third pass
  p.block_number_pass = 1;
  p.block_nbr_prog_name = "%MAIN";  // case does not matter, nor the %
  ContinueMatcher named(p);
  EXPECT_TRUE(named.Matches(n20, b.parsed.program, 0));
  p.block_nbr_prog_name = "sub";
  ContinueMatcher other(p);
  EXPECT_FALSE(other.Matches(n20, b.parsed.program, 0));
}

TEST(ContinueMatcher, FileOffsetNameAndPath) {
  const std::string text = "%main\nN10 X1\nN20 X2\n";
  Blocks b(text);
  BlockSearchParameters p;
  p.type = BlockSearchType::kFileOffset;
  p.start.offset = static_cast<int64_t>(text.find("N20"));
  const nc::PreparedBlock n20 = b.At("20");
  for (const char* name : {"", "prog.nc", "dir/prog.nc"}) {
    p.start.name = name;
    ContinueMatcher m(p);
    EXPECT_TRUE(m.Matches(n20, b.parsed.program, 0)) << name;
  }
  p.start.name = "rog.nc";  // a part of the name is not the file
  EXPECT_FALSE(ContinueMatcher(p).Matches(n20, b.parsed.program, 0));
  p.start.name = "prog.nc";
  p.start.path = 1;  // the subprogram path: not the main program
  EXPECT_FALSE(ContinueMatcher(p).Matches(n20, b.parsed.program, 0));
  EXPECT_TRUE(ContinueMatcher(p).Matches(n20, b.parsed.program, 1));
  p.start.path = 0;
  p.start.offset += 1;  // not a line start
  EXPECT_FALSE(ContinueMatcher(p).Matches(n20, b.parsed.program, 0));
}

axes::AxisParameters Axis(const std::string& name, double rapid) {
  axes::AxisParameters a;
  a.name = name;
  a.rapid_per_s = rapid;
  return a;
}

TEST(DistanceOf, MainAxesLineArcAndFollowingAxis) {
  const std::vector<axes::AxisParameters> axes = {Axis("X", 100), Axis("Z", 100), Axis("C", 360),
                                                  Axis("W", 50)};
  BlockMotion line;
  line.moves = true;
  line.start = {0, 0, 0, 0};
  line.end = {3, 4, 90, 0};
  EXPECT_NEAR(DistanceOf(line, axes), 5, 1e-12);  // C follows: not counted
  BlockMotion arc = line;
  arc.end = {10, 10, 0, 0};
  arc.arc_axes[0] = 1, arc.arc_axes[1] = 0;
  arc.arc_radius = 10;
  arc.arc_sweep = -M_PI / 2;
  EXPECT_NEAR(DistanceOf(arc, axes), 5 * M_PI, 1e-12);
  // No main axis moves: the following axis that takes longest at its rapid limit, C 90 deg
  // (0.25 s) against W 20 mm (0.4 s).
  BlockMotion following = line;
  following.end = {0, 0, 90, 20};
  EXPECT_NEAR(DistanceOf(following, axes), 20, 1e-12);
  following.moves = false;
  EXPECT_EQ(DistanceOf(following, axes), 0);
}

TEST(BlockSearch, SteeringCommands) {
  // The texts as the ISG front end keeps them: upper case, single spaces. #CAX TRACK itself
  // is parsed by cax_track.hpp (cax_track_test.cpp).
  for (const char* text : {"DISTANCE PROG START ON", "BLOCKSEARCH LOCKED", "CAX TRACK ON",
                           "CAXTRACK ON [ANGLIMIT 3, OFFSET 0]"}) {
    EXPECT_TRUE(SteersBlockSearch(nc::HashCommandOf(text))) << text;
    EXPECT_EQ(RefusedHashCommand(nc::HashCommandOf(text)), "") << text;
  }
  for (const char* text : {"CALL AX [X, 1, 1]", "CAX", "TRACK ON", "VECTOR OFFSET OFF ALL"})
    EXPECT_FALSE(SteersBlockSearch(nc::HashCommandOf(text))) << text;
  // 4.2.3: vmt has no orientation angles for #VECTOR OFFSET to correct: refused, not passed.
  EXPECT_NE(RefusedHashCommand(nc::HashCommandOf("VECTOR OFFSET ON [ DS=20 DE=15 ANC=2 DRC=3 ]"))
                .find("#VECTOR OFFSET (path-dependent angle correction, block search 4.2.3) is not "
                      "supported by vmt"),
            std::string::npos);
}

}  // namespace
}  // namespace vmt::control::channel
