// cases.jsonl / cases.csv: appended whole lines, a torn last line dropped on reading, one
// result per case id, CSV quoting.
#include "sim/study/case_files.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "sim/study/case_merge.hpp"
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

std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The streaming merge writes the bytes of reading everything, deduplicating and rewriting:
// sorted and unsorted inputs (one longer than a run), ids repeated within and across inputs
// (the first input's, its first line's, wins), a torn last line left out.
TEST(study_files, MergeStreamsTheBytesOfReadingEverything) {
  const std::string dir = std::string(VMT_BINARY_DIR) + "/test_output/study/merge";
  std::filesystem::remove_all(dir);
  std::mt19937 rng(7);
  const char* verdicts[] = {"clear", "collision", "error"};
  std::vector<std::string> inputs;
  std::vector<CaseResult> all;
  const size_t sizes[] = {300, kMergeRunCases + 1500, 40};
  for (size_t k = 0; k < 3; ++k) {
    std::vector<CaseResult> some;
    for (size_t i = 0; i < sizes[k]; ++i) {
      CaseResult r = Case("c" + std::to_string(rng() % 30000), verdicts[rng() % 3]);
      r["shard"] = k, r["line"] = i;
      some.push_back(r);
    }
    if (k != 1) some = Deduplicated(some);  // a shard's file is in id order; 1 is not
    const std::string in = dir + "/in" + std::to_string(k);
    std::filesystem::create_directories(in);
    std::ofstream out(in + "/cases.jsonl", std::ios::binary);
    for (const CaseResult& r : some) out << CaseJsonLine(r);
    if (k == 2) out << "{\"case\":\"c1\",\"verd";
    inputs.push_back(in + "/cases.jsonl");
    all.insert(all.end(), some.begin(), some.end());
  }
  RewriteCaseFiles(dir + "/whole", Deduplicated(all));
  std::vector<std::string> order;
  const size_t n = MergeCaseFiles(inputs, dir + "/merged", TornLine::kLeftOut,
                                  [&](const CaseResult& r) { order.push_back(r["case"]); });
  EXPECT_EQ(n, Deduplicated(all).size());
  EXPECT_TRUE(std::is_sorted(order.begin(), order.end()));
  EXPECT_EQ(Slurp(dir + "/merged/cases.jsonl"), Slurp(dir + "/whole/cases.jsonl"));
  EXPECT_EQ(Slurp(dir + "/merged/cases.csv"), Slurp(dir + "/whole/cases.csv"));
  // In place: a study's own file, merged into itself.
  MergeCaseFiles({inputs[1]}, dir + "/in1", TornLine::kLeftOut);
  RewriteCaseFiles(dir + "/whole1", Deduplicated(ReadCases(inputs[1])));
  EXPECT_EQ(Slurp(inputs[1]), Slurp(dir + "/whole1/cases.jsonl"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/in1/.merge.tmp-" + std::to_string(::getpid())));
  // A torn or corrupt shard refuses the merge and leaves the output as it was.
  const std::string before = Slurp(dir + "/merged/cases.jsonl");
  EXPECT_THROW(MergeCaseFiles(inputs, dir + "/merged", TornLine::kError), std::runtime_error);
  std::ofstream(inputs[0], std::ios::app) << "not json\n";
  EXPECT_THROW(MergeCaseFiles(inputs, dir + "/merged", TornLine::kLeftOut), std::runtime_error);
  EXPECT_EQ(Slurp(dir + "/merged/cases.jsonl"), before);
}

}  // namespace
}  // namespace vmt::sim::study
