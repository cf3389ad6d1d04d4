#include "sim/study/case_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>

namespace vmt::sim::study {
namespace {

// RFC 4180: a field with a comma, quote or line break is quoted, quotes doubled.
std::string Csv(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string Cell(const nlohmann::ordered_json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return Csv(v.get<std::string>());
  if (v.is_array()) {  // parts "a|b", point "x y z"
    std::string s;
    const bool text = !v.empty() && v[0].is_string();
    for (const auto& e : v) {
      if (!s.empty()) s += text ? "|" : " ";
      s += e.is_string() ? e.get<std::string>() : e.dump();
    }
    return Csv(s);
  }
  return Csv(v.dump());
}

const char* const kColumns[] = {
    "case",           "subroutine",   "interrupt",    "block", "per_mille",     "t_interrupt_s",
    "retract",        "mode",         "verdict",      "parts", "point",         "min_clearance_mm",
    "path_length_mm", "repos_time_s", "error_number", "error", "contact_class", "past_contact_mm"};

void WriteAll(int fd, const std::string& s) {
  size_t done = 0;
  while (done < s.size()) {
    const ssize_t n = ::write(fd, s.data() + done, s.size() - done);
    if (n <= 0) throw std::runtime_error("cannot write a study's case files");
    done += static_cast<size_t>(n);
  }
}

}  // namespace

std::string FileNameOf(const std::string& case_id) {
  std::string name;
  for (const char c : case_id)
    name += (std::isalnum(static_cast<unsigned char>(c)) || c == '-') ? c : '_';
  return name;
}

std::string CsvHeader() {
  std::string h;
  for (const char* c : kColumns) {
    if (!h.empty()) h += ',';
    h += c;
  }
  return h + "\n";
}

std::string CsvRow(const CaseResult& r) {
  std::string row;
  bool first = true;
  for (const char* c : kColumns) {
    if (!first) row += ",";
    first = false;
    if (r.contains(c)) row += Cell(r[c]);
  }
  return row + "\n";
}

std::vector<CaseResult> ReadCases(const std::string& jsonl_path) {
  std::vector<CaseResult> out;
  std::ifstream in(jsonl_path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  size_t begin = 0;
  for (size_t end; (end = text.find('\n', begin)) != std::string::npos; begin = end + 1) {
    CaseResult r = nlohmann::ordered_json::parse(text.substr(begin, end - begin), nullptr, false);
    if (!r.is_discarded() && r.is_object() && r.contains("case") && r["case"].is_string())
      out.push_back(std::move(r));
  }
  return out;
}

std::vector<CaseResult> Deduplicated(std::vector<CaseResult> cases) {
  std::stable_sort(cases.begin(), cases.end(), [](const CaseResult& a, const CaseResult& b) {
    return a["case"].get<std::string>() < b["case"].get<std::string>();
  });
  std::vector<CaseResult> out;
  for (CaseResult& r : cases)
    if (out.empty() || out.back()["case"] != r["case"]) out.push_back(std::move(r));
  return out;
}

void RewriteCaseFiles(const std::string& dir, const std::vector<CaseResult>& cases) {
  std::filesystem::create_directories(dir);
  // Written beside and renamed: a study killed now still has its old files whole.
  std::ofstream jsonl(dir + "/cases.jsonl.tmp", std::ios::binary);
  std::ofstream csv(dir + "/cases.csv.tmp", std::ios::binary);
  csv << CsvHeader();
  for (const CaseResult& r : cases) {
    jsonl << r.dump() << '\n';
    csv << CsvRow(r);
  }
  jsonl.close();
  csv.close();
  if (!jsonl || !csv) throw std::runtime_error("cannot write the case files in " + dir);
  std::filesystem::rename(dir + "/cases.jsonl.tmp", dir + "/cases.jsonl");
  std::filesystem::rename(dir + "/cases.csv.tmp", dir + "/cases.csv");
}

CaseFiles::CaseFiles(const std::string& dir) {
  std::filesystem::create_directories(dir);
  jsonl_ = ::open((dir + "/cases.jsonl").c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  csv_ = ::open((dir + "/cases.csv").c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (jsonl_ < 0 || csv_ < 0) throw std::runtime_error("cannot open the case files in " + dir);
  struct stat st {};
  if (::fstat(csv_, &st) == 0 && st.st_size == 0) WriteAll(csv_, CsvHeader());
}

CaseFiles::~CaseFiles() {
  if (jsonl_ >= 0) ::close(jsonl_);
  if (csv_ >= 0) ::close(csv_);
}

void CaseFiles::Write(const CaseResult& r) {
  WriteAll(jsonl_, r.dump() + "\n");
  WriteAll(csv_, CsvRow(r));
}

}  // namespace vmt::sim::study
