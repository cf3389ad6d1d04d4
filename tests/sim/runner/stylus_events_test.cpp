// A scene run with the stylus: the runner gives the backend the scene's workpiece, the ruby's
// contact shows on IPROBE_CONTACT, and driven on beyond its over-travel the stylus' crash is a
// `stylus` event in events.jsonl.

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "../sim_test_support.hpp"
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
