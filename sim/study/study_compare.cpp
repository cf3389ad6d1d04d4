#include "sim/study/study_compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "common/output_file.hpp"
#include "sim/study/case_files.hpp"
#include "sim/study/study_conclusions.hpp"
#include "sim/study/study_plane.hpp"

namespace vmt::sim::study {
namespace {

std::string Str(const CaseResult& r, const char* key) {
  const auto& v = Field(r, key);
  return v.is_string() ? v.get<std::string>() : "";
}

std::string Mm(double v, const char* fmt = "%.3f") {
  char buf[32];
  std::snprintf(buf, sizeof buf, fmt, v + 0.0);
  return buf;
}

std::string Label(const std::string& cls) {
  return cls.empty() ? "(none)" : cls == "retract_refused" ? "retract refused" : cls;
}

int Rank(const std::string& cls) {
  static const char* const order[] = {"crash", "graze", "error", "clear", "retract_refused"};
  for (int i = 0; i < 5; ++i)
    if (cls == order[i]) return i;
  return 5;
}

std::string Counts(const ClassCount& n) {
  return std::to_string(n.cases) + " cases: " + std::to_string(n.clear) + " clear, " +
         std::to_string(n.crash) + " crash, " + std::to_string(n.graze) + " graze, " +
         std::to_string(n.error) + " error, " + std::to_string(n.retract_refused) +
         " retract refused";
}

std::string What(const CaseChange& c, double threshold) {
  if (!c.a) return "only in B: " + Label(c.class_b);
  if (!c.b) return "only in A: " + Label(c.class_a);
  std::string s;
  if (c.class_changed) s = Label(c.class_a) + " -> " + Label(c.class_b);
  if (std::abs(c.clearance_delta) > threshold)
    s += (s.empty() ? "" : ", ") + std::string("clearance ") +
         Mm(Field(*c.a, "min_clearance_mm").get<double>()) + " -> " +
         Mm(Field(*c.b, "min_clearance_mm").get<double>()) + " mm";
  if (std::abs(c.past_contact_delta) > threshold)
    s += (s.empty() ? "" : ", ") + std::string("past contact ") +
         Mm(Field(*c.a, "past_contact_mm").get<double>()) + " -> " +
         Mm(Field(*c.b, "past_contact_mm").get<double>()) + " mm";
  const CaseResult& now = c.b ? *c.b : *c.a;
  if (Field(now, "parts").is_array()) s += " (" + Field(now, "parts").dump() + ")";
  return s;
}

// What a comparison reads of a case (identity, class, distances, first contact; of the path
// only its last corner, which ContactAxes takes): a few hundred bytes where a whole case with its
// path holds kilobytes.
CaseResult ComparedFields(CaseResult&& r) {
  CaseResult kept = CaseResult::object();
  for (const char* key :
       {"case", "subroutine", "interrupt", "retract", "mode", "verdict", "retract_contact",
        "contact_class", "min_clearance_mm", "past_contact_mm", "parts", "contact_position"}) {
    const auto it = r.find(key);
    if (it != r.end()) kept[key] = std::move(*it);
  }
  const auto path = r.find("path");
  if (path != r.end() && path->is_array() && !path->empty())
    kept["path"] = CaseResult::array({std::move(path->back())});
  return kept;
}

// Pairs of cases given in identity order become a comparison; the changes, a copy of what was
// read of each changed case, are sorted at the end.
class Comparer {
 public:
  Comparer(double threshold_mm, const std::string& name_a, const std::string& name_b) {
    out_.name_a = name_a, out_.name_b = name_b;
    out_.threshold_mm = threshold_mm;
  }

  void Count(const CaseResult& r, bool in_b) {
    auto& t = out_.tallies[{Str(r, "subroutine"), Str(r, "mode")}];
    (in_b ? t.second : t.first).Add(r);
    ++(in_b ? out_.cases_b : out_.cases_a);
  }

