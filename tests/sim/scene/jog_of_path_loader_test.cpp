// A scene's `nc: jog_of_path: FILE` (block search 4.2.1): the JogOfPath channel's program, parsed
// like the channel's; a missing file or a bad program names the scene entry and the NC line.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "sim/scene/scene.hpp"
#include "tests/sim/sim_test_support.hpp"

namespace vmt::sim {
namespace {

using ::testing::HasSubstr;

std::string WriteScene(const std::string& name, const std::string& jog_of_path) {
  const std::string dir = testing::OutputDir("jog_of_path_loader");
  const std::string path = dir + "/" + name + ".yaml";
  std::ofstream(path) << "scene: " << name
                      << "\nmodel: " << testing::SourcePath("models/lathe-c1/machine.yaml")
                      << "\nduration: 0.01\nnc:\n  program: "
                      << testing::SourcePath("scenes/nc/stepped_shaft.mtc")
                      << "\n  jog_of_path: " << jog_of_path << "\n";
  return path;
}

TEST(JogOfPathLoaderTest, TheProgramOfTheJogOfPathChannel) {
  const Scene s =
      LoadScene(WriteScene("ok", testing::SourcePath("scenes/nc/stepped_shaft_pre_return.mtc")));
  ASSERT_TRUE(s.nc.jog_of_path);
  EXPECT_EQ(s.nc.programs.size(), 1u);  // not one of the channel's programs
  EXPECT_FALSE(s.nc.jog_of_path->program.blocks.empty());
}

TEST(JogOfPathLoaderTest, AMissingFileOrABadProgramIsTheScenesError) {
  EXPECT_THAT(testing::SceneLoadError(WriteScene("missing", "no_such.mtc")),
              HasSubstr("nc.jog_of_path: cannot open NC program"));
  const std::string bad = testing::OutputDir("jog_of_path_loader") + "/bad.mtc";
  std::ofstream(bad) << "N10 G00 Z170\nN20 X24 Q\n";
  EXPECT_THAT(testing::SceneLoadError(WriteScene("bad", bad)), HasSubstr("bad.mtc:2:"));
}

}  // namespace
}  // namespace vmt::sim
