#include "sim/study/study_report.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "sim/study/case_files.hpp"
#include "sim/study/case_snapshots.hpp"

namespace vmt::sim::study {
namespace {

std::string Esc(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<')
      o += "&lt;";
    else if (c == '>')
      o += "&gt;";
    else if (c == '&')
      o += "&amp;";
    else if (c == '"')
      o += "&quot;";
    else
      o += c;
  }
  return o;
}

std::string Num(double v, const char* fmt = "%.3f") {
  char buf[32];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

std::string Str(const CaseResult& r, const char* key) {
  return r.contains(key) && r[key].is_string() ? r[key].get<std::string>() : "";
}

// The link that watches a case: served by `vmt view STUDY_DIR`, which saves the case's run and
// opens a replay station for it.
std::string ReplayHref(const std::string& case_id) {
  std::string q = "replay?case=";
  for (const unsigned char c : case_id) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~') {
      q += static_cast<char>(c);
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      q += hex;
    }
  }
  return q;
}

const char* Colour(const std::string& verdict) {
  if (verdict == "clear") return "#2a9d3f";
  if (verdict == "collision") return "#d62828";
  return "#f08c00";
}

struct Box {
  double z0 = std::numeric_limits<double>::infinity(), z1 = -z0, x0 = z0, x1 = -z0;
  void Add(double x, double z) {
    x0 = std::min(x0, x), x1 = std::max(x1, x), z0 = std::min(z0, z), z1 = std::max(z1, z);
  }
};

// The XZ plane: Z to the right, X (the tool's radius) up, one scale for both.
std::string Plane(const std::vector<const CaseResult*>& cases, const Reference* ref) {
  Box box;
  if (ref)
    for (const auto& [x, z] : ref->path) box.Add(x, z);
  for (const CaseResult* r : cases)
    for (const auto& p : (*r)["path"]) box.Add(p[0].get<double>(), p[1].get<double>());
  if (!std::isfinite(box.x0)) return "<p>(no paths)</p>\n";
  const double w = 640, h = 420, pad = 20;
  const double span_z = std::max(box.z1 - box.z0, 1.0), span_x = std::max(box.x1 - box.x0, 1.0);
  const double s = std::min((w - 2 * pad) / span_z, (h - 2 * pad) / span_x);
  auto px = [&](double z) { return Num(pad + (z - box.z0) * s, "%.1f"); };
  auto py = [&](double x) { return Num(h - pad - (x - box.x0) * s, "%.1f"); };
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w << "\" height=\"" << h
    << "\" style=\"border:1px solid #ccc;background:#fff\">\n";
  o << "<text x=\"" << w - 60 << "\" y=\"" << h - 5 << "\" font-size=\"11\">Z &#8594;</text>"
    << "<text x=\"4\" y=\"14\" font-size=\"11\">X &#8593;</text>\n";
  if (ref && !ref->path.empty()) {
    o << "<polyline fill=\"none\" stroke=\"#888\" stroke-width=\"1.5\" points=\"";
    for (const auto& [x, z] : ref->path) o << px(z) << "," << py(x) << " ";
    o << "\"><title>the program's tool path (reference run)</title></polyline>\n";
  }
  // Clear first, so that collisions and errors are drawn on top.
  for (const char* pass : {"clear", "error", "collision"})
    for (const CaseResult* r : cases) {
      const std::string v = Str(*r, "verdict");
      const std::string kind = v == "clear" || v == "collision" ? v : "error";
      if (kind != pass) continue;
      const auto& path = (*r)["path"];
      if (path.empty()) continue;
      o << "<a href=\"" << Esc(ReplayHref(Str(*r, "case"))) << "\">";
      o << "<polyline fill=\"none\" stroke-opacity=\"0.6\" stroke=\"" << Colour(v)
        << "\" stroke-width=\"1\" points=\"";
      for (const auto& p : path)
        o << px(p[1].get<double>()) << "," << py(p[0].get<double>()) << " ";
      o << "\"><title>" << Esc(Str(*r, "case")) << ": " << Esc(v) << "</title></polyline></a>\n";
      if (v == "collision") {
        const auto& last = path.back();
        o << "<circle r=\"3\" fill=\"#d62828\" cx=\"" << px(last[1].get<double>()) << "\" cy=\""
          << py(last[0].get<double>()) << "\"><title>" << Esc(Str(*r, "case")) << ": "
          << Esc((*r)["parts"].dump()) << "</title></circle>\n";
      }
    }
  o << "</svg>\n";
  return o.str();
}

}  // namespace

