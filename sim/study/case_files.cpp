#include "sim/study/case_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>

#include "common/json_text.hpp"
#include "common/output_file.hpp"

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

constexpr size_t kErrorsShown = 10;  // of a corrupt cases.jsonl's bad lines

void WriteAll(int fd, const std::string& s, const std::string& path) {
  size_t done = 0;
  while (done < s.size()) {
    const ssize_t n = ::write(fd, s.data() + done, s.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw common::WriteError(path, n < 0 ? errno : ENOSPC);
    done += static_cast<size_t>(n);
  }
}

}  // namespace

std::string LineError(const std::string& line, CaseResult& r) {
  r = nlohmann::ordered_json::parse(line, nullptr, false);
  if (r.is_discarded()) return "not JSON";
  if (!r.is_object()) return "not a JSON object";
  if (!r.contains("case") || !r["case"].is_string()) return "no \"case\" id";
  return "";
}

std::string CaseJsonLine(const CaseResult& r) {
  return r.dump(-1, ' ', false, common::kReplaceBadUtf8) + '\n';
}

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

std::vector<CaseResult> ReadCases(const std::string& jsonl_path, TornLine torn,
                                  const std::function<CaseResult(CaseResult&&)>& keep) {
  std::vector<CaseResult> out;
  std::ifstream in(jsonl_path, std::ios::binary);
  std::string errors, text;
  size_t bad = 0, line = 0;
  const auto fault = [&](const std::string& why) {
    if (++bad <= kErrorsShown)
      errors += "\n" + jsonl_path + ":" + std::to_string(line) + ": " + why;
  };
  while (std::getline(in, text)) {
    if (in.eof()) {  // no line break after it
      if (torn == TornLine::kError) {
        ++line;
        fault("the last line is cut short (the study was stopped while writing it; run it again)");
      }
      break;
    }
    ++line;
    CaseResult r;
    const std::string why = LineError(text, r);
    if (!why.empty())
      fault(why);
    else
      out.push_back(keep ? keep(std::move(r)) : std::move(r));
  }
  if (bad > kErrorsShown) errors += "\n... and " + std::to_string(bad - kErrorsShown) + " more";
  if (bad > 0)
    throw std::runtime_error(jsonl_path + ": " + std::to_string(bad) + " of " +
                             std::to_string(line) + " lines are no case:" + errors);
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
  common::OutputFile jsonl(dir + "/cases.jsonl");
  common::OutputFile csv(dir + "/cases.csv");
  csv.Write(CsvHeader());
  for (const CaseResult& r : cases) {
    jsonl.Write(CaseJsonLine(r));
    csv.Write(CsvRow(r));
  }
  jsonl.Commit();
  csv.Commit();
}

CaseFiles::CaseFiles(const std::string& dir) {
  std::filesystem::create_directories(dir);
  jsonl_path_ = dir + "/cases.jsonl";
  csv_path_ = dir + "/cases.csv";
  jsonl_ = ::open(jsonl_path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (jsonl_ < 0) throw common::WriteError(jsonl_path_, errno);
  csv_ = ::open(csv_path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (csv_ < 0) throw common::WriteError(csv_path_, errno);
  struct stat st {};
  if (::fstat(csv_, &st) == 0 && st.st_size == 0) WriteAll(csv_, CsvHeader(), csv_path_);
}

CaseFiles::~CaseFiles() {
  if (jsonl_ >= 0) ::close(jsonl_);
  if (csv_ >= 0) ::close(csv_);
}

void CaseFiles::Write(const CaseResult& r) {
  WriteAll(jsonl_, r.dump(-1, ' ', false, common::kReplaceBadUtf8) + "\n", jsonl_path_);
  WriteAll(csv_, CsvRow(r), csv_path_);
}

}  // namespace vmt::sim::study
