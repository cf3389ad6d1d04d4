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

#include "common/output_file.hpp"
#include "sim/study/case_files.hpp"
#include "sim/study/case_snapshots.hpp"
#include "sim/study/study_conclusions.hpp"
#include "sim/study/study_plane.hpp"

namespace vmt::sim::study {
namespace {

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

// The contact point in machine coordinates (where the tool tip would touch it), else in the
// model frame, said so.
std::string ContactPoint(const CaseResult& r, const Reference* ref) {
  const auto& p = Field(r, "point");
  if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() || !p[2].is_number())
    return "";
  if (ref && ref->has_tip)
    return "X" + Num(std::hypot(p[0].get<double>(), p[1].get<double>()) - ref->tip_x) + " Z" +
           Num(p[2].get<double>() - ref->tip_z);
  return "model frame " + p.dump();
}

// The NC's message of a case. A contact's is said by the columns before it (PathGuard's text
// gives the point in the model frame): its number only.
std::string Message(const CaseResult& r) {
  const std::string cls = ClassOf(r);
  if ((cls == "crash" || cls == "graze") && Field(r, "error_number").is_number())
    return "NC error " + std::to_string(Field(r, "error_number").get<int>());
  return Str(r, "error");
}

std::string ClassName(const std::string& cls) {
  return cls == "retract_refused" ? "retract refused" : cls;
}

void Conclude(std::ostringstream& o, const std::vector<CaseResult>& cases, const Reference* ref) {
  o << "<h2>Conclusions</h2>\n";
  for (const ModeConclusion& m : Conclusions(cases, ref)) {
    o << "<h3>" << Esc(m.mode) << "</h3>\n<p class=\"headline\"><b>" << Esc(m.headline)
      << "</b></p>\n<ul>\n";
    for (const std::string& s : m.sentences) o << "<li>" << Esc(s) << "</li>\n";
    o << "</ul>\n";
  }
}

}  // namespace

