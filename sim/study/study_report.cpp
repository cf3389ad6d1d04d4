#include "sim/study/study_report.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "common/json_text.hpp"
#include "common/output_file.hpp"
#include "sim/study/case_files.hpp"
#include "sim/study/case_merge.hpp"
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

void Conclude(std::ostringstream& o, const std::vector<ModeConclusion>& conclusions) {
  o << "<h2>Conclusions</h2>\n";
  for (const ModeConclusion& m : conclusions) {
    o << "<h3>" << Esc(m.mode) << "</h3>\n<p class=\"headline\"><b>" << Esc(m.headline)
      << "</b></p>\n<ul>\n";
    for (const std::string& s : m.sentences) o << "<li>" << Esc(s) << "</li>\n";
    o << "</ul>\n";
  }
}

// The `n` most severe of the cases added (MoreSevere), most severe first.
class MostSevere {
 public:
  explicit MostSevere(size_t n) : n_(n) {}
  void Add(const CaseResult& r) {
    if (n_ == 0 || (kept_.size() == n_ && !MoreSevere(r, kept_.back()))) return;
    kept_.insert(std::upper_bound(kept_.begin(), kept_.end(), r, MoreSevere), r);
    if (kept_.size() > n_) kept_.pop_back();
  }
  const std::vector<CaseResult>& kept() const { return kept_; }

 private:
  size_t n_;
  std::vector<CaseResult> kept_;
};

// A row of the summary: one subroutine in one mode (or all its modes).
struct SummaryRow {
  ClassCount n;
  double worst = std::numeric_limits<double>::infinity(), deepest = -1;
  void Add(const CaseResult& r) {
    n.Add(r);
    const std::string cls = ClassOf(r);
    if (cls == "clear" && Field(r, "min_clearance_mm").is_number())
      worst = std::min(worst, Field(r, "min_clearance_mm").get<double>());
    if ((cls == "crash" || cls == "graze") && Field(r, "past_contact_mm").is_number())
      deepest = std::max(deepest, Field(r, "past_contact_mm").get<double>());
  }
};

// What the report keeps of one subroutine's cases.
struct SubroutineTally {
  std::map<std::string, SummaryRow> by_mode;
  SummaryRow all;
  MostSevere plane{kPlaneCases};
  MostSevere worst{20};  // the failures
  MostSevere tight{5};   // the clear cases with a clearance
  std::vector<CaseResult> pictured;
};

// The table of all cases: an empty table the page's script fills a page file at a time
// (cases-pages/N.js, each calling vmtCasesPage(N, rows)): a <script> element loads from a file://
// report and from `vmt view` alike, and the browser holds one page of rows, not the study.
void AllCases(std::ostringstream& o, size_t cases, size_t pages) {
  o << "<h2>All cases</h2>\n<p>" << cases << " cases in case id order, " << kCasesPerPage
    << " to a page (cases.csv and cases.jsonl beside this report hold them all).</p>\n"
       "<p><button id=\"prev\">&#8592; previous</button> page <input id=\"page\" type=\"number\" "
       "min=\"1\" max=\""
    << pages << "\" value=\"1\" style=\"width:6em\"> of " << pages
    << " <button id=\"next\">next &#8594;</button> <span id=\"status\"></span></p>\n"
       "<table id=\"cases\"><thead><tr><th class=\"l\">case</th><th class=\"l\">subroutine</th>"
       "<th class=\"l\">mode</th><th class=\"l\">block</th><th class=\"l\">retract</th>"
       "<th class=\"l\">class</th><th>clearance, mm</th><th>past contact, mm</th>"
       "<th class=\"l\">NC message</th><th class=\"l\">replay</th></tr></thead>"
       "<tbody id=\"rows\"></tbody></table>\n<script>\n(function() {\n  var pages = "
    << pages << R"JS(, shown = 0;
  var rows = document.getElementById('rows'), page = document.getElementById('page');
  var status = document.getElementById('status');
  window.vmtCasesPage = function(n, list) {
    if (n !== shown) return;
    rows.textContent = '';
    list.forEach(function(r) {
      var tr = document.createElement('tr');
      r.forEach(function(v, i) {
        var td = document.createElement('td');
        if (i < 6 || i === 8) td.className = 'l';
        if (i === 5) td.className += ' ' + v.replace(' ', '_');
        td.textContent = v === null ? '' : String(v);
        tr.appendChild(td);
      });
      var td = document.createElement('td'), a = document.createElement('a');
      td.className = 'l';
      a.className = 'replay';
      a.href = 'replay?case=' + encodeURIComponent(r[0]);
      a.textContent = 'watch';
      td.appendChild(a);
      tr.appendChild(td);
      rows.appendChild(tr);
    });
    status.textContent = '';
  };
  function show(n) {
    n = Math.max(1, Math.min(pages, Math.floor(Number(n)) || 1));
    shown = n;
    page.value = n;
    status.textContent = 'loading...';
    var s = document.createElement('script');
    s.src = 'cases-pages/' + n + '.js';
    s.onload = function() { s.remove(); };
    s.onerror = function() { status.textContent = 'page file ' + s.src + ' missing'; };
    document.body.appendChild(s);
  }
  document.getElementById('prev').onclick = function() { show(shown - 1); };
  document.getElementById('next').onclick = function() { show(shown + 1); };
  page.onchange = function() { show(page.value); };
  show(1);
})();
</script>
)JS";
}