  void Pair(const std::string& identity, const CaseResult* a, const CaseResult* b) {
    CaseChange c;
    c.identity = identity;
    if (a) c.class_a = ClassOf(*a);
    if (b) c.class_b = ClassOf(*b);
    if (!a || !b) {
      ++(a ? out_.only_a : out_.only_b);
      Keep(std::move(c), a, b);
      return;
    }
    ++out_.matched;
    c.class_changed = c.class_a != c.class_b;
    const auto delta = [&](const char* key) {
      const auto &x = Field(*a, key), &y = Field(*b, key);
      return x.is_number() && y.is_number() ? y.get<double>() - x.get<double>() : 0.0;
    };
    c.clearance_delta = delta("min_clearance_mm");
    c.past_contact_delta = delta("past_contact_mm");
    c.beyond = std::abs(c.clearance_delta) > out_.threshold_mm ||
               std::abs(c.past_contact_delta) > out_.threshold_mm;
    out_.class_changes += c.class_changed;
    out_.beyond += c.beyond;
    if (c.class_changed || c.beyond) Keep(std::move(c), a, b);
  }

  Comparison Finish() && {
    const auto group = [](const CaseChange& c) {
      return c.a && c.b ? (c.class_changed ? 0 : 1) : c.a ? 2 : 3;
    };
    std::stable_sort(
        out_.changes.begin(), out_.changes.end(), [&](const CaseChange& x, const CaseChange& y) {
          if (group(x) != group(y)) return group(x) < group(y);
          if (group(x) == 0 && Rank(x.class_b) != Rank(y.class_b))
            return Rank(x.class_b) < Rank(y.class_b);
          if (group(x) == 1) {
            const double dx = std::max(std::abs(x.clearance_delta), std::abs(x.past_contact_delta));
            const double dy = std::max(std::abs(y.clearance_delta), std::abs(y.past_contact_delta));
            if (dx != dy) return dx > dy;
          }
          return x.identity < y.identity;
        });
    return std::move(out_);
  }

 private:
  void Keep(CaseChange&& c, const CaseResult* a, const CaseResult* b) {
    if (a) c.a = *a;
    if (b) c.b = *b;
    out_.changes.push_back(std::move(c));
  }

  Comparison out_;
};

// A file that cannot be walked in order (not in case id order, two ids of one identity, a line
// that is no case): it is read whole instead, and that reader names any bad line.
struct NotInOrder {};

// One study's cases.jsonl case by case in identity order, each id once (its first line), as
// ComparedFields keeps it. Throws NotInOrder as soon as the file is not so.
class OrderedCases {
 public:
  explicit OrderedCases(const std::string& path) : in_(path, std::ios::binary) { Advance(); }
  const CaseResult* current() const { return has_ ? &case_ : nullptr; }
  const std::string& identity() const { return identity_; }

  void Advance() {
    const bool had = has_;
    has_ = false;
    for (std::string line; std::getline(in_, line);) {
      CaseResult r;
      if (in_.eof() || !LineError(line, r).empty()) throw NotInOrder{};
      std::string id = r["case"].get<std::string>();
      if (had && id == id_) continue;
      if (had && id < id_) throw NotInOrder{};
      r = ComparedFields(std::move(r));
      std::string identity = CaseIdentity(r);
      if (had && !(identity_ < identity)) throw NotInOrder{};
      id_ = std::move(id), identity_ = std::move(identity), case_ = std::move(r);
      has_ = true;
      return;
    }
  }