std::string ReportHtml(const std::string& title, const std::vector<CaseResult>& cases,
                       const Reference* reference,
                       const std::map<std::string, std::string>& snapshots) {
  std::map<std::string, std::vector<const CaseResult*>> by_sub;
  for (const CaseResult& r : cases) by_sub[Str(r, "subroutine")].push_back(&r);
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << Esc(title)
    << "</title>\n<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}"
       "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}td.l,th.l{text-align:left}"
       ".clear{color:#2a9d3f}.collision{color:#d62828}.error{color:#f08c00}</style></head><body>\n";
  o << "<h1>" << Esc(title) << "</h1>\n<p>" << cases.size()
    << " cases. Verdicts: <span class=\"clear\">clear</span> (the REPOS subroutine returned, "
       "or the operator's manual jogs restored the conditions, PxxS.CREST; every move checked "
       "clear by PathGuard), <span class=\"collision\">collision</span> (PathGuard found a "
       "contact on a REPOS move or a manual return jog), <span class=\"error\">error</span> "
       "(another NC error or a timeout). The rows <i>manual X,Z</i> are the operator jogging "
       "back in manual mode in that order of axes (repositioning manual 3).</p>\n";
  o << "<h2>Summary per REPOS subroutine or manual order</h2>\n<table><tr><th class=\"l\">"
       "subroutine</th>"
       "<th class=\"l\">mode</th><th>cases</th><th>clear</th><th>collisions</th><th>errors</th>"
       "<th>worst clearance, mm</th></tr>\n";
  for (const auto& [sub, list] : by_sub) {
    std::map<std::string, std::vector<const CaseResult*>> by_mode;
    for (const CaseResult* r : list) by_mode[Str(*r, "mode")].push_back(r);
    by_mode["all"] = list;
    for (const auto& [mode, ms] : by_mode) {
      int clear = 0, coll = 0, err = 0;
      double worst = std::numeric_limits<double>::infinity();
      for (const CaseResult* r : ms) {
        const std::string v = Str(*r, "verdict");
        clear += v == "clear", coll += v == "collision", err += v != "clear" && v != "collision";
        if (v == "clear" && (*r)["min_clearance_mm"].is_number())
          worst = std::min(worst, (*r)["min_clearance_mm"].get<double>());
      }
      o << "<tr><td class=\"l\">" << Esc(sub) << "</td><td class=\"l\">" << Esc(mode) << "</td><td>"
        << ms.size() << "</td><td class=\"clear\">" << clear << "</td><td class=\"collision\">"
        << coll << "</td><td class=\"error\">" << err << "</td><td>"
        << (std::isfinite(worst) ? Num(worst) : "&#8211;") << "</td></tr>\n";
    }
  }
  o << "</table>\n";
  for (const auto& [sub, list] : by_sub) {
    o << "<h2>" << Esc(sub) << ": approach paths in the XZ plane</h2>\n"
      << "<p>Grey: the program's tool path (the contour as turned). Each case's REPOS path from "
         "where the operator left the tool, coloured by verdict; a dot marks a first contact "
         "(hover for the case).</p>\n"
      << Plane(list, reference);
    std::vector<const CaseResult*> worst;
    for (const CaseResult* r : list)
      if (Str(*r, "verdict") != "clear") worst.push_back(r);
    std::vector<const CaseResult*> tight;
    for (const CaseResult* r : list)
      if (Str(*r, "verdict") == "clear" && (*r)["min_clearance_mm"].is_number()) tight.push_back(r);
    std::stable_sort(tight.begin(), tight.end(), [](const CaseResult* a, const CaseResult* b) {
      return (*a)["min_clearance_mm"].get<double>() < (*b)["min_clearance_mm"].get<double>();
    });
    if (tight.size() > 5) tight.resize(5);
    if (worst.size() > 20) worst.resize(20);
    worst.insert(worst.end(), tight.begin(), tight.end());
    o << "<h3>Worst cases</h3>\n<table><tr><th class=\"l\">case</th><th class=\"l\">verdict"
         "</th><th class=\"l\">first contact</th><th class=\"l\">point, mm</th><th>clearance, mm"
         "</th><th class=\"l\">error</th><th class=\"l\">picture</th><th class=\"l\">replay"
         "</th></tr>\n";
    for (const CaseResult* r : worst) {
      const std::string v = Str(*r, "verdict");
      o << "<tr><td class=\"l\">" << Esc(Str(*r, "case")) << "</td><td class=\"l " << Esc(v)
        << "\">" << Esc(v) << "</td><td class=\"l\">"
        << ((*r)["parts"].is_array() ? Esc((*r)["parts"].dump()) : "") << "</td><td class=\"l\">"
        << ((*r)["point"].is_array() ? Esc((*r)["point"].dump()) : "") << "</td><td>"
        << ((*r)["min_clearance_mm"].is_number() ? Num((*r)["min_clearance_mm"].get<double>()) : "")
        << "</td><td class=\"l\">" << Esc(Str(*r, "error")) << "</td><td class=\"l\">";
      const auto shot = snapshots.find(Str(*r, "case"));
      if (shot != snapshots.end()) o << "<a href=\"" << Esc(shot->second) << "\">picture</a>";
      o << "</td><td class=\"l\"><a class=\"replay\" href=\"" << Esc(ReplayHref(Str(*r, "case")))
        << "\">watch</a></td></tr>\n";
    }
    o << "</table>\n";
    // The pictures of this subroutine's worst cases: a collision at its first contact, the
    // tightest clear case at its end.
    bool any = false;
    for (const CaseResult* r : list) {
      const auto shot = snapshots.find(Str(*r, "case"));
      if (shot == snapshots.end()) continue;
      if (!any) o << "<h3>Pictures of the worst cases</h3>\n<div>\n";
      any = true;
      const std::string v = Str(*r, "verdict");
      o << "<figure style=\"display:inline-block;margin:4px\"><a href=\"" << Esc(shot->second)
        << "\"><img src=\"" << Esc(shot->second) << "\" width=\"320\" alt=\""
        << Esc(Str(*r, "case")) << "\"></a><figcaption class=\"" << Esc(v) << "\">"
        << Esc(Str(*r, "case")) << ": " << Esc(v)
        << (v == "collision" ? " (first contact)" : " (end of the return)")
        << "</figcaption></figure>\n";
    }
    if (any) o << "</div>\n";
  }
  o << "</body></html>\n";
  return o.str();
}

void WriteReport(const std::string& dir, const std::string& title) {
  const std::vector<CaseResult> cases = Deduplicated(ReadCases(dir + "/cases.jsonl"));
  std::optional<Reference> ref;
  std::ifstream in(dir + "/reference.json", std::ios::binary);
  if (in) {
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    try {
      ref = ReferenceFromJson(text);
    } catch (const std::exception&) {  // a torn reference only loses the contour
    }
  }
  std::ofstream(dir + "/report.html", std::ios::binary)
      << ReportHtml(title, cases, ref ? &*ref : nullptr, ReadSnapshotIndex(dir));
}

}  // namespace vmt::sim::study
