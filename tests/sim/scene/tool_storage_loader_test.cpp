// The tool storage axis in machine.yaml (`nc: tool_storage:`, the drive or its axis
// parameters) and a scene's `nc: tool_storage_nc:` that makes it NC-controlled (REPOS manual
// 3.4, 4.2).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <string>

#include "sim/model/model_error.hpp"
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
  EXPECT_EQ(s.nc.data.tool_storage_stations, 12);  // T1..T12, 30 deg apart
}

// The stations its T words index (REPOS manual 4.2): only the tool storage axis has them, a
// rotary one, and an NC-controlled one needs them.
TEST(ToolStorageLoaderTest, StationsAreTheToolStorageAxis) {
  const std::string from = "tool_storage: {name: T, number: 5, stations: 12,";
  auto error = [&](const std::string& name, const std::function<std::string(std::string)>& edit) {
    try {
      testing::EditedLathe(name, edit);
    } catch (const ModelError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_THAT(error("stations_negative",
                    [&](std::string y) {
                      return testing::ReplaceOnce(y, from, "tool_storage: {name: T, number: 5, "
                                                           "stations: -1,");
                    }),
              HasSubstr("nc.tool_storage.stations: must be >= 0"));
  EXPECT_THAT(error("stations_on_x",
                    [](std::string y) {
                      return testing::ReplaceOnce(y, "      number: 1\n",
                                                  "      number: 1\n      stations: 4\n");
                    }),
              HasSubstr("nc.axes[0].stations: only the tool storage axis has stations"));
  // Without stations lathe-c1's turret is the PLC's as before; NC-controlled it is refused.
  EXPECT_EQ(error("no_stations",
                  [&](std::string y) {
                    return testing::ReplaceOnce(y, from, "tool_storage: {name: T, number: 5,");
                  }),
            "");
  const std::string model = testing::OutputDir("edited_models") + "/no_stations.yaml";
  auto scene = [&](const std::string& name, const std::string& nc_keys) {
    const std::string path = testing::OutputDir("tool_storage_loader") + "/" + name + ".yaml";
    std::ofstream(path) << "scene: " << name << "\nmodel: " << model
                        << "\nduration: 0.01\nnc:\n  program: "
                        << testing::SourcePath("scenes/nc/repos_turning.mtc") << "\n"
                        << nc_keys;
    return path;
  };
  EXPECT_EQ(testing::SceneLoadError(scene("no_stations_plc", "")), "");
  const std::string path = scene("no_stations_nc", "  tool_storage_nc: yes\n");
  EXPECT_THAT(testing::SceneLoadError(path),
              HasSubstr("nc.tool_storage_nc: the machine's tool storage axis has no stations"));
}

TEST(ToolStorageLoaderTest, AMachineWithoutOneRefusesTheKey) {
  EXPECT_THAT(testing::SceneLoadError(
                  WriteScene("none", "models/lathe-c2/machine.yaml", "  tool_storage_nc: yes\n")),
              HasSubstr("nc.tool_storage_nc: the machine has no tool storage axis"));
}

}  // namespace
}  // namespace vmt::sim
