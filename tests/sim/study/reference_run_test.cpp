// The reference run of a study: the program once, uninterrupted; its blocks' time spans, its end
// and the tool's path, and reference.json back and forth.
#include "sim/study/reference_run.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace vmt::sim::study {
namespace {

const std::string kTiny = std::string(VMT_SOURCE_DIR) + "/tests/sim/study/tiny-study.yaml";
std::string Out(const std::string& name) {
  return std::string(VMT_BINARY_DIR) + "/test_output/study/" + name;
}

TEST(study_reference, BlocksFollowEachOtherFromStartToEnd) {
  const Reference ref = RunReference(LoadScene(kTiny), Out("reference-blocks"));
  ASSERT_GE(ref.blocks.size(), 3u);
  EXPECT_GT(ref.end_s, ref.start_s);
  // The first block is current from the NC's first cycle on.
  EXPECT_NEAR(ref.blocks.front().start_s, ref.start_s, 0.001 + 1e-9);
  EXPECT_LE(ref.blocks.back().end_s, ref.end_s);
  for (size_t i = 0; i < ref.blocks.size(); ++i) {
    const BlockSpan& b = ref.blocks[i];
    EXPECT_LE(b.start_s, b.end_s) << b.label;
    EXPECT_GE(b.line, 1) << b.label;  // a cycle between two blocks is the one before's
    // Labels are the block's N number where the line has one, else the line.
    EXPECT_TRUE(b.label[0] == 'N' || b.label == "L" + std::to_string(b.line)) << b.label;
    if (i > 0) {
      EXPECT_NE(b.line, ref.blocks[i - 1].line);  // a span per block as it was current
      EXPECT_GE(b.start_s, ref.blocks[i - 1].end_s) << b.label;
    }
  }
  // The tool's path every 10 ms from the start to the end, continuous (no jump above the
  // axes' rapid in 10 ms).
  const double samples = (ref.end_s - ref.start_s) / 0.01;
  EXPECT_NEAR(static_cast<double>(ref.path.size()), samples, 2 + samples * 0.01);
  for (size_t i = 1; i < ref.path.size(); ++i)
    ASSERT_LT(std::hypot(ref.path[i].first - ref.path[i - 1].first,
                         ref.path[i].second - ref.path[i - 1].second),
              10.0)
        << i;
}

TEST(study_reference, AProgramThatDoesNotEndIsAnErrorNamingTheScene) {
  Scene scene = LoadScene(kTiny);
  scene.duration_s = 1.0;  // the tiny program runs for several seconds
  try {
    RunReference(scene, Out("reference-short"));
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("tiny-study.yaml"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("did not end within its duration"));
  }
}

TEST(study_reference, JsonBackAndForthExactly) {
  Reference r;
  r.start_s = 0.1;
  r.end_s = 12.345678901234567;
  r.blocks = {{3, "N0030", 0.1, 2.5, true}, {4, "L4", 2.5, 2.75, false}};
  r.path = {{40.0, 120.0}, {1.0 / 3, -2e-9}};
  const Reference back = ReferenceFromJson(ReferenceJson(r));
  EXPECT_EQ(back.start_s, r.start_s);
  EXPECT_EQ(back.end_s, r.end_s);
  ASSERT_EQ(back.blocks.size(), 2u);
  EXPECT_EQ(back.blocks[0].label, "N0030");
  EXPECT_EQ(back.blocks[1].line, 4);
  EXPECT_EQ(back.blocks[1].end_s, 2.75);
  EXPECT_TRUE(back.blocks[0].motion);
  EXPECT_FALSE(back.blocks[1].motion);
  ASSERT_EQ(back.path.size(), 2u);
  EXPECT_EQ(back.path[1].first, 1.0 / 3);  // bit for bit: a resumed study plans the same cases
  EXPECT_EQ(back.path[1].second, -2e-9);
  EXPECT_THROW(ReferenceFromJson("{\"start_s\": 1"), std::exception);
  EXPECT_THROW(ReferenceFromJson("{\"start_s\": 1, \"end_s\": 2}"), std::exception);
}

}  // namespace
}  // namespace vmt::sim::study
