// What a study concludes, from synthetic results: the classes (a graze within 0.1 mm of the
// move's end, a crash beyond), the severity order, retracts PathGuard refused counted apart,
// and the sentences per mode that name the parts, the count and the program region.
#include "sim/study/study_conclusions.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "sim/study/study_report.hpp"

namespace vmt::sim::study {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

CaseResult Case(const std::string& sub, const std::string& block, const std::string& retract,
                const std::string& mode, const std::string& verdict) {
  CaseResult r;
  r["case"] = sub + "/" + block + "@250/" + retract + "/" + mode;
  r["subroutine"] = sub;
  r["interrupt"] = block + "@250";
  r["block"] = block;
  r["retract"] = retract;
  r["mode"] = mode;
  r["verdict"] = verdict;
  r["parts"] = nullptr;
  r["min_clearance_mm"] = verdict == "clear" ? nlohmann::ordered_json(5.0) : nullptr;
  r["error"] = nullptr;
  r["path"] = nlohmann::ordered_json::array({{40.0, 120.0}, {30.0, 95.0}});
  return r;
}

CaseResult Contact(CaseResult r, const std::string& a, const std::string& b, double past) {
  r["verdict"] = "collision";
  r["parts"] = {a, b};
  r["point"] = {30.0, 0.0, 155.0};
  r["contact_position"] = {{"X", 30.0}};
  r["past_contact_mm"] = past;
  r["contact_class"] = past <= kGrazeMm ? "graze" : "crash";
  return r;
}

// The program's blocks in the order they ran, with their lines.
Reference Program() {
  Reference ref;
  int line = 4;
  for (const char* b : {"N0010", "N0020", "N0030", "N0040", "N0050", "N0060"})
    ref.blocks.push_back({line++, b, 0, 1, true});
  return ref;
}

TEST(study_conclusions, ClassesFromVerdictAndDepth) {
  EXPECT_EQ(ClassOf(Case("s", "N0010", "r", "m", "clear")), "clear");
  EXPECT_EQ(ClassOf(Case("s", "N0010", "r", "m", "error")), "error");
  EXPECT_EQ(ClassOf(Case("s", "N0010", "r", "m", "retract_refused")), "retract_refused");
  const CaseResult base = Case("s", "N0010", "r", "m", "clear");
  EXPECT_EQ(ClassOf(Contact(base, "tool", "jaw1", 12.5)), "crash");
  EXPECT_EQ(ClassOf(Contact(base, "tool", "workpiece", 0.1)), "graze");
  EXPECT_EQ(ClassOf(Contact(base, "tool", "workpiece", 0.0)), "graze");
  // A collision of a study made before the classes: a crash, never hidden as a graze.
  CaseResult old = Contact(base, "tool", "jaw1", 0.05);
  old.erase("contact_class");
  EXPECT_EQ(ClassOf(old), "crash");
  // ... and an error after a retract PathGuard refused: the operator's, as now.
  CaseResult refused = Case("s", "N0010", "r", "m", "error");
  refused["retract_contact"] = {"turret_st01_holder", "spindle_jaw3"};
  EXPECT_EQ(ClassOf(refused), "retract_refused");
}

TEST(study_conclusions, SeverityOrdersCrashesByDepthThenGrazesErrorsClear) {
  const CaseResult c = Case("s", "N0010", "r", "m", "clear");
  std::vector<CaseResult> cases = {
      Case("s", "N0010", "a", "m", "clear"),
      Contact(Case("s", "N0020", "b", "m", "clear"), "t", "w", 0.05),
      Contact(Case("s", "N0030", "c", "m", "clear"), "t", "j", 3.0),
      Case("s", "N0040", "d", "m", "retract_refused"),
      Case("s", "N0050", "e", "m", "error"),
      Contact(Case("s", "N0060", "f", "m", "clear"), "t", "j", 40.0),
  };
  cases[0]["min_clearance_mm"] = 0.4;
  std::sort(cases.begin(), cases.end(), MoreSevere);
  std::vector<std::string> order;
  for (const CaseResult& r : cases) order.push_back(r["retract"].get<std::string>());
  // The 40 mm crash, the 3 mm crash, the graze, the error, the clear case, the refused retract.
  EXPECT_EQ(order, (std::vector<std::string>{"f", "c", "b", "e", "a", "d"}));
}

TEST(study_conclusions, RetractsRefusedAreCountedApart) {
  ClassCount n;
  n.Add(Case("s", "N0010", "r", "m", "retract_refused"));
  n.Add(Case("s", "N0010", "r", "m", "clear"));
  n.Add(Case("s", "N0020", "r", "m", "clear"));
  EXPECT_EQ(n.cases, 3u);
  EXPECT_EQ(n.retract_refused, 1u);
  EXPECT_EQ(n.error, 0u);
  EXPECT_EQ(n.judged(), 2u);
  // A subroutine whose only failures are refused retracts is clear in all its cases.
  const std::vector<ModeConclusion> m =
      Conclusions({Case("s", "N0010", "X- toward the chuck", "repositioning", "retract_refused"),
                   Case("s", "N0010", "X+", "repositioning", "clear")},
                  nullptr);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].headline, "repositioning: clear in all cases: s.");
  EXPECT_THAT(m[0].sentences[0], HasSubstr("s is clear in its one case."));
  EXPECT_THAT(m[0].sentences.back(),
              HasSubstr("in 1 case PathGuard refused the operator's retract (\u201cX- toward "
                        "the chuck\u201d)"));
}

