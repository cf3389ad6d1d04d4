// The tool storage axis in machine.yaml (`nc: tool_storage:`, the drive or its axis
// parameters) and a scene's `nc: tool_storage_nc:` that makes it NC-controlled (REPOS manual
// 3.4, 4.2).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "sim/scene/scene.hpp"
#include "tests/sim/sim_test_support.hpp"

namespace vmt::sim {
namespace {

using ::testing::HasSubstr;

std::string WriteScene(const std::string& name, const std::string& model,
                       const std::string& nc_keys) {
  const std::string path = testing::OutputDir("tool_storage_loader") + "/" + name + ".yaml";
  std::ofstream(path) << "scene: " << name << "\nmodel: " << testing::SourcePath(model)
                      << "\nduration: 0.01\nnc:\n  program: "
                      << testing::SourcePath("scenes/nc/repos_turning.mtc") << "\n"
                      << nc_keys;
  return path;
}

TEST(ToolStorageLoaderTest, LatheC1sTurretWithItsJoggingParameters) {
  const Scene plc = LoadScene(WriteScene("plc", "models/lathe-c1/machine.yaml", ""));
  EXPECT_FALSE(plc.nc.tool_storage_nc);  // the PLC indexes it unless the scene says
  const Scene s =
      LoadScene(WriteScene("nc", "models/lathe-c1/machine.yaml", "  tool_storage_nc: yes\n"));
  EXPECT_TRUE(s.nc.tool_storage_nc);
  const int t = s.model->DriveIndex("T");
  EXPECT_EQ(s.nc.data.tool_storage_drive, t);
  const control::axes::AxisParameters& a = s.nc.data.tool_storage;
  EXPECT_EQ(a.drive, t);
  EXPECT_EQ(a.name, "T");
  EXPECT_TRUE(a.rotary);
  EXPECT_DOUBLE_EQ(a.jog_per_s, 30);         // Cxx.020 1800 deg/min
  EXPECT_DOUBLE_EQ(a.jog_rapid_per_s, 180);  // Cxx.021 10800 deg/min
  EXPECT_DOUBLE_EQ(a.jog_distance, 30);      // Cxx.022: one station
  EXPECT_DOUBLE_EQ(a.acceleration, 7200);    // the drive's limit
}

TEST(ToolStorageLoaderTest, AMachineWithoutOneRefusesTheKey) {
  EXPECT_THAT(testing::SceneLoadError(
                  WriteScene("none", "models/lathe-c2/machine.yaml", "  tool_storage_nc: yes\n")),
              HasSubstr("nc.tool_storage_nc: the machine has no tool storage axis"));
}

}  // namespace
}  // namespace vmt::sim
