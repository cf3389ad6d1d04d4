#include "sim/cli/golden_report.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "common/json_text.hpp"
#include "common/output_file.hpp"

namespace vmt::sim {
namespace {

// Text for XML and HTML: the five characters that could end an element or an attribute.
std::string Escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

void WriteText(const std::string& path, const std::string& text) {
  common::WriteFileAtomically(path, text);
}

std::string Seconds(double t) {
  std::ostringstream s;
  s << t;
  return s.str();
}

}  // namespace

const char* ToString(GoldenStatus s) {
  switch (s) {
    case GoldenStatus::kPassed:
      return "passed";
    case GoldenStatus::kFailed:
      return "failed";
    case GoldenStatus::kMissing:
      return "missing";
    case GoldenStatus::kCreated:
      return "created";
    case GoldenStatus::kUpdated:
      return "updated";
    case GoldenStatus::kStale:
      return "stale";
    case GoldenStatus::kRemoved:
      return "removed";
  }
  return "failed";
}

bool IsFailure(GoldenStatus s) {
  return s == GoldenStatus::kFailed || s == GoldenStatus::kMissing || s == GoldenStatus::kStale;
}

bool GoldenScene::ok() const {
  for (const GoldenPicture& p : pictures)
    if (IsFailure(p.status)) return false;
  return run_failures.empty();
}

std::string ReplayCommand(const std::string& run_dir) {
  return "vmt view " + std::filesystem::absolute(run_dir).lexically_normal().string() +
         " --http 127.0.0.1:8080";
}

void WriteJUnit(const std::string& path, const std::vector<GoldenScene>& scenes) {
  int tests = 0, failures = 0;
  std::ostringstream body;
  for (const GoldenScene& s : scenes) {
    const bool run_case = s.ran || !s.run_failures.empty();
    int suite_failures = run_case && !s.run_failures.empty() ? 1 : 0;
    for (const GoldenPicture& p : s.pictures) suite_failures += IsFailure(p.status) ? 1 : 0;
    const int suite_tests = int(s.pictures.size()) + (run_case ? 1 : 0);
    tests += suite_tests, failures += suite_failures;
    body << "  <testsuite name=\"" << Escape(s.name) << "\" tests=\"" << suite_tests
         << "\" failures=\"" << suite_failures << "\" errors=\"0\">\n";
    if (run_case) {
      body << "    <testcase classname=\"golden." << Escape(s.name) << "\" name=\"run\">";
      if (!s.run_failures.empty()) {
        std::string all;
        for (const std::string& f : s.run_failures) all += f + "\n";
        body << "\n      <failure message=\"" << Escape(s.run_failures.front())
             << "\" type=\"run\">" << Escape(all) << "</failure>\n    ";
      }
      body << "</testcase>\n";
    }
    for (const GoldenPicture& p : s.pictures) {
      body << "    <testcase classname=\"golden." << Escape(s.name) << "\" name=\""
           << Escape(p.file) << "\">";
      if (IsFailure(p.status)) {
        std::ostringstream text;
        text << "status: " << ToString(p.status) << "\n";
        if (!p.actual.empty()) text << "t: " << Seconds(p.t) << " s\n";
        if (p.compared)
          text << "differing pixels: " << p.differing_pixels << " of " << p.compared_pixels
               << " compared (" << p.masked_pixels << " masked), fraction " << p.differing_fraction
               << ", allowed " << p.allowed_fraction << ", tolerance " << p.tolerance_levels
               << " levels, max channel delta " << p.max_channel_delta << "\n";
        text << "golden: " << p.golden << "\n";
        if (!p.actual.empty()) text << "actual: " << p.actual << "\n";
        if (!p.page.empty()) text << "page: " << p.page << "\n";
        body << "\n      <failure message=\"" << Escape(p.detail) << "\" type=\""
             << ToString(p.status) << "\">" << Escape(text.str()) << "</failure>\n    ";
      }
      body << "</testcase>\n";
    }
    body << "  </testsuite>\n";
  }
  WriteText(path,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"vmt golden\" "
            "tests=\"" +
                std::to_string(tests) + "\" failures=\"" + std::to_string(failures) + "\">\n" +
                body.str() + "</testsuites>\n");
}

void WriteJson(const std::string& path, const std::vector<GoldenScene>& scenes) {
  nlohmann::ordered_json doc;
  bool passed = true;
  auto& list = doc["scenes"] = nlohmann::ordered_json::array();
  for (const GoldenScene& s : scenes) {
    passed = passed && s.ok();
    nlohmann::ordered_json scene = {{"scene", s.name},
                                    {"out_dir", s.out_dir},
                                    {"passed", s.ok()},
                                    {"ran", s.ran},
                                    {"run_failures", s.run_failures}};
    auto& pictures = scene["pictures"] = nlohmann::ordered_json::array();
    for (const GoldenPicture& p : s.pictures) {
      nlohmann::ordered_json j = {
          {"file", p.file},     {"t", p.t},           {"status", ToString(p.status)},
          {"detail", p.detail}, {"golden", p.golden}, {"actual", p.actual}};
      if (p.compared) {
        j["differing_pixels"] = p.differing_pixels;
        j["compared_pixels"] = p.compared_pixels;
        j["masked_pixels"] = p.masked_pixels;
        j["differing_fraction"] = p.differing_fraction;
        j["allowed_fraction"] = p.allowed_fraction;
        j["tolerance_levels"] = p.tolerance_levels;
        j["max_channel_delta"] = p.max_channel_delta;
      }
      if (!p.page.empty()) j["page"] = p.page;
      pictures.push_back(std::move(j));
    }
    list.push_back(std::move(scene));
  }
  doc["passed"] = passed;
  // "passed" first, for a reader that looks at the top only.
  nlohmann::ordered_json out = {{"passed", passed}, {"scenes", doc["scenes"]}};
  WriteText(path, out.dump(2, ' ', false, common::kReplaceBadUtf8) + "\n");
}

void WriteFailurePage(const std::string& dir, const GoldenPicture& p, const std::string& run_dir) {
  const std::string t = Seconds(p.t), shot = Escape(p.file);
  const std::string diff =
      std::filesystem::exists(dir + "/diff.png")
          ? "<figure><img src=\"diff.png\"><figcaption>difference (red: beyond tolerance, blue "
            "stripes: masked)</figcaption></figure>"
          : "";
  std::ostringstream html;
  html << "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>" << shot
       << " differs from its golden</title>\n<style>body{font-family:sans-serif;margin:2em}"
          "figure{display:inline-block;margin:4px}</style></head>\n<body><h1>"
       << shot << " differs from its golden</h1><p>" << Escape(p.detail) << "</p>\n"
       << "<figure><img src=\"golden.png\"><figcaption>golden</figcaption></figure>\n"
       << "<figure><img src=\"actual.png\"><figcaption>actual</figcaption></figure>" << diff
       << "\n<p>Golden: <code>" << Escape(p.golden) << "</code></p>\n"
       << "<p>Watch the run at the picture's time (t = " << t << " s): run <code>"
       << Escape(ReplayCommand(run_dir))
       << "</code>, then open <a href=\"http://127.0.0.1:8080/?t=" << t
       << "\">http://127.0.0.1:8080/?t=" << t << "</a>.</p></body></html>\n";
  WriteText(dir + "/index.html", html.str());
}

}  // namespace vmt::sim