TEST(study_conclusions, SentencesNamePartsCountsAndProgramRegion) {
  const Reference ref = Program();
  std::vector<CaseResult> cases;
  // REPOS_A: the turret's holder hits chuck jaws 1 and 2 when interrupted in N0030..N0050,
  // always after the retract "X+ then Z-"; elsewhere clear. REPOS_B: clear everywhere.
  for (const char* b : {"N0010", "N0020", "N0030", "N0040", "N0050", "N0060"})
    for (const char* retract : {"X+ then Z+", "X+ then Z-"}) {
      const std::string block = b;
      const bool bad = std::string(retract) == "X+ then Z-" && block >= "N0030" && block <= "N0050";
      CaseResult a = Case("REPOS_A", block, retract, "repositioning", "clear");
      // The record may name the parts either way round: what stands is hit by what moves.
      if (bad)
        a = block == "N0040" ? Contact(a, "spindle_jaw2", "turret_holder", 8.0)
                             : Contact(a, "turret_holder", "spindle_jaw1", 12.0);
      cases.push_back(a);
      cases.push_back(Case("REPOS_B", block, retract, "repositioning", "clear"));
    }
  // NC-block restart: REPOS_B grazes the workpiece once, in N0060.
  cases.push_back(Contact(Case("REPOS_B", "N0060", "X+ then Z+", "restart", "clear"),
                          "turret_insert", "workpiece", 0.02));
  cases.push_back(Case("REPOS_B", "N0010", "X+ then Z+", "restart", "clear"));
  cases.push_back(Case("REPOS_B", "N0020", "X+ then Z+", "restart", "error"));
  cases.back()["error"] = "timeout: no RTS of the REPOS subroutine within 30.000000 s";

  const std::vector<ModeConclusion> m = Conclusions(cases, &ref);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].mode, "repositioning");
  EXPECT_EQ(m[0].headline, "repositioning: clear in all cases: REPOS_B.");
  ASSERT_EQ(m[0].sentences.size(), 2u);
  EXPECT_EQ(m[0].sentences[0],
            "REPOS_A fails in 3 of 12 cases: turret_holder hits spindle_jaw 1 or 2 in 3 cases "
            "(crashes, up to 12.000 mm past the first contact), all interrupted in "
            "N0030\u2013N0050 (lines 6\u20138), after the retract \u201cX+ then Z-\u201d. "
            "Clear in 9.");
  EXPECT_EQ(m[0].sentences[1], "REPOS_B is clear in all 12 cases.");
  EXPECT_EQ(m[1].headline, "restart: no subroutine or manual order is clear in all cases.");
  ASSERT_EQ(m[1].sentences.size(), 1u);
  EXPECT_THAT(m[1].sentences[0], HasSubstr("REPOS_B fails in 2 of 3 cases: "));
  EXPECT_THAT(m[1].sentences[0],
              HasSubstr("turret_insert hits workpiece in 1 case (a graze, within 0.100 mm of "
                        "the move's end), interrupted in N0060 (line 9)"));
  EXPECT_THAT(m[1].sentences[0], HasSubstr("an NC error or timeout in 1 case (timeout: no RTS"));

  // The report opens with them, escaped, before the summary table.
  const std::string html = ReportHtml("t", cases, &ref);
  const size_t conclusions = html.find("<h2>Conclusions</h2>");
  ASSERT_NE(conclusions, std::string::npos);
  EXPECT_LT(conclusions, html.find("<h2>Summary"));
  EXPECT_THAT(html, HasSubstr("<b>repositioning: clear in all cases: REPOS_B.</b>"));
  EXPECT_THAT(html, HasSubstr("Machine coordinates throughout"));
}

TEST(study_conclusions, RegionsSplitWhereAnInterruptionWasClear) {
  const Reference ref = Program();
  std::vector<CaseResult> cases;
  for (const char* b : {"N0010", "N0020", "N0030", "N0040", "N0050"}) {
    CaseResult r = Case("S", b, "r", "m", "clear");
    if (std::string(b) != "N0030") r = Contact(r, "tool", "jaw1", 2);
    cases.push_back(r);
  }
  const std::vector<ModeConclusion> m = Conclusions(cases, &ref);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0].sentences[0], HasSubstr("all interrupted in N0010\u2013N0020 (lines 4\u20135) "
                                           "and N0040\u2013N0050 (lines 7\u20138)"));
  // Without the reference run: the blocks by name, no lines.
  EXPECT_THAT(Conclusions(cases, nullptr)[0].sentences[0],
              HasSubstr("all interrupted in N0010\u2013N0020 and N0040\u2013N0050"));
  EXPECT_THAT(Conclusions(cases, nullptr)[0].sentences[0], Not(HasSubstr("line")));
}

TEST(study_conclusions, ContactAxesFromThePathAndTheRecord) {
  CaseResult r = Contact(Case("s", "N0010", "r", "m", "clear"), "t", "w", 1);
  r["path"] = nlohmann::ordered_json::array({{40.0, 120.0}, {28.0, 159.999}});
  r["contact_position"] = {{"Z", 159.999}};
  EXPECT_EQ(ContactAxes(r), "X28.000 Z159.999");
  EXPECT_EQ(ContactAxes(Case("s", "N0010", "r", "m", "clear")), "");
}

}  // namespace
}  // namespace vmt::sim::study
