// A scene run with the stylus: the runner gives the backend the scene's workpiece, the ruby's
// contact shows on IPROBE_CONTACT, and driven on beyond its over-travel the stylus' crash is a
// `stylus` event in events.jsonl.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../sim_test_support.hpp"
#include "sim/backend/probe_wiring.hpp"
#include "sim/runner/runner.hpp"

namespace vmt::sim {
namespace {

TEST(StylusEventsTest, TheRubyDrivenIntoThePartIsAStylusEvent) {
  const std::string dir = testing::OutputDir("stylus_events");
  const std::string path = dir + "/scene.yaml";
  // T3 (the probe) at X 31: the ruby's lowest point 1 mm off the d60 shaft; X down to 28.5
  // deflects it 1.5 mm, beyond its 1 mm over-travel.
  std::ofstream(path) << "scene: stylus-events\nmodel: "
                      << testing::SourcePath("models/lathe-c1/machine.yaml")
                      << "\nbackend: kinematic\nduration: 1.2\n"
                         "workpiece: {diameter: 60, length: 160, z: 60}\n"
                         "initial: {Z: 100, X: 31, T: 60}\n"
                         "timeline:\n"
                         "  - output: {name: QPROBE_ON, value: true}\n"
                         "  - wait_until: {input: IPROBE_READY, value: true, timeout: 1}\n"
                         "  - move: {axis: X, to: 28.5, feed: 600}\n";
  RunOptions options;
  options.out_dir = dir;
  options.snapshots = false;
  const RunResult r = RunScene(LoadScene(path), options);
  EXPECT_TRUE(r.ok());
  const std::string events = testing::ReadBytes(dir + "/events.jsonl");
  EXPECT_NE(events.find("\"event\":\"input\",\"name\":\"IPROBE_CONTACT\",\"value\":1"),
            std::string::npos)
      << events;
  const size_t at = events.find("\"event\":\"stylus\",\"state\":\"over_travel\",\"T\":3,"
                                "\"sphere\":1,\"parts\":[\"probe_ruby\",\"workpiece\"],"
                                "\"point\":[30.0,0.0,160.0]}");
  ASSERT_NE(at, std::string::npos) << events;
  EXPECT_EQ(events.find("\"event\":\"stylus\"", at + 1), std::string::npos);  // once
}

}  // namespace
}  // namespace vmt::sim

namespace vmt::sim {
namespace {

// The measuring scene: each latch event gives the drive's measured value beside the exact
// contact; the exact contact is the analytic surface less the pre-travel (5 µm), the measured
// value within the feed's travel in 170 µs (7.3: the most between edge and position value;
// 200 mm/min: 0.57 µm) and half an encoder increment of it.
TEST(StylusEventsTest, ProbeLatchEventsShowTheSamplingError) {
  const std::string dir = testing::OutputDir("probe_latch_events");
  RunOptions options;
  options.out_dir = dir;
  options.snapshots = false;
  const RunResult r = RunScene(LoadScene(testing::SourcePath("scenes/measure-shaft.yaml")),
                               options);
  EXPECT_TRUE(r.ok());
  std::ifstream events(dir + "/events.jsonl");
  std::string line;
  int x_latches = 0, z_latches = 0;
  const double feed_mm_s = 200.0 / 60, half_increment_mm = 0.5e-4;
  while (std::getline(events, line)) {
    const auto e = nlohmann::json::parse(line);
    if (e["event"] != "probe_latch") continue;
    const double exact = e["exact_position"], measured = e["measured_value"];
    EXPECT_LE(std::abs(measured - exact), feed_mm_s * kLatchMaxDelayS + half_increment_mm)
        << line;
    EXPECT_NEAR(e["sampling_error"].get<double>(), measured - exact, 2e-6) << line;
    // The axis that measured stands where the ruby met the surface, less the pre-travel: X
    // reads the ruby's lowest point (radius 30 and 20.05), Z its centre (faces at 160, 130).
    // (Both drives latch each contact; the other axis stands still elsewhere.)
    if (e["drive"] == "X" && (std::abs(exact - 30) < 1 || std::abs(exact - 20.5) < 0.5)) {
      const bool d60 = exact > 25;
      EXPECT_NEAR(exact, (d60 ? 30.0 : 20.05) - 0.005, 1e-7) << line;
      ++x_latches;
    }
    if (e["drive"] == "Z" && (std::abs(exact - 163) < 1 || std::abs(exact - 133) < 1)) {
      const bool end_face = exact > 150;
      EXPECT_NEAR(exact, (end_face ? 163.0 : 133.0) - 0.005, 1e-7) << line;
      ++z_latches;
    }
  }
  EXPECT_EQ(x_latches, 3);  // the d60 calibration, P1 (d60), P2 (d40.1)
  EXPECT_EQ(z_latches, 3);  // the end face calibration, P3, P4 (shoulder)
}

}  // namespace
}  // namespace vmt::sim
