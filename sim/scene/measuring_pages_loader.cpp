#include "sim/scene/measuring_pages_loader.hpp"

#include <cmath>
#include <set>
#include <string>
#include <utility>

#include "sim/model/yaml_reader.hpp"

namespace vmt::sim {

namespace measure = control::measure;

void PresetStylusPages(const MachineModel& m, measure::MeasuringPages& pages) {
  // The model allows at most four styluses (probe_stylus.cpp), as the page does.
  for (size_t i = 0; i < m.probes.size() && i < pages.stylus.size(); ++i) {
    const ProbeStylus& p = m.probes[i];
    measure::TastwerkzeugPage& page = pages.stylus[i];
    page = {};
    page.tool_number = p.t_number;
    page.normally_closed = p.normally_closed;
    page.pin5 = p.pin5;
    for (size_t k = 0; k < p.spheres.size() && k < page.sphere_radius.size(); ++k)
      page.sphere_radius[k] = p.spheres[k].radius_m * 1000;
  }
}

namespace {

double Finite(const YamlNode& n) {
  const double v = n.Double();
  if (!std::isfinite(v)) n.Fail("must be a finite number");
  return v;
}

/// A list of exactly six numbers: the measuring directions axis 1 +, -, axis 2 +, -, axis 3 +, -.
std::array<double, 6> SixValues(const YamlNode& n, bool non_negative) {
  if (!n.IsSequence() || n.size() != 6)
    n.Fail("expected 6 numbers: axis 1 +, axis 1 -, axis 2 +, axis 2 -, axis 3 +, axis 3 -");
  std::array<double, 6> v{};
  for (size_t i = 0; i < 6; ++i) {
    v[i] = Finite(n[i]);
    if (non_negative && v[i] < 0) n[i].Fail("must be >= 0");
  }
  return v;
}

}  // namespace

void LoadMeasuringPages(const YamlNode& node, const control::axes::ToolTable& tools,
                        measure::MeasuringPages& pages) {
  node.AllowKeys({"stylus", "calibration"});
  if (node.Has("stylus")) {
    const YamlNode list = node["stylus"];
    if (!list.IsSequence() || list.size() < 1 ||
        list.size() > static_cast<size_t>(measure::kStyluses))
      list.Fail("expected a list of 1 to 4 styluses (TASTWERKZEUGPAGE LV1 1..4)");
    pages.stylus = {};
    for (size_t i = 0; i < list.size(); ++i) {
      const YamlNode e = list[i];
      e.AllowKeys({"tool_number", "normally_closed", "pin5", "sphere_radius"});
      measure::TastwerkzeugPage& page = pages.stylus[i];
      page.tool_number = e["tool_number"].Int();
      if (page.tool_number < 1) e["tool_number"].Fail("must be >= 1");
      if (!tools.Find(page.tool_number, 1))
        e["tool_number"].Fail("T" + std::to_string(page.tool_number) +
                              " D1 is not in the tool list (the stylus is handled like a tool)");
      page.normally_closed = e.Bool("normally_closed", false);
      page.pin5 = e.Bool("pin5", false);
      const YamlNode radii = e["sphere_radius"];
      if (!radii.IsSequence() || radii.size() < 1 ||
          radii.size() > static_cast<size_t>(measure::kSpheres))
        radii.Fail("expected a list of 1 to 5 measuring sphere radii, mm");
      for (size_t k = 0; k < radii.size(); ++k) {
        page.sphere_radius[k] = Finite(radii[k]);
        if (!(page.sphere_radius[k] > 0)) radii[k].Fail("must be > 0");
      }
    }
  }
  if (node.Has("calibration")) {
    const YamlNode list = node["calibration"];
    if (!list.IsSequence()) list.Fail("expected a list of {stylus, sphere, ...} entries");
    std::set<std::pair<int, int>> seen;
    for (size_t i = 0; i < list.size(); ++i) {
      const YamlNode e = list[i];
      e.AllowKeys({"stylus", "sphere", "measuring_direction", "measuring_feed"});
      const int stylus = e["stylus"].Int(), sphere = e["sphere"].Int();
      if (stylus < 1 || stylus > measure::kStyluses) e["stylus"].Fail("must be in 1..4");
      if (sphere < 1 || sphere > measure::kSpheres) e["sphere"].Fail("must be in 1..5");
      if (!seen.insert({stylus, sphere}).second)
        e.Fail("stylus " + std::to_string(stylus) + " sphere " + std::to_string(sphere) +
               " listed twice");
      measure::EichwertePage& page = pages.calibration[stylus - 1][sphere - 1];
      if (e.Has("measuring_direction"))
        page.measuring_direction = SixValues(e["measuring_direction"], false);
      if (e.Has("measuring_feed")) page.measuring_feed = SixValues(e["measuring_feed"], true);
    }
  }
}

}  // namespace vmt::sim