 private:
  std::ifstream in_;
  CaseResult case_;
  std::string id_, identity_;
  bool has_ = false;
};

Comparison CompareInOrder(const std::string& path_a, const std::string& path_b, double threshold_mm,
                          const std::string& name_a, const std::string& name_b) {
  Comparer compare(threshold_mm, name_a, name_b);
  OrderedCases a(path_a), b(path_b);
  while (a.current() || b.current()) {
    const bool take_a = a.current() && (!b.current() || !(b.identity() < a.identity()));
    const bool take_b = b.current() && (!a.current() || !(a.identity() < b.identity()));
    if (take_a) compare.Count(*a.current(), false);
    if (take_b) compare.Count(*b.current(), true);
    compare.Pair(take_a ? a.identity() : b.identity(), take_a ? a.current() : nullptr,
                 take_b ? b.current() : nullptr);
    if (take_a) a.Advance();
    if (take_b) b.Advance();
  }
  return std::move(compare).Finish();
}

}  // namespace

std::string CaseIdentity(const CaseResult& r) {
  const std::string sub = Str(r, "subroutine"), in = Str(r, "interrupt"),
                    retract = Str(r, "retract"), mode = Str(r, "mode");
  if (sub.empty() || in.empty() || retract.empty() || mode.empty()) return Str(r, "case");
  return sub + "/" + in + "/" + retract + "/" + mode;
}

Comparison CompareCases(const std::vector<CaseResult>& a, const std::vector<CaseResult>& b,
                        double threshold_mm, const std::string& name_a, const std::string& name_b) {
  Comparer compare(threshold_mm, name_a, name_b);
  for (const CaseResult& r : a) compare.Count(r, false);
  for (const CaseResult& r : b) compare.Count(r, true);
  std::map<std::string, std::pair<const CaseResult*, const CaseResult*>> by;
  for (const CaseResult& r : a) by[CaseIdentity(r)].first = &r;  // the last of equals
  for (const CaseResult& r : b) by[CaseIdentity(r)].second = &r;
  for (const auto& [id, pair] : by) compare.Pair(id, pair.first, pair.second);
  return std::move(compare).Finish();
}

std::string CompareText(const Comparison& c) {
  std::ostringstream o;
  o << "A: " << c.name_a << " (" << c.cases_a << " cases)\nB: " << c.name_b << " (" << c.cases_b
    << " cases)\n"
    << c.matched << " cases in both, " << c.only_a << " only in A, " << c.only_b << " only in B\n"
    << c.class_changes << " changed class, " << c.beyond
    << " moved clearance or depth past contact by more than " << Mm(c.threshold_mm) << " mm\n";
  std::map<std::string, size_t> kinds;
  for (const CaseChange& k : c.changes)
    if (k.class_changed) ++kinds[Label(k.class_a) + " -> " + Label(k.class_b)];
  for (const auto& [kind, n] : kinds) o << "  " << kind << ": " << n << "\n";
  o << "per subroutine and mode:\n";
  for (const auto& [key, t] : c.tallies) {
    o << "  " << key.first << ", " << key.second << "\n    A " << Counts(t.first) << "\n    B "
      << Counts(t.second) << "\n";
  }
  if (c.changes.size() > 20)
    o << "changes (the first 20 of " << c.changes.size() << "; all on the page):\n";
  else if (!c.changes.empty())
    o << "changes:\n";
  for (size_t i = 0; i < c.changes.size() && i < 20; ++i)
    o << "  " << c.changes[i].identity << ": " << What(c.changes[i], c.threshold_mm) << "\n";
  return o.str();
}

std::string CompareHtml(const Comparison& c) {
  std::ostringstream o;
  const std::string title = "Study comparison: " + c.name_a + " vs " + c.name_b;
  o << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << Esc(title)
    << "</title>\n<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}"
       "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}td.l,th.l{text-align:left}"
       "</style></head><body>\n<h1>"
    << Esc(title) << "</h1>\n<p>A: " << Esc(c.name_a) << " (" << c.cases_a
    << " cases); B: " << Esc(c.name_b) << " (" << c.cases_b
    << " cases). Cases match by subroutine, "
       "interruption point, retract and mode: "
    << c.matched << " in both, " << c.only_a << " only in A, " << c.only_b << " only in B. "
    << c.class_changes << " changed class; " << c.beyond
    << " moved their clearance or depth past the first contact by more than " << Mm(c.threshold_mm)
    << " mm. Machine coordinates, mm.</p>\n";
  o << "<h2>Classes per subroutine and mode</h2>\n<table><tr><th class=\"l\">subroutine</th>"
       "<th class=\"l\">mode</th><th class=\"l\">study</th><th>cases</th><th>clear</th>"
       "<th>crash</th><th>graze</th><th>errors</th><th>retract refused</th></tr>\n";
  for (const auto& [key, t] : c.tallies)
    for (int side = 0; side < 2; ++side) {
      const ClassCount& n = side ? t.second : t.first;
      o << "<tr><td class=\"l\">" << Esc(key.first) << "</td><td class=\"l\">" << Esc(key.second)
        << "</td><td class=\"l\">" << (side ? "B" : "A") << "</td><td>" << n.cases
        << "</td><td style=\"color:" << ClassColour("clear") << "\">" << n.clear
        << "</td><td style=\"color:" << ClassColour("crash") << "\">" << n.crash
        << "</td><td style=\"color:" << ClassColour("graze") << "\">" << n.graze
        << "</td><td style=\"color:" << ClassColour("error") << "\">" << n.error
        << "</td><td style=\"color:" << ClassColour("retract_refused") << "\">" << n.retract_refused
        << "</td></tr>\n";
    }
  o << "</table>\n<h2>Changed cases</h2>\n";
  if (c.changes.empty())
    o << "<p>None: every case has the same class and clearance.</p>\n";
  else
    o << "<table><tr><th class=\"l\">case</th><th class=\"l\">A</th><th class=\"l\">B</th>"
         "<th>clearance A, mm</th><th>clearance B, mm</th><th>past contact A, mm</th>"
         "<th>past contact B, mm</th><th class=\"l\">first contact A</th>"
         "<th class=\"l\">first contact B</th></tr>\n";
  const auto ptr = [](const std::optional<CaseResult>& r) { return r ? &*r : nullptr; };
  const auto num = [](const CaseResult* r, const char* key) {
    if (!r || !Field(*r, key).is_number()) return std::string();
    return Mm(Field(*r, key).get<double>());
  };
  const auto parts = [](const CaseResult* r) {
    if (!r || !Field(*r, "parts").is_array()) return std::string();
    return Field(*r, "parts").dump() + " at " + ContactAxes(*r);
  };
  for (const CaseChange& k : c.changes) {
    o << "<tr><td class=\"l\">" << Esc(k.identity)
      << "</td><td class=\"l\" style=\"color:" << ClassColour(k.class_a) << "\">"
      << Esc(Label(k.class_a)) << "</td><td class=\"l\" style=\"color:" << ClassColour(k.class_b)
      << "\">" << (k.class_changed ? "<b>" : "") << Esc(Label(k.class_b))
      << (k.class_changed ? "</b>" : "") << "</td><td>" << num(ptr(k.a), "min_clearance_mm")
      << "</td><td>" << num(ptr(k.b), "min_clearance_mm") << "</td><td>"
      << num(ptr(k.a), "past_contact_mm") << "</td><td>" << num(ptr(k.b), "past_contact_mm")
      << "</td><td class=\"l\">" << Esc(parts(ptr(k.a))) << "</td><td class=\"l\">"
      << Esc(parts(ptr(k.b))) << "</td></tr>\n";
  }
  if (!c.changes.empty()) o << "</table>\n";
  o << "</body></html>\n";
  return o.str();
}

std::string CompareStudies(const std::string& dir_a, const std::string& dir_b,
                           const std::string& html_path, double threshold_mm) {
  for (const std::string& d : {dir_a, dir_b})
    if (!std::filesystem::exists(d + "/cases.jsonl"))
      throw std::runtime_error(d + ": no cases.jsonl (not a study folder)");
  if (!(threshold_mm >= 0)) throw std::runtime_error("--threshold needs a distance >= 0 mm");
  const std::string path_a = dir_a + "/cases.jsonl", path_b = dir_b + "/cases.jsonl";
  Comparison c;
  try {
    c = CompareInOrder(path_a, path_b, threshold_mm, dir_a, dir_b);
  } catch (const NotInOrder&) {
    const std::vector<CaseResult> a =
        Deduplicated(ReadCases(path_a, TornLine::kError, ComparedFields));
    const std::vector<CaseResult> b =
        Deduplicated(ReadCases(path_b, TornLine::kError, ComparedFields));
    c = CompareCases(a, b, threshold_mm, dir_a, dir_b);
  }
  common::WriteFileAtomically(html_path, CompareHtml(c));
  return CompareText(c);
}

}  // namespace vmt::sim::study
