#include "sim/scene/workpiece_loader.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"

namespace vmt::sim {
namespace {

// Physically sensible sizes of a lathe's part (mm): beyond them a number is a typo, and a
// diameter of 1e20 makes the mesh and collision code iterate for minutes.
constexpr double kMaxDiameterMm = 2000;
constexpr double kMaxLengthMm = 10000;
constexpr double kMaxPositionMm = 10000;  // |z|, |from|, |to|
constexpr double kMaxOversizeMm = 100;

// A number within [lo, hi] (or (0, hi] with `positive`), refused with the range otherwise.
double Bounded(const YamlNode& n, double lo, double hi, bool positive = false) {
  const double v = n.Double();
  if (positive ? !(v > 0 && v <= hi) : !(v >= lo && v <= hi))
    n.Fail("must be in " + std::string(positive ? "(0, " : "[" + Fmt(lo) + ", ") + Fmt(hi) +
           "] mm, got " + Fmt(v));
  return v;
}

bool ShareMaterial(const RevolvedSection& a, const RevolvedSection& b) {
  return a.z0_m < b.z1_m && b.z0_m < a.z1_m && a.r_inner_m < b.r_outer_m &&
         b.r_inner_m < a.r_outer_m;
}

// The machined sections' diameters carry the oversize, the others are what the part was
// clamped or calibrated on and keep their true size: a measuring program calibrates on a master
// of known size, and an oversize that grew the master with the part would hide itself. It is a
// diameter allowance, as a lathe part is dimensioned and measured (G16): an outer diameter
// grows by it, a bore shrinks by it. The faces stay where the sections put them.
void ApplyOversize(const YamlNode& w, const std::vector<bool>& machined,
                   std::vector<RevolvedSection>& sections) {
  const YamlNode o = w["oversize"];
  if (machined.empty()) o.Fail("needs sections, some of them machined: true");
  if (std::find(machined.begin(), machined.end(), true) == machined.end())
    o.Fail("no section is machined: true");
  const double radius_m = Bounded(o, -kMaxOversizeMm, kMaxOversizeMm) / 2 / kMmPerM;
  for (size_t i = 0; i < sections.size(); ++i) {
    if (!machined[i]) continue;
    RevolvedSection& s = sections[i];
    s.r_outer_m += radius_m;
    if (s.r_inner_m > 0) {
      s.r_inner_m -= radius_m;
      if (!(s.r_inner_m > 0)) o.Fail("closes the bore of section " + std::to_string(i));
    }
    if (!(s.r_outer_m > s.r_inner_m))
      o.Fail("leaves section " + std::to_string(i) + " without material");
  }
  for (size_t i = 0; i < sections.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if ((machined[i] || machined[j]) && ShareMaterial(sections[i], sections[j]))
        o.Fail("closes the gap between sections " + std::to_string(j) + " and " +
               std::to_string(i));
}

}  // namespace

Workpiece LoadWorkpiece(const YamlNode& w, const MachineModel& m) {
  w.AllowKeys({"diameter", "length", "sections", "oversize", "z", "colour", "link"});
  Workpiece p;
  p.present = true;
  std::vector<bool> machined;  // per section: the oversize applies to it
  p.part.link = w.String("link", "spindle");
  if (m.LinkIndex(p.part.link) < 0) w["link"].Fail("no link '" + p.part.link + "'");
  const double z_m = Bounded(w["z"], -kMaxPositionMm, kMaxPositionMm) / kMmPerM;
  if (w.Has("sections") == (w.Has("diameter") || w.Has("length")))
    w.Fail("needs either diameter and length (a stock cylinder) or sections");
  if (w.Has("diameter")) {
    const double d = Bounded(w["diameter"], 0, kMaxDiameterMm, true);
    const double length = Bounded(w["length"], 0, kMaxLengthMm, true);
    p.part.sections.push_back({z_m, z_m + length / kMmPerM, 0, d / 2 / kMmPerM});
  } else {
    const YamlNode list = w["sections"];
    if (!list.IsSequence() || list.size() == 0) list.Fail("must be a non-empty list");
    for (size_t i = 0; i < list.size(); ++i) {
      const YamlNode n = list[i];
      n.AllowKeys({"from", "to", "diameter", "bore", "machined"});
      const double from = Bounded(n["from"], -kMaxPositionMm, kMaxPositionMm);
      const double to = Bounded(n["to"], -kMaxPositionMm, kMaxPositionMm);
      const double d = Bounded(n["diameter"], 0, kMaxDiameterMm, true);
      const double bore = n.Double("bore", 0);
      if (!(to > from)) n["to"].Fail("must be beyond from (" + Fmt(from) + " mm)");
      if (!(bore >= 0 && bore < d)) n["bore"].Fail("must be in [0, diameter)");
      const RevolvedSection s{z_m + from / kMmPerM, z_m + to / kMmPerM, bore / 2 / kMmPerM,
                              d / 2 / kMmPerM};
      for (size_t j = 0; j < p.part.sections.size(); ++j)
        if (ShareMaterial(s, p.part.sections[j]))
          n.Fail("shares material with section " + std::to_string(j));
      p.part.sections.push_back(s);
      machined.push_back(n.Bool("machined", false));
    }
  }
  if (w.Has("oversize")) ApplyOversize(w, machined, p.part.sections);
  if (w.Has("colour")) {
    const auto c = w["colour"].Doubles(4);
    p.colour = {float(c[0]), float(c[1]), float(c[2]), float(c[3])};
  }
  return p;
}

}  // namespace vmt::sim
