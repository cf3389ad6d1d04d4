// report.html of a study: the summary per subroutine and mode, the worst cases, the plane, and
// texts from cases.jsonl never read as HTML.
#include "sim/study/study_report.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "sim/study/case_files.hpp"

namespace vmt::sim::study {
namespace {

CaseResult Case(const std::string& id, const std::string& sub, const std::string& mode,
                const std::string& verdict, double clearance = 0) {
  CaseResult r;
  r["case"] = id;
  r["subroutine"] = sub;
  r["mode"] = mode;
  r["verdict"] = verdict;
  r["parts"] = verdict == "collision" ? nlohmann::ordered_json({"tool", "chuck"}) : nullptr;
  r["point"] = verdict == "collision" ? nlohmann::ordered_json({30.0, 95.0, 0.0}) : nullptr;
  r["min_clearance_mm"] = verdict == "clear" ? nlohmann::ordered_json(clearance) : nullptr;
  r["error"] = verdict == "error" ? "timeout" : "";
  r["path"] = nlohmann::ordered_json::array({{40.0, 120.0}, {30.0, 95.0}});
  return r;
}

size_t Count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The summary row of `sub` and `mode`: subroutine, mode, cases, clear, crashes (collisions
// without a class), grazes 0, errors, retract refused 0, worst clearance, deepest past contact.
std::string Row(const std::string& sub, const std::string& mode, int cases, int clear, int coll,
                int err, const std::string& worst, const std::string& deepest = "&#8211;") {
  return "<tr><td class=\"l\">" + sub + "</td><td class=\"l\">" + mode + "</td><td>" +
         std::to_string(cases) + "</td><td class=\"clear\">" + std::to_string(clear) +
         "</td><td class=\"crash\">" + std::to_string(coll) +
         "</td><td class=\"graze\">0</td><td class=\"error\">" + std::to_string(err) +
         "</td><td class=\"retract_refused\">0</td><td>" + worst + "</td><td>" + deepest +
         "</td></tr>";
}

TEST(study_report, SummaryPerSubroutineAndMode) {
  const std::vector<CaseResult> cases = {
      Case("a1", "nc/99.mtc", "automatic", "clear", 2.5),
      Case("a2", "nc/99.mtc", "automatic", "collision"),
      Case("a3", "nc/99.mtc", "manual", "clear", 0.75),
      Case("a4", "nc/99.mtc", "manual", "error"),
      Case("b1", "nc/98.mtc", "automatic", "collision"),
  };
  const std::string html = ReportHtml("study", cases, nullptr);
  EXPECT_NE(html.find("<p>5 cases."), std::string::npos);
  EXPECT_NE(html.find(Row("nc/99.mtc", "all", 4, 2, 1, 1, "0.750")), std::string::npos) << html;
  EXPECT_NE(html.find(Row("nc/99.mtc", "automatic", 2, 1, 1, 0, "2.500")), std::string::npos);
  EXPECT_NE(html.find(Row("nc/99.mtc", "manual", 2, 1, 0, 1, "0.750")), std::string::npos);
  // No clear case: no worst clearance.
  EXPECT_NE(html.find(Row("nc/98.mtc", "all", 1, 0, 1, 0, "&#8211;")), std::string::npos);
  // One plane per subroutine, a contact dot per collision.
  EXPECT_EQ(Count(html, "<svg xmlns"), 2u);
  EXPECT_EQ(Count(html, "<circle"), 2u);
}

TEST(study_report, WorstCasesAreTheFailuresThenTheTightestClearOnes) {
  std::vector<CaseResult> cases;
  for (int i = 0; i < 25; ++i)
    cases.push_back(Case("c" + std::to_string(100 + i), "s", "m", "collision"));
  for (int i = 0; i < 8; ++i)
    cases.push_back(Case("k" + std::to_string(i), "s", "m", "clear", 10.0 - i));  // k7 tightest
  const std::string html = ReportHtml("t", cases, nullptr);
  const std::string worst = html.substr(html.find("<h3>Worst cases"));
  // At most 20 failures, then the 5 tightest clear cases, tightest first.
  EXPECT_EQ(Count(worst, "<td class=\"l crash\">"), 20u);
  EXPECT_EQ(Count(worst, "<td class=\"l clear\">"), 5u);
  EXPECT_NE(worst.find("c119"), std::string::npos);  // equally severe: by case id
  EXPECT_EQ(worst.find("c120"), std::string::npos);
  EXPECT_LT(worst.find(">k7<"), worst.find(">k6<"));
  EXPECT_NE(worst.find(">k3<"), std::string::npos);
  EXPECT_EQ(worst.find(">k2<"), std::string::npos);
}

TEST(study_report, WorstCasesMostSevereFirstRefusedRetractsApart) {
  std::vector<CaseResult> cases;
  const auto contact = [](const std::string& id, double past, const char* cls) {
    CaseResult r = Case(id, "s", "m", "collision");
    r["past_contact_mm"] = past;
    r["contact_class"] = cls;
    r["contact_position"] = {{"X", 30.0}, {"Z", 95.0}};
    return r;
  };
  cases.push_back(contact("a-graze", 0.05, "graze"));
  cases.push_back(contact("b-shallow", 0.4, "crash"));
  cases.push_back(Case("c-error", "s", "m", "error"));
  cases.push_back(contact("d-deep", 25.0, "crash"));
  cases.push_back(Case("e-refused", "s", "m", "retract_refused"));
  const std::string html = ReportHtml("t", cases, nullptr);
  const std::string worst = html.substr(html.find("<h3>Worst cases"));
  EXPECT_LT(worst.find(">d-deep<"), worst.find(">b-shallow<"));
  EXPECT_LT(worst.find(">b-shallow<"), worst.find(">a-graze<"));
  EXPECT_LT(worst.find(">a-graze<"), worst.find(">c-error<"));
  EXPECT_EQ(worst.find(">e-refused<"), std::string::npos);  // not the subroutine's
  EXPECT_NE(worst.find("<td>25.000</td>"), std::string::npos);
  // The summary counts them apart: 2 crashes, 1 graze, 1 error, 1 retract refused.
  EXPECT_NE(html.find("<td class=\"crash\">2</td><td class=\"graze\">1</td><td class=\"error\">"
                      "1</td><td class=\"retract_refused\">1</td>"),
            std::string::npos);
}

TEST(study_report, TextsFromTheCasesAreNotReadAsHtml) {
  // cases.jsonl is a file anyone can edit or tear: what it says is shown, never interpreted.
  CaseResult hostile =
      Case("<b>x</b>", "<script>alert(1)</script>", "\"mode\"", "bad\"><script>alert(2)</script>");
  hostile["error"] = "<img src=x onerror=alert(3)>";
  const std::string html =
      ReportHtml("<title>&", {hostile}, nullptr, {{"<b>x</b>", "shots/\"a\".png"}});
  EXPECT_EQ(html.find("<script>"), std::string::npos) << html;
  EXPECT_EQ(html.find("<img src=x"), std::string::npos);
  EXPECT_EQ(html.find("<b>x"), std::string::npos);
  EXPECT_NE(html.find("&lt;title&gt;&amp;"), std::string::npos);
  EXPECT_NE(html.find("shots/&quot;a&quot;.png"), std::string::npos);
}

TEST(study_report, NoPathsNoPlane) {
  CaseResult r = Case("a", "s", "m", "error");
  r["path"] = nlohmann::ordered_json::array();
  EXPECT_NE(ReportHtml("t", {r}, nullptr).find("(no paths)"), std::string::npos);
  // The reference's path alone draws the plane: the contour as turned.
  Reference ref;
  ref.path = {{50, 150}, {50, 100}, {30, 100}};
  const std::string html = ReportHtml("t", {r}, &ref);
  EXPECT_NE(html.find("the program's tool path (reference run)"), std::string::npos);
}

TEST(study_report, ATornReferenceOnlyLosesTheContour) {
  const std::string dir = std::string(VMT_BINARY_DIR) + "/test_output/study/report_torn";
  std::filesystem::remove_all(dir);
  {
    CaseFiles files(dir);
    files.Write(Case("a", "s", "m", "clear", 1));
  }
  std::ofstream(dir + "/reference.json") << "{\"start_s\": 0.1, \"blo";
  WriteReport(dir, "torn");
  std::ifstream in(dir + "/report.html");
  const std::string html((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(html.find("<h1>torn</h1>"), std::string::npos);
  EXPECT_NE(html.find(Row("s", "all", 1, 1, 0, 0, "1.000")), std::string::npos);
  EXPECT_EQ(html.find("reference run"), std::string::npos);
}

// A study of any size gives a report of bounded size: the plane draws a subroutine's most
// severe kPlaneCases, and every case is in the paged table's files (cases-pages/N.js), a page
// left from a larger study removed.
TEST(study_report, LargeStudyPagesItsCasesAndBoundsThePage) {
  const std::string dir = std::string(VMT_BINARY_DIR) + "/test_output/study/report_pages";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir + "/cases-pages");
  std::ofstream(dir + "/cases-pages/9.js") << "vmtCasesPage(9, []);\n";
  const size_t n = 2 * kCasesPerPage + 200;
  {
    CaseFiles files(dir);
    char id[16];
    for (size_t i = 0; i < n; ++i) {
      std::snprintf(id, sizeof id, "c%05zu", i);
      files.Write(Case(id, "s", "m", i % 7 == 0 ? "collision" : "clear", 1.0 + i));
    }
  }
  WriteReport(dir, "big");
  std::ifstream in(dir + "/report.html");
  const std::string html((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(html.find(Row("s", "all", static_cast<int>(n), static_cast<int>(n - n / 7 - 1),
                          static_cast<int>(n / 7 + 1), 0, "2.000")),
            std::string::npos);
  EXPECT_NE(html.find("Drawn: the " + std::to_string(kPlaneCases) + " most severe of its " +
                      std::to_string(n) + " cases."),
            std::string::npos);
  EXPECT_EQ(Count(html, "</polyline></a>"), kPlaneCases);  // a case's path
  EXPECT_NE(html.find("<h2>All cases</h2>"), std::string::npos);
  EXPECT_NE(html.find("of 3 <button"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir + "/cases-pages/3.js"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/cases-pages/4.js"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/cases-pages/9.js"));
  std::ifstream last(dir + "/cases-pages/3.js");
  const std::string page((std::istreambuf_iterator<char>(last)), {});
  EXPECT_EQ(page.rfind("vmtCasesPage(3, [\n[\"c01000\",\"s\",\"m\"", 0), 0u) << page.substr(0, 80);
  EXPECT_EQ(Count(page, "\n["), 200u);
  EXPECT_NE(page.find("[\"c01199\""), std::string::npos);
  // The page built in memory (no files) has no table of all cases.
  EXPECT_EQ(ReportHtml("t", {Case("a", "s", "m", "clear", 1)}, nullptr).find("All cases"),
            std::string::npos);
}

}  // namespace
}  // namespace vmt::sim::study
