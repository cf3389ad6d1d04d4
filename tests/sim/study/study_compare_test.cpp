// Two studies case by case: cases matched by subroutine, interruption, retract and mode; class
// changes, clearance moves beyond the threshold and cases only in one study reported, in the
// text summary and the page.
#include "sim/study/study_compare.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sim/study/case_files.hpp"

namespace vmt::sim::study {
namespace {

using ::testing::HasSubstr;

CaseResult Case(const std::string& block, const std::string& verdict, double clearance = 5) {
  CaseResult r;
  r["case"] = "nc/99.mtc/" + block + "@250/X+/repositioning";
  r["subroutine"] = "nc/99.mtc";
  r["interrupt"] = block + "@250";
  r["block"] = block;
  r["retract"] = "X+";
  r["mode"] = "repositioning";
  r["verdict"] = verdict;
  r["parts"] = nullptr;
  r["min_clearance_mm"] = verdict == "clear" ? nlohmann::ordered_json(clearance) : nullptr;
  r["path"] = nlohmann::ordered_json::array();
  if (verdict == "collision") {
    r["parts"] = {"turret_disc", "spindle_jaw1"};
    r["contact_position"] = {{"X", 31.0}, {"Z", 110.0}};
    r["past_contact_mm"] = 15.0;
    r["contact_class"] = "crash";
  }
  return r;
}

TEST(study_compare, CaseByCaseWhatChanged) {
  const std::vector<CaseResult> a = {Case("N0010", "clear", 5.0), Case("N0020", "clear", 2.0),
                                     Case("N0030", "collision"), Case("N0040", "clear", 1.0),
                                     Case("N0050", "clear")};
  const std::vector<CaseResult> b = {Case("N0010", "clear", 5.05),  // within the threshold
                                     Case("N0020", "clear", 0.5),   // tighter by 1.5 mm
                                     Case("N0030", "clear", 0.8),   // the crash is gone
                                     Case("N0040", "collision"),    // a new crash
                                     Case("N0060", "clear")};
  const Comparison c = CompareCases(a, b, 0.1);
  EXPECT_EQ(c.matched, 4u);
  EXPECT_EQ(c.only_a, 1u);
  EXPECT_EQ(c.only_b, 1u);
  EXPECT_EQ(c.class_changes, 2u);
  EXPECT_EQ(c.beyond, 1u);
  ASSERT_EQ(c.changes.size(), 5u);
  // Class changes first, the one that became a crash before the one that became clear; then
  // the clearance move; then the cases only in A, only in B.
  EXPECT_EQ(c.changes[0].identity, "nc/99.mtc/N0040@250/X+/repositioning");
  EXPECT_EQ(c.changes[0].class_a, "clear");
  EXPECT_EQ(c.changes[0].class_b, "crash");
  EXPECT_EQ(c.changes[1].class_b, "clear");
  EXPECT_EQ(c.changes[2].identity, "nc/99.mtc/N0020@250/X+/repositioning");
  EXPECT_DOUBLE_EQ(c.changes[2].clearance_delta, -1.5);
  EXPECT_FALSE(c.changes[3].b);
  EXPECT_FALSE(c.changes[4].a);

  const std::string text = CompareText(c);
  EXPECT_THAT(text, HasSubstr("4 cases in both, 1 only in A, 1 only in B"));
  EXPECT_THAT(text, HasSubstr("clear -> crash: 1"));
  EXPECT_THAT(text, HasSubstr("crash -> clear: 1"));
  EXPECT_THAT(text, HasSubstr("nc/99.mtc/N0020@250/X+/repositioning: clearance 2.000 -> 0.500 mm"));
  EXPECT_THAT(text, HasSubstr("A 5 cases: 4 clear, 1 crash, 0 graze, 0 error, 0 retract refused"));
  const std::string html = CompareHtml(c);
  EXPECT_THAT(html, HasSubstr("<b>crash</b>"));
  EXPECT_THAT(html, HasSubstr("only in A"));
}

TEST(study_compare, IdenticalStudiesHaveNoChanges) {
  const std::vector<CaseResult> a = {Case("N0010", "clear"), Case("N0030", "collision")};
  const Comparison c = CompareCases(a, a, 0.1);
  EXPECT_EQ(c.matched, 2u);
  EXPECT_TRUE(c.changes.empty());
  EXPECT_THAT(CompareHtml(c), HasSubstr("None: every case has the same class"));
}

TEST(study_compare, TextsFromTheCasesAreNotReadAsHtml) {
  CaseResult a = Case("N0010", "clear");
  a["subroutine"] = "<script>alert(1)</script>";
  CaseResult b = a;
  b["verdict"] = "collision";
  b["parts"] = {"<b>tool</b>", "jaw"};
  b["point"] = {"x", 1, 2};  // a damaged line: shown, never trusted
  const std::vector<CaseResult> as = {a}, bs = {b};
  const std::string html = CompareHtml(CompareCases(as, bs, 0.1));
  EXPECT_EQ(html.find("<script>"), std::string::npos) << html;
  EXPECT_EQ(html.find("<b>tool"), std::string::npos);
}

TEST(study_compare, FoldersReadAndPageWritten) {
  const std::string root = std::string(VMT_BINARY_DIR) + "/test_output/study/compare";
  std::filesystem::remove_all(root);
  {
    CaseFiles fa(root + "/a");
    fa.Write(Case("N0010", "clear"));
    CaseFiles fb(root + "/b");
    fb.Write(Case("N0010", "collision"));
  }
  const std::string text = CompareStudies(root + "/a", root + "/b", root + "/c.html", 0.1);
  EXPECT_THAT(text, HasSubstr("clear -> crash: 1"));
  EXPECT_TRUE(std::filesystem::exists(root + "/c.html"));
  EXPECT_THROW(CompareStudies(root + "/a", root + "/none", root + "/d.html", 0.1),
               std::runtime_error);
}

// A finished study's file is in case id order and walked side by side with the other; a file
// out of order (a study still running), one with an id twice or a cut last line is read whole.
// Either way the same comparison comes out.
TEST(study_compare, FilesInOrderOrNotCompareAlike) {
  const std::string root = std::string(VMT_BINARY_DIR) + "/test_output/study/compare_order";
  std::filesystem::remove_all(root);
  const std::vector<CaseResult> a = {Case("N0010", "clear", 5.0), Case("N0020", "clear", 2.0),
                                     Case("N0030", "collision"), Case("N0040", "clear", 1.0),
                                     Case("N0050", "clear")};
  CaseResult twice = Case("N0020", "collision");  // a second line of one id: the first counts
  const std::vector<CaseResult> b = {
      Case("N0015", "clear"),      Case("N0020", "clear", 0.5), twice,
      Case("N0030", "clear", 0.8), Case("N0040", "collision"),  Case("N0060", "clear")};
  const auto write = [&](const std::string& dir, const std::vector<CaseResult>& cases,
                         const std::string& tail = "") {
    std::filesystem::create_directories(root + "/" + dir);
    std::ofstream f(root + "/" + dir + "/cases.jsonl", std::ios::binary);
    for (const CaseResult& r : cases) f << CaseJsonLine(r);
    f << tail;
  };
  write("a", a);
  write("b", b);
  std::vector<CaseResult> shuffled(a.rbegin(), a.rend());
  write("a_shuffled", shuffled);
  const std::vector<CaseResult> b_first = {b[0], b[1], b[3], b[4], b[5]};
  const std::string expected = CompareText(CompareCases(a, b_first, 0.1, root + "/a", root + "/b"));
  EXPECT_THAT(expected, HasSubstr("3 cases in both, 2 only in A, 2 only in B"));
  EXPECT_EQ(CompareStudies(root + "/a", root + "/b", root + "/1.html", 0.1), expected);
  const std::string shuffled_text =
      CompareStudies(root + "/a_shuffled", root + "/b", root + "/2.html", 0.1);
  EXPECT_EQ(shuffled_text.substr(shuffled_text.find('\n')), expected.substr(expected.find('\n')));
  // A cut last line is an error, in order or not.
  write("a_cut", a, "{\"case\":\"nc/99.mtc/N0060");
  try {
    CompareStudies(root + "/a_cut", root + "/b", root + "/3.html", 0.1);
    FAIL() << "compared";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("cases.jsonl:6: the last line is cut short"));
  }
}

}  // namespace
}  // namespace vmt::sim::study
