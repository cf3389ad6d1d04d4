#include "sim/study/study_conclusions.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>
#include <memory>
#include <set>

namespace vmt::sim::study {
namespace {

std::string Str(const CaseResult& r, const char* key) {
  return r.contains(key) && r[key].is_string() ? r[key].get<std::string>() : "";
}

double Num(const CaseResult& r, const char* key, double otherwise) {
  return r.contains(key) && r[key].is_number() ? r[key].get<double>() : otherwise;
}

std::string Mm(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

int Rank(const std::string& cls) {
  if (cls == "crash") return 0;
  if (cls == "graze") return 1;
  if (cls == "error") return 2;
  if (cls == "clear") return 3;
  return 4;  // retract refused: not the subroutine's
}

std::string Plural(size_t n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// The program's blocks in the order they ran (the reference run), else by label.
struct BlockOrder {
  std::map<std::string, size_t> index;
  std::map<std::string, int> line;
  explicit BlockOrder(const Reference* ref) {
    if (!ref) return;
    for (const BlockSpan& b : ref->blocks)
      if (index.emplace(b.label, index.size()).second) line[b.label] = b.line;
  }
  bool Before(const std::string& a, const std::string& b) const {
    const auto ia = index.find(a), ib = index.find(b);
    if (ia != index.end() && ib != index.end()) return ia->second < ib->second;
    if ((ia != index.end()) != (ib != index.end())) return ia != index.end();
    return a < b;
  }
};

// "N0030-N0070 (lines 7-11)": the blocks of `failing`, runs of blocks that follow each other
// among the interrupted ones (`all`) joined into ranges.
std::string Region(const std::set<std::string>& failing, const std::set<std::string>& all,
                   const BlockOrder& order) {
  std::vector<std::string> blocks(all.begin(), all.end());
  std::sort(blocks.begin(), blocks.end(),
            [&](const std::string& a, const std::string& b) { return order.Before(a, b); });
  std::vector<std::pair<std::string, std::string>> runs;
  bool open = false;
  for (const std::string& b : blocks) {
    if (!failing.count(b)) {
      open = false;
      continue;
    }
    if (open)
      runs.back().second = b;
    else
      runs.push_back({b, b});
    open = true;
  }
  auto line_of = [&](const std::string& b) {
    const auto it = order.line.find(b);
    return it == order.line.end() ? std::string() : std::to_string(it->second);
  };
  std::string s;
  for (size_t i = 0; i < runs.size(); ++i) {
    const auto& [first, last] = runs[i];
    if (i > 0) s += i + 1 == runs.size() ? " and " : ", ";
    const std::string l0 = line_of(first), l1 = line_of(last);
    if (first == last) {
      s += first + (l0.empty() ? "" : " (line " + l0 + ")");
    } else {
      s += first + "\u2013" + last;
      if (!l0.empty() && !l1.empty()) s += " (lines " + l0 + "\u2013" + l1 + ")";
    }
  }
  return s;
}

std::string Quoted(const std::set<std::string>& names) {
  std::string s;
  size_t i = 0;
  for (const std::string& n : names) {
    if (i > 0) s += i + 1 == names.size() ? " or " : ", ";
    s += "\u201c" + n + "\u201d";
    ++i;
  }
  return s;
}

// A part's family: its name without the trailing number (spindle_jaw2: spindle_jaw), so that
// the three jaws of a chuck are one cause.
std::string Family(const std::string& part) {
  size_t end = part.size();
  while (end > 0 && std::isdigit(static_cast<unsigned char>(part[end - 1]))) --end;
  return end > 0 && end < part.size() ? part.substr(0, end) : part;
}

// "spindle_jaw 1, 2 or 3", or the one part's name.
std::string Members(const std::set<std::string>& parts) {
  if (parts.size() == 1) return *parts.begin();
  const std::string family = Family(*parts.begin());
  std::string s = family + " ";
  size_t i = 0;
  for (const std::string& p : parts) {
    if (i > 0) s += i + 1 == parts.size() ? " or " : ", ";
    s += p.substr(family.size());
    ++i;
  }
  return s;
}

// The failures of one subroutine in one mode that have the same cause: two families of parts
// meeting (the moving one first), or an error.
struct Cause {
  std::string a, b;                        ///< the families; empty: an error
  std::set<std::string> parts_a, parts_b;  ///< the parts of each that met
  size_t cases = 0, crash = 0, graze = 0;
  double deepest = 0;
  std::string first_error;
  std::set<std::string> blocks, retracts;
};

}  // namespace

const nlohmann::ordered_json& Field(const CaseResult& r, const char* key) {
  static const nlohmann::ordered_json null;
  const auto it = r.find(key);
  return it == r.end() ? null : *it;
}

std::string ClassOf(const CaseResult& r) {
  const std::string v = Str(r, "verdict");
  if (v == "clear" || v == "retract_refused") return v;
  // A study made before the verdict existed called a refused retract an error.
  if (v == "error" && Field(r, "retract_contact").is_array()) return "retract_refused";
  if (v == "collision") return Str(r, "contact_class") == "graze" ? "graze" : "crash";
  return "error";
}

void ClassCount::Add(const CaseResult& r) {
  const std::string c = ClassOf(r);
  ++cases;
  clear += c == "clear", crash += c == "crash", graze += c == "graze", error += c == "error";
  retract_refused += c == "retract_refused";
}

bool MoreSevere(const CaseResult& a, const CaseResult& b) {
  const std::string ca = ClassOf(a), cb = ClassOf(b);
  if (Rank(ca) != Rank(cb)) return Rank(ca) < Rank(cb);
  if (ca == "crash" || ca == "graze") {
    const double pa = Num(a, "past_contact_mm", 0), pb = Num(b, "past_contact_mm", 0);
    if (pa != pb) return pa > pb;
  } else if (ca == "clear") {
    const double ka = Num(a, "min_clearance_mm", 1e30), kb = Num(b, "min_clearance_mm", 1e30);
    if (ka != kb) return ka < kb;
  }
  return Str(a, "case") < Str(b, "case");
}

std::string ContactAxes(const CaseResult& r) {
  const auto& at = Field(r, "contact_position");
  if (!at.is_object()) return "";
  // The record names the axes that moved; the path's last corner is X and Z at the contact.
  std::map<std::string, double> axes;
  const auto& path = Field(r, "path");
  if (path.is_array() && !path.empty() && path.back().is_array() && path.back().size() == 2 &&
      path.back()[0].is_number() && path.back()[1].is_number())
    axes["X"] = path.back()[0].get<double>(), axes["Z"] = path.back()[1].get<double>();
  for (const auto& [axis, v] : at.items())
    if (v.is_number()) axes[axis] = v.get<double>();
  std::string s;
  for (const auto& [axis, v] : axes) s += (s.empty() ? "" : " ") + axis + Mm(v);
  return s;
}

namespace {

// What the conclusions keep of one subroutine in one mode: counts and sets of names, no case.
struct SubTally {
  ClassCount n;
  std::set<std::string> blocks, retracts;
  std::vector<Cause> causes;
};

struct ModeTally {
  std::map<std::string, SubTally> subs;
  std::set<std::string> refused_retracts;
  size_t refused = 0;
};

}  // namespace

struct ConclusionTally::State {
  std::set<std::string> standing{"workpiece"};
  std::vector<std::string> modes;  ///< in order of first appearance
  std::map<std::string, ModeTally> by;
};

ConclusionTally::ConclusionTally(const Reference* reference)
    : reference_(reference), state_(std::make_unique<State>()) {
  if (reference)
    for (const ChuckOutline& c : reference->chuck) state_->standing.insert(c.name);
}

ConclusionTally::~ConclusionTally() = default;

void ConclusionTally::Add(const CaseResult& r) {
  const std::string mode = Str(r, "mode");
  if (std::find(state_->modes.begin(), state_->modes.end(), mode) == state_->modes.end())
    state_->modes.push_back(mode);
  ModeTally& mt = state_->by[mode];
  SubTally& st = mt.subs[Str(r, "subroutine")];
  const std::set<std::string>& standing = state_->standing;
  std::vector<Cause>& causes = st.causes;
  st.n.Add(r);
  const std::string cls = ClassOf(r);
  if (cls == "retract_refused") {
    ++mt.refused;
    mt.refused_retracts.insert(Str(r, "retract"));
    return;
  }
  st.blocks.insert(Str(r, "block"));
  st.retracts.insert(Str(r, "retract"));
  if (cls == "clear") return;
  std::string a, b;
  const auto& parts = Field(r, "parts");
  if (cls != "error" && parts.is_array() && parts.size() == 2 && parts[0].is_string() &&
      parts[1].is_string()) {
    a = parts[0].get<std::string>(), b = parts[1].get<std::string>();
    // What stands (the chuck's parts, the workpiece) is hit by what moves.
    if (standing.count(a) && !standing.count(b)) std::swap(a, b);
  }
  // Else the order the cause was first named in.
  if (std::none_of(causes.begin(), causes.end(),
                   [&](const Cause& c) { return c.a == Family(a) && c.b == Family(b); }))
    for (const Cause& c : causes)
      if (c.a == Family(b) && c.b == Family(a)) std::swap(a, b);
  auto it = std::find_if(causes.begin(), causes.end(),
                         [&](const Cause& c) { return c.a == Family(a) && c.b == Family(b); });
  if (it == causes.end()) {
    causes.emplace_back();
    it = causes.end() - 1;
    it->a = Family(a), it->b = Family(b);
  }
  if (!a.empty()) it->parts_a.insert(a), it->parts_b.insert(b);
  ++it->cases;
  it->crash += cls == "crash", it->graze += cls == "graze";
  it->deepest = std::max(it->deepest, Num(r, "past_contact_mm", 0));
  if (it->first_error.empty()) it->first_error = Str(r, "error");
  it->blocks.insert(Str(r, "block"));
  it->retracts.insert(Str(r, "retract"));
}

std::vector<ModeConclusion> Conclusions(const std::vector<CaseResult>& cases,
                                        const Reference* reference) {
  ConclusionTally tally(reference);
  for (const CaseResult& r : cases) tally.Add(r);
  return tally.Conclusions();
}

std::vector<ModeConclusion> ConclusionTally::Conclusions() const {
  const BlockOrder order(reference_);
  std::vector<ModeConclusion> out;
  for (const std::string& mode : state_->modes) {
    ModeConclusion m;
    m.mode = mode;
    std::vector<std::string> all_clear;
    ModeTally mt = state_->by.at(mode);
    const std::set<std::string>& refused_retracts = mt.refused_retracts;
    const size_t refused = mt.refused;
    for (auto& [sub, st] : mt.subs) {
      const ClassCount& n = st.n;
      const std::set<std::string>& blocks = st.blocks;
      const std::set<std::string>& retracts = st.retracts;
      std::vector<Cause>& causes = st.causes;
      const size_t judged = n.judged();
      const size_t failed = judged - n.clear;
      if (judged == 0) {
        m.sentences.push_back(sub + ": no case to judge: PathGuard refused the operator's " +
                              "retract in all " + Plural(n.cases, "case", "cases") + ".");
        continue;
      }
      if (failed == 0) {
        all_clear.push_back(sub);
        m.sentences.push_back(
            sub + (judged == 1 ? " is clear in its one case."
                               : " is clear in all " + std::to_string(judged) + " cases."));
        continue;
      }
      std::stable_sort(causes.begin(), causes.end(),
                       [](const Cause& x, const Cause& y) { return x.cases > y.cases; });
      std::string s = sub + " fails in " + std::to_string(failed) + " of " +
                      Plural(judged, "case", "cases") + ": ";
      for (size_t i = 0; i < causes.size(); ++i) {
        const Cause& c = causes[i];
        if (i > 0) s += "; ";
        if (c.a.empty()) {
          s += "an NC error or timeout in " + Plural(c.cases, "case", "cases") + " (" +
               (c.first_error.empty() ? "no message" : c.first_error) + ")";
        } else {
          s += Members(c.parts_a) + " hits " + Members(c.parts_b) + " in " +
               Plural(c.cases, "case", "cases");
          if (c.crash && c.graze)
            s += " (" + Plural(c.crash, "crash", "crashes") + ", up to " + Mm(c.deepest) +
                 " mm past the first contact; " + Plural(c.graze, "graze", "grazes") + ")";
          else if (c.crash)
            s += " (" + std::string(c.crash == 1 ? "a crash, " : "crashes, up to ") +
                 Mm(c.deepest) + " mm past the first contact)";
          else
            s += " (" + std::string(c.graze == 1 ? "a graze" : "all grazes") + ", within " +
                 Mm(kGrazeMm) + " mm of the move's end)";
        }
        s += (c.cases == 1 ? ", interrupted in " : ", all interrupted in ") +
             Region(c.blocks, blocks, order);
        if (c.retracts.size() < retracts.size()) s += ", after the retract " + Quoted(c.retracts);
      }
      s += ". Clear in " + std::to_string(n.clear) + ".";
      m.sentences.push_back(s);
    }
    if (all_clear.empty()) {
      m.headline = mode + ": no subroutine or manual order is clear in all cases.";
    } else {
      m.headline = mode + ": clear in all cases: ";
      for (size_t i = 0; i < all_clear.size(); ++i) m.headline += (i ? ", " : "") + all_clear[i];
      m.headline += ".";
    }
    if (refused)
      m.sentences.push_back("Not counted above: in " + Plural(refused, "case", "cases") +
                            " PathGuard refused the operator's retract (" +
                            Quoted(refused_retracts) +
                            ") before any return: the operator's jog, not the subroutine's move.");
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace vmt::sim::study
