// The headstock's status indication as a run reports it (C-axis manual 2.3 Status Indication):
// summary.json's spindle_status (speeds in spindle operation, null -- lines -- in rotary axis
// mode, the overrides always) and the headstock events' "speeds", on lathe-c2.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "sim/runner/runner.hpp"
#include "sim/scene/scene.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using testing::OutputDir;
using testing::SourcePath;

std::string WriteScene(const std::string& dir) {
  std::ofstream(dir + "/status.mtc") << "N1 M03 S1000\nN2 G04 F1\nN3 G01 C90 F3600\nN4 RET\n";
  const std::string path = dir + "/status.yaml";
  std::ofstream(path) << "scene: status\nmodel: " << SourcePath("models/lathe-c2/machine.yaml")
                      << "\nbackend: kinematic\nduration: 3\n"
                         "initial: {Z: 400, X: 150, W: 300}\n"
                         "nc: {program: status.mtc, override: 50}\n"
                         "timeline:\n  - nc: start\n";
  return path;
}

nlohmann::json RunUntil(const std::string& scene_path, const std::string& out, double until_s) {
  RunOptions options;
  options.out_dir = OutputDir(out);
  options.snapshots = false;
  options.until_s = until_s;
  RunScene(LoadScene(scene_path), options);
  std::ifstream in(options.out_dir + "/summary.json");
  return nlohmann::json::parse(in);
}

TEST(HeadstockStatusOutput, SummaryShowsSpeedsInSpindleModeAndLinesInRotaryMode) {
  const std::string dir = OutputDir("headstock_status");
  const std::string scene = WriteScene(dir);

  const nlohmann::json spindle = RunUntil(scene, "headstock_status/spindle", 0.5)["spindle_status"];
  EXPECT_EQ(spindle["axis"], "S1");
  EXPECT_EQ(spindle["speeds"], "shown");
  EXPECT_DOUBLE_EQ(spindle["programmed_rpm"].get<double>(), 1000);
  EXPECT_GT(spindle["actual_rpm"].get<double>(), 100);       // running up
  EXPECT_DOUBLE_EQ(spindle["max_rpm"].get<double>(), 4000);  // lathe-c2's Cxx.049
  EXPECT_DOUBLE_EQ(spindle["spindle_override_percent"].get<double>(), 100);
  EXPECT_DOUBLE_EQ(spindle["feed_override_percent"].get<double>(), 50);

  const std::string out = OutputDir("headstock_status/rotary");
  const nlohmann::json rotary = RunUntil(scene, "headstock_status/rotary", 3)["spindle_status"];
  EXPECT_EQ(rotary["axis"], "C");
  EXPECT_EQ(rotary["speeds"], "lines");
  EXPECT_TRUE(rotary["programmed_rpm"].is_null());
  EXPECT_TRUE(rotary["actual_rpm"].is_null());
  EXPECT_TRUE(rotary["max_rpm"].is_null());
  EXPECT_DOUBLE_EQ(rotary["spindle_override_percent"].get<double>(), 100);
  EXPECT_DOUBLE_EQ(rotary["feed_override_percent"].get<double>(), 50);

  // The events: the display's switches, each with what the status indication shows.
  std::ifstream events(out + "/events.jsonl");
  std::vector<std::string> shown;
  for (std::string line; std::getline(events, line);) {
    const nlohmann::json e = nlohmann::json::parse(line);
    if (e["event"] == "headstock" && e.contains("speeds"))
      shown.push_back(e["axis"].get<std::string>() + " " + e["speeds"].get<std::string>());
  }
  EXPECT_THAT(shown, ::testing::Contains("S1 shown"));
  EXPECT_EQ(shown.back(), "C lines");
}

}  // namespace
}  // namespace vmt::sim
