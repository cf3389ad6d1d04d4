#include "sim/model/probe_stylus.hpp"

#include <cmath>

#include "sim/model/machine_model.hpp"
#include "sim/model/yaml_reader.hpp"

namespace vmt::sim {
namespace {

int InputNamed(const MachineModel& m, const YamlNode& node) {
  const int i = control::IndexOf(m.io, node.String());
  if (i < 0) node.Fail("no I/O point '" + node.String() + "' in io:");
  if (m.io[i].is_output || m.io[i].key) node.Fail("'" + node.String() + "' must be an input");
  return i;
}

ProbeStylus ReadStylus(const MachineModel& m, const YamlNode& p) {
  p.AllowKeys({"T", "link", "contact", "pin", "spheres", "sphere_parts", "pre_travel",
               "over_travel", "input", "ready"});
  ProbeStylus s;
  s.t_number = p["T"].Int();
  if (s.t_number < 1) p["T"].Fail("must be >= 1");
  if (m.nc.present && !m.nc.tools.Find(s.t_number, 1))
    p["T"].Fail("no tool T" + std::to_string(s.t_number) + " D1 in nc: tools:");

  s.link = m.LinkIndex(p["link"].String());
  if (s.link < 0) p["link"].Fail("no link '" + p["link"].String() + "' in " + m.urdf_path);

  const std::string contact = p["contact"].String();
  if (contact != "NO" && contact != "NC") p["contact"].Fail("expected NO or NC");
  s.normally_closed = contact == "NC";
  const std::string pin = p["pin"].String();
  if (pin != "PIN4" && pin != "PIN5") p["pin"].Fail("expected PIN4 or PIN5");
  s.pin5 = pin == "PIN5";

  const YamlNode spheres = p["spheres"];
  // TASTWERKZEUGPAGE: measuring sphere radius 1..5.
  if (!spheres.IsSequence() || spheres.size() < 1 || spheres.size() > 5)
    spheres.Fail("expected a list of 1 to 5 measuring spheres");
  for (size_t i = 0; i < spheres.size(); ++i) {
    const YamlNode b = spheres[i];
    b.AllowKeys({"centre", "radius"});
    const std::vector<double> c = b["centre"].Doubles(3);
    MeasuringSphere sphere;
    // A stylus is centimetres long with a ruby of a few mm: larger numbers are typos, and
    // huge ones stall the collision geometry.
    for (const double v : c)
      if (!(std::abs(v) <= 1000)) b["centre"].Fail("coordinates must be within +-1000 mm");
    sphere.centre_m = Eigen::Vector3d(c[0], c[1], c[2]) / kMmPerM;
    sphere.radius_m = b["radius"].Double() / kMmPerM;
    if (!(sphere.radius_m > 0 && sphere.radius_m <= 0.05))
      b["radius"].Fail("must be in (0, 50] mm");
    s.spheres.push_back(sphere);
  }

  const YamlNode parts = p["sphere_parts"];
  if (!parts.IsSequence() || parts.size() < 1) parts.Fail("expected a list of collision parts");
  for (size_t i = 0; i < parts.size(); ++i) {
    const std::string name = parts[i].String();
    bool found = false;
    for (const Visual& c : m.links[s.link].collisions) found = found || c.name == name;
    if (!found)
      parts[i].Fail("no <collision name=\"" + name + "\"> in link '" + m.links[s.link].name + "'");
    s.sphere_parts.push_back(name);
  }

  s.pre_travel_m = p["pre_travel"].Double() / kMmPerM;
  if (!(s.pre_travel_m > 0 && s.pre_travel_m <= 0.01))
    p["pre_travel"].Fail("must be in (0, 10] mm");
  s.over_travel_m = p["over_travel"].Double() / kMmPerM;
  if (!(s.over_travel_m > s.pre_travel_m && s.over_travel_m <= 0.05))
    p["over_travel"].Fail("must be greater than pre_travel, at most 50 mm");

  s.contact_input = InputNamed(m, p["input"]);
  if (p.Has("ready")) {
    s.ready_input = InputNamed(m, p["ready"]);
    if (s.ready_input == s.contact_input) p["ready"].Fail("is the switch's own input");
  }
  return s;
}

}  // namespace

std::vector<ProbeStylus> ReadProbeStyluses(const MachineModel& m, const YamlNode& list) {
  // TASTWERKZEUGPAGE, LV1 NO_CLASS [1-4]: at most four styluses in a system.
  if (!list.IsSequence() || list.size() > 4) list.Fail("expected a list of up to four styluses");
  std::vector<ProbeStylus> styluses;
  for (size_t i = 0; i < list.size(); ++i) {
    ProbeStylus s = ReadStylus(m, list[i]);
    for (const ProbeStylus& other : styluses) {
      if (other.t_number == s.t_number) list[i]["T"].Fail("a second stylus with this T number");
      if (other.contact_input == s.contact_input)
        list[i]["input"].Fail("the switch input of another stylus");
    }
    styluses.push_back(std::move(s));
  }
  return styluses;
}

}  // namespace vmt::sim