std::string ReportHtml(const std::string& title, const std::vector<CaseResult>& cases,
                       const Reference* reference,
                       const std::map<std::string, std::string>& snapshots) {
  std::map<std::string, std::vector<const CaseResult*>> by_sub;
  for (const CaseResult& r : cases) by_sub[Str(r, "subroutine")].push_back(&r);
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << Esc(title)
    << "</title>\n<style>body{font-family:sans-serif;margin:2em;max-width:80em}"
       "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:3px 8px;"
       "text-align:right}td.l,th.l{text-align:left}.clear{color:#2a9d3f}.crash{color:#d62828}"
       ".graze{color:#7b2cbf}.error{color:#f08c00}.retract_refused{color:#6c757d}"
       "dt{font-weight:bold}</style></head><body>\n";
  o << "<h1>" << Esc(title) << "</h1>\n<p>" << cases.size() << " cases.</p>\n";
  Conclude(o, cases, reference);
  o << "<h2>How to read this report</h2>\n<dl>"
       "<dt>Classes</dt><dd><span class=\"clear\">clear</span>: the REPOS subroutine returned "
       "(or the operator's manual jogs restored the conditions, PxxS.CREST) with every move "
       "checked clear by PathGuard. <span class=\"crash\">crash</span>: PathGuard found a "
       "contact on a REPOS move or a manual return jog, farther than "
    << Num(kGrazeMm, "%.1f")
    << " mm before the move's end. <span class=\"graze\">graze</span>: the first contact lies "
       "within "
    << Num(kGrazeMm, "%.1f")
    << " mm of the move's end: the parts only meet where the move stops (typically the tool "
       "set back onto the contour it was cutting). <span class=\"error\">error</span>: another "
       "NC error or a timeout. <span class=\"retract_refused\">retract refused</span>: PathGuard "
       "refused the operator's own retract jog, so no return was tried: the operator's problem, "
       "counted apart and not against the subroutine. The rows <i>manual X,Z</i> are the "
       "operator jogging back in manual mode in that order of axes (repositioning manual 3)."
       "</dd><dt>Severity</dt><dd>For a contact: how far the refused move would have gone on "
       "past its first contact (the axes' distance from the contact position to the move's end, "
       "mm): the depth the parts would have run into each other along the move. Worst cases are "
       "sorted by it: crashes deepest first, then grazes, then errors, then the clear cases with "
       "the smallest clearance.</dd><dt>Clearance</dt><dd>The smallest distance PathGuard found "
       "between two parts that move against each other (tool, turret and slides against the "
       "chuck, its jaws, the tailstock and the part as turned) over the REPOS moves it checked "
       "clear, mm; exact to 10 &#181;m or 10 %, never reported larger than it is. For a contact: "
       "over the moves before the refused one.</dd><dt>Coordinates</dt><dd>Machine coordinates "
       "throughout: X and Z are the axes' positions as the NC shows them (mm). Points in space "
       "(a contact point, the chuck's parts) are given where the tool tip touches them at those "
       "axis positions";
  if (reference && reference->has_tip)
    o << " (the model frame shifted by the tool tip's offset: x &#8722; " << Num(reference->tip_x)
      << " mm, z &#8722; " << Num(reference->tip_z) << " mm)";
  o << ".</dd></dl>\n";
  o << "<h2>Summary per REPOS subroutine or manual order</h2>\n<table><tr><th class=\"l\">"
       "subroutine</th><th class=\"l\">mode</th><th>cases</th><th>clear</th><th>crash</th>"
       "<th>graze</th><th>errors</th><th>retract refused</th><th title=\"the smallest clearance "
       "PathGuard found on the REPOS moves of the clear cases\">worst clearance, mm</th>"
       "<th title=\"how far a refused move would have gone on past its first contact, the "
       "largest\">deepest past contact, mm</th></tr>\n";
  for (const auto& [sub, list] : by_sub) {
    std::map<std::string, std::vector<const CaseResult*>> by_mode;
    for (const CaseResult* r : list) by_mode[Str(*r, "mode")].push_back(r);
    by_mode["all"] = list;
    for (const auto& [mode, ms] : by_mode) {
      ClassCount n;
      double worst = std::numeric_limits<double>::infinity(), deepest = -1;
      for (const CaseResult* r : ms) {
        n.Add(*r);
        const std::string cls = ClassOf(*r);
        if (cls == "clear" && Field(*r, "min_clearance_mm").is_number())
          worst = std::min(worst, Field(*r, "min_clearance_mm").get<double>());
        if ((cls == "crash" || cls == "graze") && Field(*r, "past_contact_mm").is_number())
          deepest = std::max(deepest, Field(*r, "past_contact_mm").get<double>());
      }
      o << "<tr><td class=\"l\">" << Esc(sub) << "</td><td class=\"l\">" << Esc(mode) << "</td><td>"
        << n.cases << "</td><td class=\"clear\">" << n.clear << "</td><td class=\"crash\">"
        << n.crash << "</td><td class=\"graze\">" << n.graze << "</td><td class=\"error\">"
        << n.error << "</td><td class=\"retract_refused\">" << n.retract_refused << "</td><td>"
        << (std::isfinite(worst) ? Num(worst) : "&#8211;") << "</td><td>"
        << (deepest >= 0 ? Num(deepest) : "&#8211;") << "</td></tr>\n";
    }
  }
  o << "</table>\n";
  for (const auto& [sub, list] : by_sub) {
    o << "<h2>" << Esc(sub) << ": approach paths in the XZ plane</h2>\n"
      << "<p>Machine coordinates, mm. Grey: the program's tool path (the contour as turned); "
         "dashed: the chuck's parts as the envelopes they sweep while the spindle turns (what "
         "PathGuard checks against). Each case's REPOS path from where the operator left the "
         "tool, coloured by class; a dot marks where the tool stood at a first contact, a cross "
         "the contact point (hover for the case, click to watch it).</p>\n"
      << PlaneSvg(list, reference, [](const std::string& id) { return ReplayHref(id); });
    std::vector<const CaseResult*> worst;
    for (const CaseResult* r : list) {
      const std::string cls = ClassOf(*r);
      if (cls != "clear" && cls != "retract_refused") worst.push_back(r);
    }
    std::vector<const CaseResult*> tight;
    for (const CaseResult* r : list)
      if (ClassOf(*r) == "clear" && Field(*r, "min_clearance_mm").is_number()) tight.push_back(r);
    const auto severe = [](const CaseResult* a, const CaseResult* b) { return MoreSevere(*a, *b); };
    std::stable_sort(worst.begin(), worst.end(), severe);
    std::stable_sort(tight.begin(), tight.end(), severe);
    if (tight.size() > 5) tight.resize(5);
    if (worst.size() > 20) worst.resize(20);
    worst.insert(worst.end(), tight.begin(), tight.end());
    o << "<h3>Worst cases, most severe first</h3>\n<table><tr><th class=\"l\">case</th>"
         "<th class=\"l\">class</th><th class=\"l\">first contact</th><th class=\"l\">"
         "move</th><th class=\"l\">axes at the contact</th><th class=\"l\">contact point</th>"
         "<th title=\"how far the refused move would have gone on past its first contact\">past "
         "contact, mm</th><th title=\"the smallest clearance PathGuard found on the REPOS moves "
         "(before the refused one)\">clearance, mm</th><th class=\"l\">NC message</th>"
         "<th class=\"l\">picture</th><th class=\"l\">replay</th></tr>\n";
    for (const CaseResult* r : worst) {
      const std::string cls = ClassOf(*r);
      o << "<tr><td class=\"l\">" << Esc(Str(*r, "case")) << "</td><td class=\"l " << Esc(cls)
        << "\">" << Esc(ClassName(cls)) << "</td><td class=\"l\">"
        << (Field(*r, "parts").is_array() ? Esc(Field(*r, "parts").dump()) : "")
        << "</td><td class=\"l\">" << Esc(Str(*r, "contact_move")) << "</td><td class=\"l\">"
        << Esc(ContactAxes(*r)) << "</td><td class=\"l\">" << Esc(ContactPoint(*r, reference))
        << "</td><td>"
        << (Field(*r, "past_contact_mm").is_number()
                ? Num(Field(*r, "past_contact_mm").get<double>())
                : "")
        << "</td><td>"
        << (Field(*r, "min_clearance_mm").is_number()
                ? Num(Field(*r, "min_clearance_mm").get<double>())
                : "")
        << "</td><td class=\"l\">" << Esc(Message(*r)) << "</td><td class=\"l\">";
      const auto shot = snapshots.find(Str(*r, "case"));
      if (shot != snapshots.end()) o << "<a href=\"" << Esc(shot->second) << "\">picture</a>";
      o << "</td><td class=\"l\"><a class=\"replay\" href=\"" << Esc(ReplayHref(Str(*r, "case")))
        << "\">watch</a></td></tr>\n";
    }
    o << "</table>\n";
    // The pictures of this subroutine's worst cases: a collision at its first contact, the
    // tightest clear case at its end.
    std::vector<const CaseResult*> pictured;
    for (const CaseResult* r : list)
      if (snapshots.count(Str(*r, "case"))) pictured.push_back(r);
    std::stable_sort(pictured.begin(), pictured.end(), severe);
    if (!pictured.empty())
      o << "<h3>Pictures of the worst cases</h3>\n<p>A collision is pictured with the axes "
           "at its first contact: the two parts that meet are drawn magenta, a cyan cross marks "
           "the contact point, the workpiece as turned.</p>\n<div>\n";
    for (const CaseResult* r : pictured) {
      const std::string& file = snapshots.at(Str(*r, "case"));
      const std::string cls = ClassOf(*r);
      const bool contact = cls == "crash" || cls == "graze";
      o << "<figure style=\"display:inline-block;margin:4px\"><a href=\"" << Esc(file)
        << "\"><img src=\"" << Esc(file) << "\" width=\"320\" alt=\"" << Esc(Str(*r, "case"))
        << "\"></a><figcaption class=\"" << Esc(cls) << "\">" << Esc(Str(*r, "case")) << ": "
        << Esc(ClassName(cls))
        << (contact ? " (first contact: " + Esc(Field(*r, "parts").dump()) + ")"
                    : " (end of the return)")
        << "</figcaption></figure>\n";
    }
    if (!pictured.empty()) o << "</div>\n";
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
  common::WriteFileAtomically(dir + "/report.html", ReportHtml(title, cases, ref ? &*ref : nullptr,
                                                               ReadSnapshotIndex(dir)));
}

}  // namespace vmt::sim::study
