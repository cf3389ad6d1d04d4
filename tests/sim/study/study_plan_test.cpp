// The `study:` plan: read from the showcase scene, ignored by a run, bad input named with
// file:line:col and the YAML path.
#include "sim/study/study_plan.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sim/model/model_error.hpp"

namespace vmt::sim::study {
namespace {

const std::string kShowcase = std::string(VMT_SOURCE_DIR) + "/scenes/study-repos-turning.yaml";

TEST(study_plan, ReadsTheShowcase) {
  const Scene scene = LoadScene(kShowcase);  // the scene loader accepts `study:` and skips it
  const StudyPlan plan = LoadStudyPlan(kShowcase, scene);
  EXPECT_EQ(plan.every_ms, 0);
  EXPECT_EQ(plan.per_mille, (std::vector<int>{250, 750}));
  ASSERT_EQ(plan.retracts.size(), 4u);
  EXPECT_EQ(plan.retracts[1].name, "X+ then Z-");
  ASSERT_EQ(plan.retracts[1].jogs.size(), 2u);
  EXPECT_EQ(plan.retracts[1].jogs[1].axis, "Z");
  EXPECT_EQ(plan.retracts[1].jogs[1].mm, -20);
  // The tool change point is a position of each axis, X first.
  ASSERT_EQ(plan.retracts[3].jogs.size(), 2u);
  EXPECT_EQ(plan.retracts[3].jogs[0].axis, "X");
  EXPECT_EQ(plan.retracts[3].jogs[0].to, 150);
  EXPECT_EQ(plan.retracts[3].jogs[1].to, 300);
  EXPECT_EQ(plan.modes, (std::vector<ReposMode>{ReposMode::kRepositioning, ReposMode::kRestart}));
  ASSERT_EQ(plan.subroutines.size(), 4u);  // two REPOS subroutines, two manual orders
  EXPECT_EQ(plan.subroutines[1].name, "nc/99_safe.mtc");
  EXPECT_TRUE(std::filesystem::exists(plan.subroutines[1].file));
  EXPECT_FALSE(plan.subroutines[1].manual());
  EXPECT_EQ(plan.subroutines[2].name, "manual X,Z");
  EXPECT_EQ(plan.subroutines[2].manual_order, (std::vector<std::string>{"X", "Z"}));
  EXPECT_TRUE(plan.subroutines[2].file.empty());
  EXPECT_EQ(plan.subroutines[3].name, "manual Z,X");
}

TEST(study_plan, ManualOrdersAloneOrBesideSubroutines) {
  const std::string file = std::string(VMT_SOURCE_DIR) + "/tests/sim/study/tiny-manual-study.yaml";
  const Scene scene = LoadScene(file);
  const StudyPlan plan = LoadStudyPlan(file, scene);
  ASSERT_EQ(plan.subroutines.size(), 2u);  // no `subroutines:`: the manual orders only
  EXPECT_EQ(plan.subroutines[0].manual_order, (std::vector<std::string>{"X", "Z"}));
  EXPECT_EQ(plan.subroutines[1].manual_order, (std::vector<std::string>{"Z", "X"}));
}

// A copy of the tiny study with its `study:` section replaced.
std::string Error(const std::string& study) {
  const std::string dir = std::string(VMT_SOURCE_DIR) + "/tests/sim/study";
  const std::string file = dir + "/bad-study.tmp.yaml";
  {
    std::ifstream in(dir + "/tiny-study.yaml");
    std::string text((std::istreambuf_iterator<char>(in)), {});
    text = text.substr(0, text.find("study:"));
    std::ofstream(file) << text << study;
  }
  std::string message = "no error";
  try {
    const Scene scene = LoadScene(file);
    LoadStudyPlan(file, scene);
  } catch (const ModelError& e) {
    message = e.what();
  }
  std::filesystem::remove(file);
  return message;
}

TEST(study_plan, BadInputNamesFileLineAndPath) {
  using ::testing::HasSubstr;
  using ::testing::MatchesRegex;
  const std::string retract = "  retracts: [{name: up, jogs: [{axis: X, mm: 20}]}]\n";
  const std::string subs = "  subroutines: [../../../scenes/nc/99.mtc]\n";
  std::string e = Error("study:\n  interrupt: {per_mille: [250, 2000]}\n" + retract + subs);
  EXPECT_THAT(e, MatchesRegex(".*bad-study.tmp.yaml:[0-9]+:[0-9]+: study.interrupt.per_mille.1.*"));
  EXPECT_THAT(e, HasSubstr("0..1000"));
  e = Error("study:\n  interrupt: {every_ms: 500, per_mille: [1]}\n" + retract + subs);
  EXPECT_THAT(e, HasSubstr("expected one of every_ms, per_mille"));
  e = Error(
      "study:\n  interrupt: {every_ms: 500}\n  retracts: [{name: up, jogs: [{axis: Q, "
      "mm: 20}]}]\n" +
      subs);
  EXPECT_THAT(e, HasSubstr("no NC axis Q"));
  EXPECT_THAT(e, MatchesRegex(".*:[0-9]+:[0-9]+: study.retracts.0..jogs.0..axis.*"));
  e = Error(
      "study:\n  interrupt: {every_ms: 500}\n  retracts: [{name: up, jogs: [{axis: X, "
      "mm: 20, to: 150}]}]\n" +
      subs);
  EXPECT_THAT(e, MatchesRegex(".*:[0-9]+:[0-9]+: study.retracts.0..jogs.0..mm: give mm .a "
                              "distance. or to .a position., not both.*"));
  e = Error("study:\n  interrupt: {every_ms: 500}\n" + retract + "  subroutines: [nope.mtc]\n");
  EXPECT_THAT(e, HasSubstr("cannot open NC program"));
  EXPECT_THAT(e, HasSubstr("nope.mtc: No such file or directory"));
  // An empty entry names the scene's folder: refused when the plan loads, not after the
  // reference run.
  e = Error("study:\n  interrupt: {every_ms: 500}\n" + retract + "  subroutines: [\"\"]\n");
  EXPECT_THAT(e, MatchesRegex(".*:[0-9]+:[0-9]+: study.subroutines.0.: cannot open NC program "
                              ".*: Is a directory.*"));
  e = Error("study:\n  interrupt: {every_ms: 500}\n" + retract + subs + "  modes: [manual]\n");
  EXPECT_THAT(e, HasSubstr("expected repositioning or restart"));
  e = Error("study:\n  interrupt: {every_ms: 500}\n" + retract + subs + "  speed: 3\n");
  EXPECT_THAT(e, HasSubstr("speed"));
  e = Error("study:\n  interrupt: {every_ms: 500}\n  retracts: []\n" + subs);
  EXPECT_THAT(e, HasSubstr("expected a list of retract patterns"));
  e = Error("study:\n  interrupt: {every_ms: 500}\n" + retract + "  manual: [[X, Q]]\n");
  EXPECT_THAT(e, HasSubstr("no NC axis Q"));
  EXPECT_THAT(e, MatchesRegex(".*:[0-9]+:[0-9]+: study.manual.0..1.*"));
  e = Error("study:\n  interrupt: {every_ms: 500}\n" + retract + "  manual: [[X, X]]\n");
  EXPECT_THAT(e, HasSubstr("axis X twice in one order"));
  e = Error("study:\n  interrupt: {every_ms: 500}\n" + retract + "  manual: [X, Z]\n");
  EXPECT_THAT(e, HasSubstr("expected a list of NC axes"));
  e = Error("study:\n  interrupt: {every_ms: 500}\n" + retract + "  manual: [[X], [X]]\n");
  EXPECT_THAT(e, HasSubstr("listed twice"));
  e = Error("study:\n  interrupt: {every_ms: 500}\n" + retract);
  EXPECT_THAT(e, HasSubstr("and/or `manual:`"));
  e = Error("study: [1, 2]\n");
  EXPECT_THAT(e, HasSubstr("expected a map"));
  e = Error("stud:\n  interrupt: {every_ms: 500}\n");
  EXPECT_THAT(e, HasSubstr("stud"));  // the scene loader refuses the typo
}

}  // namespace
}  // namespace vmt::sim::study
