#include "sim/scene/workpiece_loader.hpp"

#include <algorithm>

#include "sim/model/yaml_reader.hpp"
#include "sim/scene/scene_steps.hpp"

namespace vmt::sim {
namespace {

bool ShareMaterial(const RevolvedSection& a, const RevolvedSection& b) {
  return a.z0_m < b.z1_m && b.z0_m < a.z1_m && a.r_inner_m < b.r_outer_m &&
         b.r_inner_m < a.r_outer_m;
}

}  // namespace

Workpiece LoadWorkpiece(const YamlNode& w, const MachineModel& m) {
  w.AllowKeys({"diameter", "length", "sections", "oversize", "z", "colour", "link"});
  Workpiece p;
  p.present = true;
  p.part.link = w.String("link", "spindle");
  if (m.LinkIndex(p.part.link) < 0) w["link"].Fail("no link '" + p.part.link + "'");
  const double z_m = w["z"].Double() / kMmPerM;
  if (w.Has("sections") == (w.Has("diameter") || w.Has("length")))
    w.Fail("needs either diameter and length (a stock cylinder) or sections");
  if (w.Has("diameter")) {
    const double d = w["diameter"].Double(), length = w["length"].Double();
    if (!(d > 0)) w["diameter"].Fail("must be > 0");
    if (!(length > 0)) w["length"].Fail("must be > 0");
    p.part.sections.push_back({z_m, z_m + length / kMmPerM, 0, d / 2 / kMmPerM});
  } else {
    const YamlNode list = w["sections"];
    if (!list.IsSequence() || list.size() == 0) list.Fail("must be a non-empty list");
    for (size_t i = 0; i < list.size(); ++i) {
      const YamlNode n = list[i];
      n.AllowKeys({"from", "to", "diameter", "bore"});
      const double from = n["from"].Double(), to = n["to"].Double();
      const double d = n["diameter"].Double(), bore = n.Double("bore", 0);
      if (!(to > from)) n["to"].Fail("must be beyond from (" + Fmt(from) + " mm)");
      if (!(d > 0)) n["diameter"].Fail("must be > 0");
      if (!(bore >= 0 && bore < d)) n["bore"].Fail("must be in [0, diameter)");
      const RevolvedSection s{z_m + from / kMmPerM, z_m + to / kMmPerM, bore / 2 / kMmPerM,
                              d / 2 / kMmPerM};
      for (size_t j = 0; j < p.part.sections.size(); ++j)
        if (ShareMaterial(s, p.part.sections[j]))
          n.Fail("shares material with section " + std::to_string(j));
      p.part.sections.push_back(s);
    }
  }
  // Oversize is on the diameters, the dimensions a lathe part is measured by: every outer
  // radius grows by it and every bore shrinks; the faces stay where the sections put them.
  const double oversize_m = w.Double("oversize", 0) / kMmPerM;
  for (RevolvedSection& s : p.part.sections) {
    s.r_outer_m += oversize_m;
    if (s.r_inner_m > 0) s.r_inner_m = std::max(0.0, s.r_inner_m - oversize_m);
    if (!(s.r_outer_m > s.r_inner_m)) w["oversize"].Fail("leaves a section without material");
  }
  for (size_t i = 0; i < p.part.sections.size() && oversize_m > 0; ++i)
    for (size_t j = 0; j < i; ++j)
      if (ShareMaterial(p.part.sections[i], p.part.sections[j]))
        w["oversize"].Fail("closes the gap between sections " + std::to_string(j) + " and " +
                           std::to_string(i));
  if (w.Has("colour")) {
    const auto c = w["colour"].Doubles(4);
    p.colour = {float(c[0]), float(c[1]), float(c[2]), float(c[3])};
  }
  return p;
}

}  // namespace vmt::sim
