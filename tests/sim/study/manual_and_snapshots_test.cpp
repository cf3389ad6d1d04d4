// Manual repositioning cases (repositioning manual 3) against a hand-built expectation, the
// worst cases' pictures linked from the report, a study run twice giving the same bytes, and a
// study of one job that forks no process.
#include <gmock/gmock.h>
#include <pthread.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "../sim_test_support.hpp"
#include "render/offscreen_renderer.hpp"
#include "sim/study/case_snapshots.hpp"
#include "sim/study/study.hpp"
#include "sim/study/study_report.hpp"

namespace vmt::sim::study {
namespace {

using vmt::sim::testing::ReadBytes;

const std::string kManual = std::string(VMT_SOURCE_DIR) + "/tests/sim/study/tiny-manual-study.yaml";
const std::string kTiny = std::string(VMT_SOURCE_DIR) + "/tests/sim/study/tiny-study.yaml";

/// A fresh folder of the running test: ctest runs these suites in parallel, and each builds its
/// own reference run.
std::string Out(const std::string& name) {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string dir = std::string(VMT_BINARY_DIR) + "/test_output/study/" +
                          test->test_suite_name() + "." + test->name() + "/" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

struct TinyManual {
  Scene scene = LoadScene(kManual);
  StudyPlan plan = LoadStudyPlan(kManual, scene);
  Reference ref;
  std::vector<Interruption> interruptions;
  std::vector<StudyCase> cases;  // the first interruption's (3 s: N0030, the pass at X28)
  TinyManual() {
    ref = RunReference(scene, Out("tiny-manual-reference"));
    interruptions = Interruptions(plan, ref);
    for (const StudyCase& c : EnumerateCases(plan, interruptions))
      if (c.interruption == 0) cases.push_back(c);
  }
  std::map<std::string, CaseResult> Run(RunUpSharing sharing = RunUpSharing::kFork) const {
    std::map<std::string, CaseResult> by_order;
    for (size_t s = 0; s < plan.subroutines.size(); ++s)
      RunSubroutineCases(
          scene, plan, interruptions, s, [](const StudyCase& c) { return c.interruption == 0; },
          sharing, [&](const CaseResult& r) { by_order[r["subroutine"].get<std::string>()] = r; });
    return by_order;
  }
};

TEST(study_manual, VerdictsOfTheJogOrders) {
  const TinyManual t;
  ASSERT_EQ(t.cases.size(), 2u);
  std::map<std::string, CaseResult> got = t.Run();
  ASSERT_EQ(got.size(), 2u);
  // The hand-built expectation: the retract left the tool 70 mm up and 75 mm toward the chuck.
  // Z first: 75 mm in Z back over the part, then 70 mm down in X to the interruption point;
  // every jog clear, the conditions restored (CREST), no subroutine, no NC error.
  const CaseResult& zx = got["manual Z,X"];
  EXPECT_EQ(zx["verdict"], "clear") << zx.dump();
  EXPECT_EQ(zx["case"], "manual Z,X/" + t.interruptions[0].label + "/over the chuck/repositioning");
  EXPECT_TRUE(zx["error"].is_null()) << zx.dump();
  EXPECT_TRUE(zx["parts"].is_null());
  ASSERT_TRUE(zx["min_clearance_mm"].is_number()) << zx.dump();
  EXPECT_GT(zx["min_clearance_mm"].get<double>(), 0);
  // The path corner by corner (from the PathGuard records of the increments, to the µm).
  EXPECT_NEAR(zx["path_length_mm"].get<double>(), 145.0, 0.002) << zx.dump();
  ASSERT_EQ(zx["path"].size(), 3u) << zx.dump();
  const auto& first = zx["path"][0];
  const auto& corner = zx["path"][1];
  const auto& last = zx["path"][2];
  EXPECT_NEAR(corner[0].get<double>(), first[0].get<double>(), 0.001) << zx.dump();
  EXPECT_NEAR(corner[1].get<double>(), last[1].get<double>(), 0.001) << zx.dump();
  EXPECT_NEAR(first[0].get<double>() - last[0].get<double>(), 70.0, 0.001) << zx.dump();
  EXPECT_NEAR(last[1].get<double>() - first[1].get<double>(), 75.0, 0.001) << zx.dump();
  // X first: the jog down from over the chuck runs the tool into it; PathGuard refuses it.
  const CaseResult& xz = got["manual X,Z"];
  EXPECT_EQ(xz["verdict"], "collision") << xz.dump();
  ASSERT_TRUE(xz["parts"].is_array()) << xz.dump();
  EXPECT_EQ(xz["parts"].size(), 2u);
  EXPECT_EQ(xz["point"].size(), 3u);
  // Refused before it started: nothing travelled; the path is the start and the contact.
  EXPECT_EQ(xz["path_length_mm"].get<double>(), 0) << xz.dump();
  EXPECT_EQ(xz["path"].size(), 2u) << xz.dump();
}

TEST(study_manual, ForkedManualCaseEqualsTheCaseRunFromTheStart) {
  const TinyManual t;
  const std::map<std::string, CaseResult> forked = t.Run();
  const std::map<std::string, CaseResult> alone = t.Run(RunUpSharing::kNone);
  const std::map<std::string, CaseResult> in_memory = t.Run(RunUpSharing::kMemory);
  ASSERT_EQ(forked.size(), 2u);
  for (const auto& [order, r] : forked) {
    EXPECT_EQ(r.dump(), alone.at(order).dump()) << order;
    EXPECT_EQ(r.dump(), in_memory.at(order).dump()) << order;
  }
}

TEST(study_snapshots, WorstCasesPicturedAndLinked) {
  const TinyManual t;
  std::vector<CaseResult> results;
  for (const auto& [order, r] : t.Run()) results.push_back(r);
  const std::vector<std::string> ids = WorstCaseIds(results, 3);
  ASSERT_EQ(ids.size(), 2u);  // the one collision of X,Z; the clear case of Z,X (the tightest)
  const std::string dir = Out("snapshots");
  const std::map<std::string, std::string> index =
      SnapshotCases(t.scene, t.plan, t.interruptions, results, ids, dir);
  ASSERT_EQ(index.size(), 2u);
  for (const auto& [id, file] : index) {
    EXPECT_EQ(file, SnapshotFileOf(id));
    EXPECT_THAT(file, ::testing::MatchesRegex("snapshots/[A-Za-z0-9._-]+\\.png"));
    EXPECT_GT(std::filesystem::file_size(dir + "/" + file), 1000u) << file;
  }
  EXPECT_EQ(ReadSnapshotIndex(dir), index);
  const std::string html = ReportHtml("t", results, &t.ref, index);
  for (const auto& [id, file] : index)
    EXPECT_THAT(html, ::testing::HasSubstr("<a href=\"" + file + "\">")) << id;
  // Deterministic names: the same cases give the same files again (kept, not rendered twice).
  EXPECT_EQ(SnapshotCases(t.scene, t.plan, t.interruptions, results, ids, dir), index);
}

// Two processes side by side take the same pictures, to the byte, as one alone. Only a process
// that has not rendered yet forks them: a suite of its own, which ctest runs in a process of
// its own.
TEST(study_pictures_side_by_side, AreThePicturesTakenOneByOne) {
  if (render::RendererStarted()) GTEST_SKIP() << "this process has rendered: run the test alone";
  const TinyManual t;
  std::vector<CaseResult> results;
  for (const auto& [order, r] : t.Run()) results.push_back(r);
  const std::vector<std::string> ids = WorstCaseIds(results, 3);
  ASSERT_EQ(ids.size(), 2u);
  const std::string one = Out("snapshots-one"), two = Out("snapshots-two");
  const std::map<std::string, std::string> side_by_side =
      SnapshotCases(t.scene, t.plan, t.interruptions, results, ids, two, {}, 2);
  EXPECT_FALSE(render::RendererStarted());  // the helpers rendered, not this process
  const std::map<std::string, std::string> alone =
      SnapshotCases(t.scene, t.plan, t.interruptions, results, ids, one);
  ASSERT_EQ(side_by_side, alone);
  for (const auto& [id, file] : alone)
    EXPECT_EQ(ReadBytes(two + "/" + file), ReadBytes(one + "/" + file)) << file;
  EXPECT_EQ(ReadSnapshotIndex(two), alone);
}

TEST(study_determinism, SameStudyTwiceGivesTheSameBytes) {
  std::string jsonl[2], csv[2];
  for (int k = 0; k < 2; ++k) {
    StudyOptions o;
    o.scene = kTiny;
    o.out_dir = Out("twice-" + std::to_string(k));
    o.jobs = 2;  // the workers' lines interleave; the files come out in case id order
    o.snapshots = 0;
    const StudySummary s = RunStudy(o);
    EXPECT_GT(s.run, 2u);
    EXPECT_GT(s.cases_cpu_s, 0);
    jsonl[k] = ReadText(o.out_dir + "/cases.jsonl");
    csv[k] = ReadText(o.out_dir + "/cases.csv");
  }
  EXPECT_FALSE(jsonl[0].empty());
  EXPECT_EQ(jsonl[0], jsonl[1]);
  EXPECT_EQ(csv[0], csv[1]);
}

// Every fork of this process from the first call on.
int ForksSoFar() {
  static int forks = 0;
  static const bool counting = [] {
    return ::pthread_atfork([] { ++forks; }, nullptr, nullptr) == 0;
  }();
  EXPECT_TRUE(counting);
  return forks;
}

TEST(study_without_fork, OneJobRunsItsCasesInItsOwnProcess) {
  std::string jsonl[2];
  int forks[2];
  for (const int jobs : {1, 2}) {
    StudyOptions o;
    o.scene = kTiny;
    o.out_dir = Out("jobs-" + std::to_string(jobs));
    o.jobs = jobs;
    o.snapshots = 0;
    const int before = ForksSoFar();
    const StudySummary s = RunStudy(o);
    forks[jobs - 1] = ForksSoFar() - before;
    EXPECT_GT(s.run, 2u);
    EXPECT_GT(s.cases_cpu_s, 0);
    jsonl[jobs - 1] = ReadText(o.out_dir + "/cases.jsonl");
  }
  EXPECT_EQ(forks[0], 0) << "one job with run-ups in memory forks nothing";
  EXPECT_GT(forks[1], 0) << "two jobs are worker processes (the count is seen)";
  EXPECT_FALSE(jsonl[0].empty());
  EXPECT_EQ(jsonl[0], jsonl[1]);
}

}  // namespace
}  // namespace vmt::sim::study