// Writes dir/cases-pages/N.js, kCasesPerPage cases each, as the cases stream by.
class CasePages {
 public:
  explicit CasePages(const std::string& dir) : dir_(dir + "/cases-pages") {
    std::filesystem::remove_all(dir_);  // a page left from a larger study would be shown
    std::filesystem::create_directories(dir_);
  }
  void Add(const CaseResult& r) {
    const nlohmann::ordered_json& clearance = Field(r, "min_clearance_mm");
    const nlohmann::ordered_json& past = Field(r, "past_contact_mm");
    nlohmann::ordered_json row = {Str(r, "case"),
                                  Str(r, "subroutine"),
                                  Str(r, "mode"),
                                  Str(r, "block"),
                                  Str(r, "retract"),
                                  ClassName(ClassOf(r)),
                                  clearance.is_number() ? Num(clearance.get<double>()) : "",
                                  past.is_number() ? Num(past.get<double>()) : "",
                                  Message(r)};
    text_ += (rows_ ? ",\n" : "") + row.dump(-1, ' ', false, common::kReplaceBadUtf8);
    if (++rows_ == kCasesPerPage) Flush();
  }
  /// The pages written.
  size_t Finish() {
    Flush();
    return pages_;
  }

 private:
  void Flush() {
    if (rows_ == 0) return;
    ++pages_;
    common::WriteFileAtomically(
        dir_ + "/" + std::to_string(pages_) + ".js",
        "vmtCasesPage(" + std::to_string(pages_) + ", [\n" + text_ + "]);\n");
    text_.clear();
    rows_ = 0;
  }
  std::string dir_, text_;
  size_t rows_ = 0, pages_ = 0;
};

// What the classes, the severity, the clearance and the coordinates mean.
void HowToRead(std::ostringstream& o, const Reference* reference) {
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
}

// A row per subroutine (or manual order) and mode, and one for all its modes.
void SummaryTable(std::ostringstream& o, const std::map<std::string, SubroutineTally>& by_sub) {
  o << "<h2>Summary per REPOS subroutine or manual order</h2>\n<table><tr><th class=\"l\">"
       "subroutine</th><th class=\"l\">mode</th><th>cases</th><th>clear</th><th>crash</th>"
       "<th>graze</th><th>errors</th><th>retract refused</th><th title=\"the smallest clearance "
       "PathGuard found on the REPOS moves of the clear cases\">worst clearance, mm</th>"
       "<th title=\"how far a refused move would have gone on past its first contact, the "
       "largest\">deepest past contact, mm</th></tr>\n";
  for (const auto& [sub, t] : by_sub) {
    std::map<std::string, SummaryRow> rows = t.by_mode;
    rows["all"] = t.all;
    for (const auto& [mode, row] : rows) {
      const ClassCount& n = row.n;
      o << "<tr><td class=\"l\">" << Esc(sub) << "</td><td class=\"l\">" << Esc(mode) << "</td><td>"
        << n.cases << "</td><td class=\"clear\">" << n.clear << "</td><td class=\"crash\">"
        << n.crash << "</td><td class=\"graze\">" << n.graze << "</td><td class=\"error\">"
        << n.error << "</td><td class=\"retract_refused\">" << n.retract_refused << "</td><td>"
        << (std::isfinite(row.worst) ? Num(row.worst) : "&#8211;") << "</td><td>"
        << (row.deepest >= 0 ? Num(row.deepest) : "&#8211;") << "</td></tr>\n";
    }
  }
  o << "</table>\n";
}

