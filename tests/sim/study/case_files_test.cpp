// cases.jsonl / cases.csv: appended whole lines, a torn last line dropped on reading, one
// result per case id, CSV quoting.
#include "sim/study/case_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sim/study/study_report.hpp"

namespace vmt::sim::study {
namespace {

CaseResult Case(const std::string& id, const std::string& verdict) {
  CaseResult r;
  r["case"] = id;
  r["subroutine"] = "nc/99.mtc";
  r["retract"] = "X+, then \"Z+\"";
  r["verdict"] = verdict;
  r["parts"] = verdict == "collision" ? nlohmann::ordered_json({"tool", "chuck"}) : nullptr;
  r["point"] = nullptr;
  r["min_clearance_mm"] = verdict == "clear" ? nlohmann::ordered_json(1.5) : nullptr;
  r["path"] = nlohmann::ordered_json::array({{40.0, 120.0}, {28.0, 100.0}});
  return r;
}

TEST(study_files, AppendReadDeduplicate) {
  const std::string dir = std::string(VMT_BINARY_DIR) + "/test_output/study/files";
  std::filesystem::remove_all(dir);
  {
    CaseFiles files(dir);
    files.Write(Case("b", "clear"));
    files.Write(Case("a", "collision"));
    files.Write(Case("b", "error"));  // a second result of b: the first stays
  }
  std::ofstream(dir + "/cases.jsonl", std::ios::app) << "{\"case\":\"c\",\"verd";  // torn
  const std::vector<CaseResult> read = ReadCases(dir + "/cases.jsonl");
  ASSERT_EQ(read.size(), 3u);
  const std::vector<CaseResult> d = Deduplicated(read);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0]["case"], "a");
  EXPECT_EQ(d[1]["verdict"], "clear");
  std::ifstream csv(dir + "/cases.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(header.rfind("case,subroutine,interrupt,", 0), 0u);
  EXPECT_NE(row.find("\"X+, then \"\"Z+\"\"\""), std::string::npos) << row;
  RewriteCaseFiles(dir, d);
  EXPECT_EQ(ReadCases(dir + "/cases.jsonl").size(), 2u);
  const std::string html = ReportHtml("t", d, nullptr);
  EXPECT_NE(html.find("<svg"), std::string::npos);
  EXPECT_NE(html.find("[&quot;tool&quot;,&quot;chuck&quot;]"), std::string::npos);
}

TEST(study_files, ACorruptFileIsRefusedNamingEachBadLine) {
  const std::string dir = std::string(VMT_BINARY_DIR) + "/test_output/study/corrupt";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/cases.jsonl";
  std::ofstream(path) << "{\"case\":\"a\"}\nnot json\n[1]\n{\"verdict\":\"clear\"}\n";
  try {
    ReadCases(path);
    FAIL() << "a corrupt cases.jsonl was read";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path + ": 3 of 4 lines are no case"), std::string::npos) << what;
    EXPECT_NE(what.find(path + ":2: not JSON"), std::string::npos) << what;
    EXPECT_NE(what.find(path + ":3: not a JSON object"), std::string::npos) << what;
    EXPECT_NE(what.find(path + ":4: no \"case\" id"), std::string::npos) << what;
  }
  // A last line cut short: a study resuming runs that case again; merge and compare refuse it.
  std::ofstream(path) << "{\"case\":\"a\"}\n{\"case\":\"b\",\"verd";
  EXPECT_EQ(ReadCases(path).size(), 1u);
  EXPECT_THROW(ReadCases(path, TornLine::kError), std::runtime_error);
}

}  // namespace
}  // namespace vmt::sim::study
