#include "sim/model/nesting_depth.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/sim/sim_test_support.hpp"

namespace vmt::sim {
namespace {

std::string Repeat(const std::string& s, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += s;
  return out;
}

TEST(XmlNesting, CountsElementsNotCommentsOrSelfClosingTags) {
  const std::string ok =
      "<?xml version=\"1.0\"?>\n<!-- <a><a><a> -->\n<robot name=\"r\">\n"
      "  <link name=\"a>b\"><visual><geometry><mesh filename=\"m.stl\"/></geometry></visual>"
      "</link>\n<![CDATA[<a><a><a>]]>\n</robot>\n";
  EXPECT_EQ(XmlNestingBeyond(ok, 4), 0);
  EXPECT_EQ(XmlNestingBeyond(ok, 3), 4);  // robot > link > visual > geometry, on line 4
}

TEST(XmlNesting, FindsADeepNestingAtItsLine) {
  const std::string deep = "<robot>\n" + Repeat("<a>", 50000) + Repeat("</a>", 50000) + "</robot>";
  EXPECT_EQ(XmlNestingBeyond(deep, kMaxNestingDepth), 2);
  const std::string siblings = "<robot>" + Repeat("<a></a>", 50000) + "</robot>";
  EXPECT_EQ(XmlNestingBeyond(siblings, 2), 0);
}

TEST(YamlNesting, CountsBlockAndFlowCollections) {
  const std::string scene =
      "scene: x   # [[[[ not nesting\n"
      "workpiece:\n"
      "  sections:\n"
      "    - {from: 0, to: 130, diameter: 60}\n"
      "text: |\n"
      "    [[[[ a block scalar's text\n"
      "name: '[[[[' \n"
      "quote: \"{{{{ \\\" {{\"\n"
      "list: [a, [b, c]]\n";
  // map > workpiece > sections list > flow map; the entry and its flow map count apart, so
  // the count errs by one on the deep side.
  EXPECT_EQ(YamlNestingBeyond(scene, 5), 0);
  EXPECT_EQ(YamlNestingBeyond(scene, 4), 4);
}

// "a:\"" is plain text, not the start of a quoted scalar that would hide what follows.
TEST(YamlNesting, AQuoteInsidePlainTextHidesNothing) {
  EXPECT_EQ(YamlNestingBeyond("x: a:\"\ny: " + Repeat("[", 200) + Repeat("]", 200), 100), 2);
  EXPECT_EQ(YamlNestingBeyond("x: it's\ny: " + Repeat("[", 200) + Repeat("]", 200), 100), 2);
}

TEST(YamlNesting, FindsDeepFlowBlockAndEntryNesting) {
  EXPECT_EQ(YamlNestingBeyond("a: " + Repeat("[", 100000) + Repeat("]", 100000), 100), 1);
  std::string block;
  for (int i = 0; i < 200; ++i) block += std::string(size_t(i) * 2, ' ') + "a:\n";
  EXPECT_EQ(YamlNestingBeyond(block, 100), 101);
  EXPECT_EQ(YamlNestingBeyond(Repeat("- ", 500) + "x\n", 100), 1);
}

// The limit leaves room: every shipped scene and model nests far less deep.
TEST(YamlNesting, ShippedFilesStayWellBelowTheLimit) {
  int files = 0;
  for (const char* dir : {"scenes", "models", "examples"}) {
    const std::filesystem::path root = testing::SourcePath(dir);
    if (!std::filesystem::exists(root)) continue;
    for (const auto& e : std::filesystem::recursive_directory_iterator(root)) {
      const std::string ext = e.path().extension().string();
      if (ext != ".yaml" && ext != ".urdf") continue;
      const std::string text = testing::ReadBytes(e.path().string());
      const int line = ext == ".yaml" ? YamlNestingBeyond(text, 12) : XmlNestingBeyond(text, 12);
      EXPECT_EQ(line, 0) << e.path();
      ++files;
    }
  }
  EXPECT_GT(files, 50);
}

}  // namespace
}  // namespace vmt::sim