// One subroutine's approach paths in the XZ plane, its worst cases and their pictures.
void SubroutineSection(std::ostringstream& o, const std::string& sub, const SubroutineTally& t,
                       const Reference* reference,
                       const std::map<std::string, std::string>& snapshots) {
  const auto severe = [](const CaseResult* a, const CaseResult* b) { return MoreSevere(*a, *b); };
  // The plane draws the cases in id order; a subroutine of more than kPlaneCases its most
  // severe ones (the page stays light whatever the study's size).
  std::vector<const CaseResult*> drawn;
  for (const CaseResult& r : t.plane.kept()) drawn.push_back(&r);
  std::sort(drawn.begin(), drawn.end(), [](const CaseResult* a, const CaseResult* b) {
    return Str(*a, "case") < Str(*b, "case");
  });
  o << "<h2>" << Esc(sub) << ": approach paths in the XZ plane</h2>\n"
    << "<p>Machine coordinates, mm. Grey: the program's tool path (the contour as turned); "
       "dashed: the chuck's parts as the envelopes they sweep while the spindle turns (what "
       "PathGuard checks against). Each case's REPOS path from where the operator left the "
       "tool, coloured by class; a dot marks where the tool stood at a first contact, a cross "
       "the contact point (hover for the case, click to watch it).";
  if (t.all.n.cases > drawn.size())
    o << " Drawn: the " << drawn.size() << " most severe of its " << t.all.n.cases << " cases.";
  o << "</p>\n" << PlaneSvg(drawn, reference, [](const std::string& id) { return ReplayHref(id); });
  std::vector<const CaseResult*> worst;
  for (const CaseResult& r : t.worst.kept()) worst.push_back(&r);
  for (const CaseResult& r : t.tight.kept()) worst.push_back(&r);
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
      << (Field(*r, "past_contact_mm").is_number() ? Num(Field(*r, "past_contact_mm").get<double>())
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
  for (const CaseResult& r : t.pictured) pictured.push_back(&r);
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

}  // namespace

struct ReportBuilder::State {
  std::map<std::string, SubroutineTally> by_sub;
  ConclusionTally conclusions;
  explicit State(const Reference* ref) : conclusions(ref) {}
};

ReportBuilder::ReportBuilder(const Reference* reference,
                             const std::map<std::string, std::string>& snapshots)
    : reference_(reference), snapshots_(snapshots), state_(std::make_unique<State>(reference)) {}

ReportBuilder::~ReportBuilder() = default;

void ReportBuilder::Add(const CaseResult& r) {
  ++cases_;
  state_->conclusions.Add(r);
  SubroutineTally& t = state_->by_sub[Str(r, "subroutine")];
  t.by_mode[Str(r, "mode")].Add(r);
  t.all.Add(r);
  t.plane.Add(r);
  const std::string cls = ClassOf(r);
  if (cls != "clear" && cls != "retract_refused") t.worst.Add(r);
  if (cls == "clear" && Field(r, "min_clearance_mm").is_number()) t.tight.Add(r);
  if (snapshots_.count(Str(r, "case"))) t.pictured.push_back(r);
}

std::string ReportBuilder::Html(const std::string& title, size_t pages) const {
  const Reference* reference = reference_;
  const std::map<std::string, std::string>& snapshots = snapshots_;
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << Esc(title)
    << "</title>\n<style>body{font-family:sans-serif;margin:2em;max-width:80em}"
       "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:3px 8px;"
       "text-align:right}td.l,th.l{text-align:left}.clear{color:#2a9d3f}.crash{color:#d62828}"
       ".graze{color:#7b2cbf}.error{color:#f08c00}.retract_refused{color:#6c757d}"
       "dt{font-weight:bold}</style></head><body>\n";
  o << "<h1>" << Esc(title) << "</h1>\n<p>" << cases_ << " cases.</p>\n";
  Conclude(o, state_->conclusions.Conclusions());
  HowToRead(o, reference);
  SummaryTable(o, state_->by_sub);
  for (const auto& [sub, t] : state_->by_sub) SubroutineSection(o, sub, t, reference, snapshots);
  if (pages > 0) AllCases(o, cases_, pages);
  o << "</body></html>\n";
  return o.str();
}

std::string ReportHtml(const std::string& title, const std::vector<CaseResult>& cases,
                       const Reference* reference,
                       const std::map<std::string, std::string>& snapshots) {
  ReportBuilder report(reference, snapshots);
  for (const CaseResult& r : cases) report.Add(r);
  return report.Html(title, 0);
}

void WriteReport(const std::string& dir, const std::string& title) {
  std::optional<Reference> ref;
  std::ifstream in(dir + "/reference.json", std::ios::binary);
  if (in) {
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    try {
      ref = ReferenceFromJson(text);
    } catch (const std::exception&) {  // a torn reference only loses the contour
    }
  }
  const std::map<std::string, std::string> snapshots = ReadSnapshotIndex(dir);
  ReportBuilder report(ref ? &*ref : nullptr, snapshots);
  CasePages pages(dir);
  std::string last;
  bool first = true;
  ForEachCase(dir + "/cases.jsonl", [&](const CaseResult& r) {
    const std::string& id = r["case"].get_ref<const std::string&>();
    if (!first && id == last) return;  // a repeated id: the first counts
    first = false;
    last = id;
    report.Add(r);
    pages.Add(r);
  });
  const size_t n = pages.Finish();
  common::WriteFileAtomically(dir + "/report.html", report.Html(title, n));
}

}  // namespace vmt::sim::study
