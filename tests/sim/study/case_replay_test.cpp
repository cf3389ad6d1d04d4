// A study's case saved for watching: its run written as vmt run writes one, and the saved steps
// run again (as vmt view does) to the same trace digest -- for a REPOS subroutine's cases, a
// collision among them, and the operator's manual return; the study folder finds a case by
// its id alone.
#include "sim/study/case_replay.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sim/runner/runner.hpp"
#include "sim/study/case_files.hpp"
#include "sim/study/reference_run.hpp"
#include "sim/study/study_source.hpp"

namespace vmt::sim::study {
namespace {

std::string Out(const std::string& name) {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string dir = std::string(VMT_BINARY_DIR) + "/test_output/study/" +
                          test->test_suite_name() + "." + test->name() + "/" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

struct Study {
  std::string file;
  Scene scene;
  StudyPlan plan;
  Reference ref;
  std::vector<Interruption> interruptions;
  std::vector<StudyCase> cases;  // the first interruption's
  explicit Study(const std::string& name)
      : file(std::string(VMT_SOURCE_DIR) + "/tests/sim/study/" + name),
        scene(LoadScene(file)),
        plan(LoadStudyPlan(file, scene)) {
    ref = RunReference(scene, Out("reference"));
    interruptions = Interruptions(plan, ref);
    for (const StudyCase& c : EnumerateCases(plan, interruptions))
      if (c.interruption == 0) cases.push_back(c);
  }
};

// The saved run's files, its result as the study's, and its steps again to the same digest.
void ExpectReplayable(const Study& s, const StudyCase& c) {
  const std::string dir = Out(FileNameOf(c.id));
  const SavedCase saved = SaveCaseRun(s.scene, s.plan, s.interruptions, c, dir);
  EXPECT_EQ(saved.result.dump(), RunCaseFromStart(s.scene, s.plan, s.interruptions, c).dump());
  for (const char* file : {"trace.csv", "events.jsonl", "summary.json"})
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + file)) << file;
  EXPECT_GT(saved.until_s, s.interruptions[c.interruption].t_s);
  EXPECT_FALSE(saved.timeline.empty());

  RunOptions options;
  options.backend = BackendKind::kKinematic;
  options.snapshots = false;
  options.until_s = saved.until_s;
  const Scene scene = SavedCaseScene(s.scene, saved);  // the run reads it by reference
  SceneRun again(scene, options);
  while (!again.done()) again.Step();
  EXPECT_EQ(again.Finish().trace_digest, saved.trace_digest) << c.id;
}

TEST(study_case_replay, SubroutineCasesRunAgainToTheSameDigest) {
  const Study s("tiny-study.yaml");
  ASSERT_EQ(s.cases.size(), 2u);
  for (const StudyCase& c : s.cases) ExpectReplayable(s, c);
}

TEST(study_case_replay, ManualReturnRunsAgainToTheSameDigest) {
  const Study s("tiny-manual-study.yaml");
  ASSERT_FALSE(s.cases.empty());
  for (const StudyCase& c : s.cases)
    if (s.plan.subroutines[c.subroutine].manual()) ExpectReplayable(s, c);
}

TEST(study_case_replay, StudyFolderSavesACaseByItsId) {
  const Study s("tiny-study.yaml");
  const std::string dir = Out("study");
  WriteStudySource(dir, SourceOf(s.file, s.plan));
  std::ofstream(dir + "/reference.json", std::ios::binary) << ReferenceJson(s.ref);
  const StudyCase& c = s.cases[1];
  const std::string folder = SaveCase(dir, c.id);
  EXPECT_EQ(folder, dir + "/" + CaseFolderOf(c.id));
  EXPECT_TRUE(std::filesystem::exists(folder + "/case.json"));
  EXPECT_EQ(SaveCase(dir, c.id), folder);  // saved once
  const std::optional<CaseReplay> replay = ReadCaseReplay(folder);
  ASSERT_TRUE(replay);
  EXPECT_GT(replay->until_s, 0);
  EXPECT_EQ(replay->trace_digest.size(), 16u);
  EXPECT_FALSE(ReadCaseReplay(dir));  // a study folder is not a case's run
  EXPECT_THROW(SaveCase(dir, "nc/none/t1/x/repositioning"), UnknownCase);
  EXPECT_THROW(SaveCase(Out("empty"), c.id), std::runtime_error);
}

}  // namespace
}  // namespace vmt::sim::study
