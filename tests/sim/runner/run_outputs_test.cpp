// What a run leaves when a file cannot be written or the run is stopped: the other files whole,
// summary.json naming the lost file or the stop, no temporary beside them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../sim_test_support.hpp"
#include "sim/runner/runner.hpp"

namespace vmt::sim {
namespace {

using ::testing::ElementsAre;
using testing::OutputDir;
using testing::ReadBytes;
using testing::SourcePath;

nlohmann::json Summary(const std::string& dir) {
  return nlohmann::json::parse(ReadBytes(dir + "/summary.json"));
}

bool HasTemporary(const std::string& dir) {
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().filename().string().find(".tmp-") != std::string::npos) return true;
  return false;
}

TEST(RunOutputs, AFileThatCannotBeWrittenIsNamedAndTheOthersAreWhole) {
  const Scene scene = LoadScene(SourcePath("scenes/jog.yaml"));
  RunOptions options;
  options.out_dir = OutputDir("run_outputs_full");
  options.snapshots = false;
  std::filesystem::remove_all(options.out_dir);
  std::filesystem::create_directories(options.out_dir);
  std::filesystem::create_symlink("/dev/full", options.out_dir + "/events.jsonl");
  const RunResult r = RunScene(scene, options);
  const std::string error =
      "cannot write " + options.out_dir + "/events.jsonl: No space left on device";
  EXPECT_THAT(r.write_errors, ElementsAre(error));
  EXPECT_TRUE(r.ok());  // the run itself held: its result is kept
  const nlohmann::json summary = Summary(options.out_dir);
  EXPECT_EQ(summary["write_errors"], nlohmann::json::array({error}));
  EXPECT_EQ(summary["trace_digest"], r.trace_digest);
  EXPECT_FALSE(summary.contains("stopped_early"));
  EXPECT_EQ(ReadBytes(options.out_dir + "/trace.csv").back(), '\n');
  EXPECT_FALSE(HasTemporary(options.out_dir));
}

TEST(RunOutputs, AStoppedRunSaysSoAndWhen) {
  const Scene scene = LoadScene(SourcePath("scenes/jog.yaml"));
  RunOptions options;
  options.out_dir = OutputDir("run_outputs_stopped");
  options.snapshots = false;
  std::filesystem::remove_all(options.out_dir);
  int ticks = 0;
  const RunResult r =
      RunScene(scene, options, [&] { return ++ticks > 4000 ? std::string("SIGTERM") : ""; });
  EXPECT_EQ(r.stop_reason, "SIGTERM");
  EXPECT_TRUE(r.write_errors.empty());
  EXPECT_NEAR(r.simulated_s, 1.0, 0.001);  // 4000 ticks of 250 us
  const nlohmann::json summary = Summary(options.out_dir);
  EXPECT_EQ(summary["stopped_early"], true);
  EXPECT_EQ(summary["stop_reason"], "SIGTERM");
  EXPECT_NEAR(summary["simulated_time_s"].get<double>(), r.simulated_s, 1e-9);
  EXPECT_EQ(ReadBytes(options.out_dir + "/trace.csv").back(), '\n');
  EXPECT_FALSE(HasTemporary(options.out_dir));
}

TEST(RunOutputs, ARunToItsEndRemovesAnEarlierSummaryFirstAndSaysNoStop) {
  const Scene scene = LoadScene(SourcePath("scenes/jog.yaml"));
  RunOptions options;
  options.out_dir = OutputDir("run_outputs_whole");
  options.snapshots = false;
  std::filesystem::remove_all(options.out_dir);
  std::filesystem::create_directories(options.out_dir);
  std::ofstream(options.out_dir + "/summary.json") << "{\"old\": true}";
  bool summary_seen_during_run = false;
  options.on_event = [&](const nlohmann::ordered_json&) {
    summary_seen_during_run =
        summary_seen_during_run || std::filesystem::exists(options.out_dir + "/summary.json");
  };
  const RunResult r = RunScene(scene, options);
  EXPECT_FALSE(summary_seen_during_run);
  EXPECT_TRUE(r.stop_reason.empty());
  const nlohmann::json summary = Summary(options.out_dir);
  EXPECT_FALSE(summary.contains("stopped_early"));
  EXPECT_FALSE(summary.contains("write_errors"));
  EXPECT_FALSE(summary.contains("old"));
}

}  // namespace
}  // namespace vmt::sim
