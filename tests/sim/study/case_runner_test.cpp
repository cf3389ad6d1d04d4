// A tiny study with known verdicts: over the chuck, program 99's X-first return collides (507);
// lifted and moved off to the free end, it is clear. A forked case equals the case run from the
// program's start; the runner's event hook sees what events.jsonl records.
#include "sim/study/case_runner.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "sim/runner/runner.hpp"

namespace vmt::sim::study {
namespace {

const std::string kTiny = std::string(VMT_SOURCE_DIR) + "/tests/sim/study/tiny-study.yaml";

bool FirstInterruption(const StudyCase& c) { return c.interruption == 0; }

struct Tiny {
  Scene scene = LoadScene(kTiny);
  StudyPlan plan = LoadStudyPlan(kTiny, scene);
  Reference ref;
  std::vector<Interruption> interruptions;
  std::vector<StudyCase> cases;
  Tiny() {
    const std::string dir = std::string(VMT_BINARY_DIR) + "/test_output/study/tiny-reference";
    ref = RunReference(scene, dir);
    interruptions = Interruptions(plan, ref);
    // Only the first interruption (3 s after the start: N0030, the pass at X28).
    for (const StudyCase& c : EnumerateCases(plan, interruptions))
      if (c.interruption == 0) cases.push_back(c);
  }
};

TEST(study_cases, ReferenceRunFindsTheBlocks) {
  const Tiny t;
  ASSERT_GE(t.interruptions.size(), 2u);
  EXPECT_NEAR(t.interruptions[0].t_s - t.ref.start_s, 3.0, 0.0011);
  EXPECT_EQ(t.interruptions[0].block, "N0030");
  std::vector<std::string> motion;
  for (const BlockSpan& b : t.ref.blocks)
    if (b.motion) motion.push_back(b.label);
  EXPECT_THAT(motion, ::testing::Contains("N0030"));
  EXPECT_GT(t.ref.end_s, 6.0);
  EXPECT_GT(t.ref.path.size(), 100u);
}

TEST(study_cases, TinyStudyVerdicts) {
  const Tiny t;
  ASSERT_EQ(t.cases.size(), 2u);
  std::map<std::string, CaseResult> by_retract;
  RunSubroutineCases(t.scene, t.plan, t.interruptions, 0, FirstInterruption, RunUpSharing::kFork,
                     [&](const CaseResult& r) { by_retract[r["retract"].get<std::string>()] = r; });
  ASSERT_EQ(by_retract.size(), 2u);
  const CaseResult& up = by_retract["X+ then Z+"];
  EXPECT_EQ(up["verdict"], "clear") << up.dump();
  ASSERT_TRUE(up["min_clearance_mm"].is_number()) << up.dump();
  EXPECT_GT(up["min_clearance_mm"].get<double>(), 0);
  EXPECT_GT(up["path_length_mm"].get<double>(), 39.0);  // 20 in Z, then 20 in X
  EXPECT_TRUE(up["parts"].is_null());
  EXPECT_TRUE(up["error_number"].is_null());
  const CaseResult& chuck = by_retract["over the chuck"];
  EXPECT_EQ(chuck["verdict"], "collision") << chuck.dump();
  EXPECT_EQ(chuck["error_number"], 507) << chuck.dump();  // PxxS.ERRNR: collision ahead
  EXPECT_THAT(chuck["error"].get<std::string>(), ::testing::HasSubstr("collision ahead (G77)"));
  ASSERT_TRUE(chuck["parts"].is_array());
  EXPECT_EQ(chuck["parts"].size(), 2u);
  EXPECT_EQ(chuck["point"].size(), 3u);
  EXPECT_EQ(chuck["case"], "../../../scenes/nc/99.mtc/" + t.interruptions[0].label +
                               "/over the chuck/repositioning");
}

TEST(study_cases, ForkedCaseEqualsTheCaseRunFromTheStart) {
  const Tiny t;
  std::vector<CaseResult> forked;
  RunSubroutineCases(t.scene, t.plan, t.interruptions, 0, FirstInterruption, RunUpSharing::kFork,
                     [&](const CaseResult& r) { forked.push_back(r); });
  ASSERT_EQ(forked.size(), t.cases.size());
  for (size_t i = 0; i < t.cases.size(); ++i)
    EXPECT_EQ(forked[i].dump(),
              RunCaseFromStart(t.scene, t.plan, t.interruptions, t.cases[i]).dump());
}

// Shared in memory, every interruption's cases, both retracts and both modes (so that a run goes
// back to the interruption, to the held feed and to the retract's end), give the bytes of the
// forked cases and of the cases run from the start, in the same order.
TEST(study_cases, CasesSharedInMemoryEqualForkedAndFromStart) {
  Tiny t;
  t.plan.modes = {ReposMode::kRepositioning, ReposMode::kRestart};
  const auto all = [](const StudyCase&) { return true; };
  std::vector<std::string> forked, in_memory, alone;
  const auto into = [](std::vector<std::string>& v) {
    return [&v](const CaseResult& r) { v.push_back(r.dump()); };
  };
  RunSubroutineCases(t.scene, t.plan, t.interruptions, 0, all, RunUpSharing::kFork, into(forked));
  RunSubroutineCases(t.scene, t.plan, t.interruptions, 0, all, RunUpSharing::kMemory,
                     into(in_memory));
  RunSubroutineCases(t.scene, t.plan, t.interruptions, 0, all, RunUpSharing::kNone, into(alone));
  ASSERT_GE(t.interruptions.size(), 2u);
  ASSERT_EQ(forked.size(), t.interruptions.size() * 4);
  EXPECT_EQ(in_memory, forked);
  EXPECT_EQ(alone, forked);
}

// The watch sees each case in the case's own process: at the tick it ended (the machine not
// stepped on), then once it is over, with its result; the same forked as from the start. It
// writes what it saw to files, so that a forked case's process tells too.
TEST(study_cases, WatchSeesTheCaseAtItsEndForkedOrNot) {
  const Tiny t;
  const auto watch_into = [](const std::string& dir) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    CaseWatch w;
    const auto write = [dir](const StudyCase& c, const std::string& what, const std::string& s) {
      std::ofstream(dir + "/" + std::to_string(c.index) + "." + what) << s;
    };
    w.at_end = [write](const SceneRun& run, const StudyCase& c) {
      nlohmann::ordered_json j = {{"t", run.time_s()}, {"q", run.joint_positions()}};
      write(c, "end", j.dump());
    };
    w.after = [write](const SceneRun& run, const StudyCase& c, const CaseResult& r) {
      write(c, "after", nlohmann::ordered_json({{"t", run.time_s()}, {"case", r["case"]}}).dump());
    };
    return w;
  };
  const auto read = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return nlohmann::ordered_json::parse(in, nullptr, false);
  };
  const std::string forked = std::string(VMT_BINARY_DIR) + "/test_output/study/watch-forked";
  const std::string alone = std::string(VMT_BINARY_DIR) + "/test_output/study/watch-alone";
  const CaseWatch in_fork = watch_into(forked), from_start = watch_into(alone);
  std::vector<CaseResult> results;
  RunSubroutineCases(
      t.scene, t.plan, t.interruptions, 0, FirstInterruption, RunUpSharing::kFork,
      [&](const CaseResult& r) { results.push_back(r); }, &in_fork);
  for (const StudyCase& c : t.cases)
    (void)RunCaseFromStart(t.scene, t.plan, t.interruptions, c, &from_start);
  ASSERT_EQ(results.size(), t.cases.size());
  for (size_t i = 0; i < t.cases.size(); ++i) {
    const std::string n = std::to_string(t.cases[i].index);
    const nlohmann::ordered_json end = read(forked + "/" + n + ".end");
    const nlohmann::ordered_json after = read(forked + "/" + n + ".after");
    ASSERT_TRUE(end.is_object()) << n;
    ASSERT_TRUE(after.is_object()) << n;
    EXPECT_EQ(end.dump(), read(alone + "/" + n + ".end").dump()) << n;
    EXPECT_EQ(after.dump(), read(alone + "/" + n + ".after").dump()) << n;
    EXPECT_EQ(after["case"], results[i]["case"]);
    EXPECT_GT(end["t"].get<double>(), results[i]["t_interrupt_s"].get<double>());
    EXPECT_GE(after["t"].get<double>(), end["t"].get<double>());
    EXPECT_EQ(end["q"].size(), t.scene.model->joints.size());
  }
}

TEST(study_runner_hook, OnEventSeesWhatEventsJsonlRecords) {
  const Scene scene = LoadScene(std::string(VMT_SOURCE_DIR) + "/scenes/repos-collision.yaml");
  RunOptions options;
  options.snapshots = false;
  options.out_dir = std::string(VMT_BINARY_DIR) + "/test_output/study/hook";
  std::string seen;
  options.on_event = [&](const nlohmann::ordered_json& e) { seen += e.dump() + "\n"; };
  RunScene(scene, options);
  std::ifstream in(options.out_dir + "/events.jsonl", std::ios::binary);
  const std::string written((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(seen, written);
  EXPECT_THAT(seen, ::testing::HasSubstr("\"event\":\"path_guard\""));
}

}  // namespace
}  // namespace vmt::sim::study
