// The PLC's messages (MSG_WR) reach the operator: the NC's message list, an event in
// events.jsonl and summary.json's message list, from the PLC program that writes them.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "sim/runner/runner.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

TEST(PlcMessagesTest, ClutchTimeoutMessage220ReachesEventsAndSummary) {
  // Valve QROTMODE stuck: the changeover PLC gives up after T_CLUTCH (5 s) with message 220;
  // Control-Reset at 7 s ends the request, and the PLC takes the message back.
  const Scene scene = LoadScene(testing::SourcePath("scenes/fault-clutch-timeout.yaml"));
  RunOptions options;
  options.snapshots = false;
  options.out_dir = testing::OutputDir("plc_message_220");
  const RunResult result = RunScene(scene, options);
  EXPECT_TRUE(result.ok());

  double shown_s = -1, cleared_s = -1;
  std::ifstream events(options.out_dir + "/events.jsonl");
  for (std::string line; std::getline(events, line);) {
    const nlohmann::json e = nlohmann::json::parse(line);
    if (e["event"] != "message" || e["source"] != "plc" || e["number"] != 220) continue;
    if (e.contains("state") && e["state"] == "cleared") {
      cleared_s = e["t"].get<double>();
    } else {
      shown_s = e["t"].get<double>();
      EXPECT_EQ(e["parameter"], 0);
      EXPECT_NE(e["text"].get<std::string>().find("clutch"), std::string::npos) << e.dump();
    }
  }
  // The request goes out at once (spindle standing), the PLC waits 5 s for the clutch.
  EXPECT_NEAR(shown_s, 5.0, 0.1);
  EXPECT_NEAR(cleared_s, 7.0, 0.05);

  std::ifstream in(options.out_dir + "/summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  ASSERT_TRUE(summary.contains("messages"));
  int found = 0;
  for (const nlohmann::json& m : summary["messages"])
    if (m["source"] == "plc" && m["number"] == 220) {
      ++found;
      EXPECT_DOUBLE_EQ(m["t"].get<double>(), shown_s);
      EXPECT_DOUBLE_EQ(m["cleared_t"].get<double>(), cleared_s);
    }
  EXPECT_EQ(found, 1);
}

}  // namespace
}  // namespace vmt::sim
