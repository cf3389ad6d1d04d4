// machine.yaml `probe:` (TASTWERKZEUGPAGE): lathe-c1/-c2's stylus as loaded, and every bad key
// named by its YAML path.

#include "sim/model/probe_stylus.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sim/model/model_error.hpp"
#include "tests/sim/sim_test_support.hpp"

namespace vmt::sim {
namespace {

using ::testing::HasSubstr;

// Stylus 1 of lathe-c1 and -c2: the radial touch probe T3.
void ExpectLatheStylus(const MachineModel& m) {
  ASSERT_GE(m.probes.size(), 1u);
  const ProbeStylus& s = m.probes[0];
  EXPECT_EQ(s.t_number, 3);
  EXPECT_FALSE(s.normally_closed);
  EXPECT_FALSE(s.pin5);
  EXPECT_EQ(s.link, m.LinkIndex("probe"));
  ASSERT_EQ(s.spheres.size(), 1u);
  EXPECT_NEAR((s.spheres[0].centre_m - Eigen::Vector3d(0.047, 0, 0)).norm(), 0, 1e-15);
  EXPECT_DOUBLE_EQ(s.spheres[0].radius_m, 0.003);
  EXPECT_EQ(s.sphere_parts, std::vector<std::string>{"probe_ruby"});
  EXPECT_DOUBLE_EQ(s.pre_travel_m, 5e-6);
  EXPECT_DOUBLE_EQ(s.over_travel_m, 1e-3);
  EXPECT_EQ(s.contact_input, control::IndexOf(m.io, "IPROBE_CONTACT"));
  EXPECT_EQ(s.ready_input, control::IndexOf(m.io, "IPROBE_READY"));
}

// The sphere the YAML gives is the ruby the URDF draws: every vertex of its collision mesh lies
// at the radius from the centre (to the OBJ's 7 decimals), the bounding box is centred on it.
void ExpectSphereIsTheRubyMesh(const MachineModel& m, size_t stylus = 0) {
  const ProbeStylus& s = m.probes.at(stylus);
  const Link& link = m.links[s.link];
  const Visual* ruby = nullptr;
  for (const Visual& c : link.collisions)
    if (c.name == s.sphere_parts.at(0)) ruby = &c;
  ASSERT_NE(ruby, nullptr);
  ASSERT_TRUE(ruby->mesh);
  const std::vector<float>& v = ruby->mesh->positions;
  ASSERT_GT(v.size(), 300u);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
  for (size_t i = 0; i + 2 < v.size(); i += 3) {
    const Eigen::Vector3d p = ruby->X_LinkVisual * Eigen::Vector3d(v[i], v[i + 1], v[i + 2]);
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    EXPECT_NEAR((p - s.spheres[0].centre_m).norm(), s.spheres[0].radius_m, 1e-6);
  }
  EXPECT_NEAR(((lo + hi) / 2 - s.spheres[0].centre_m).norm(), 0, 1e-6);
}

TEST(ProbeStylusModel, LatheC1HasItsStylusAtTheRuby) {
  ExpectLatheStylus(testing::Lathe());
  ExpectSphereIsTheRubyMesh(testing::Lathe());
}

// lathe-c1's stylus 2: the axial probe T7 in station 7, a probe of its own on the drives' PIN5,
// its ruby 50 mm ahead of the tool-tip plane along -z.
TEST(ProbeStylusModel, LatheC1HasAnAxialStylusAtItsRuby) {
  const MachineModel& m = testing::Lathe();
  ASSERT_EQ(m.probes.size(), 2u);
  const ProbeStylus& s = m.probes[1];
  EXPECT_EQ(s.t_number, 7);
  EXPECT_FALSE(s.normally_closed);
  EXPECT_TRUE(s.pin5);
  EXPECT_EQ(s.link, m.LinkIndex("probe_axial"));
  ASSERT_EQ(s.spheres.size(), 1u);
  EXPECT_NEAR((s.spheres[0].centre_m - Eigen::Vector3d(0.047, 0, -0.050)).norm(), 0, 1e-15);
  EXPECT_DOUBLE_EQ(s.spheres[0].radius_m, 0.003);
  EXPECT_EQ(s.sphere_parts, std::vector<std::string>{"probe_axial_ruby"});
  EXPECT_EQ(s.contact_input, control::IndexOf(m.io, "IPROBE2_CONTACT"));
  EXPECT_EQ(s.ready_input, control::IndexOf(m.io, "IPROBE2_READY"));
  ExpectSphereIsTheRubyMesh(m, 1);
}

TEST(ProbeStylusModel, LatheC2HasTheSameStylus) {
  const MachineModel m = LoadMachineModel(testing::SourcePath("models/lathe-c2/machine.yaml"));
  ExpectLatheStylus(m);
  EXPECT_EQ(m.probes.size(), 1u);
  ExpectSphereIsTheRubyMesh(m);
}

TEST(ProbeStylusModel, NcAndPin5AndSeveralSpheresAreRead) {
  const MachineModel m = testing::EditedLathe("probe_nc_pin5", [](std::string y) {
    y = testing::ReplaceOnce(y, "contact: NO", "contact: NC");
    y = testing::ReplaceOnce(y, "pin: PIN4", "pin: PIN5");
    return testing::ReplaceOnce(y, "- {centre: [47, 0, 0], radius: 3}",
                                "- {centre: [47, 0, 0], radius: 3}\n"
                                "      - {centre: [40, 5, -2], radius: 1.5}");
  });
  ASSERT_EQ(m.probes.size(), 2u);
  EXPECT_TRUE(m.probes[0].normally_closed);
  EXPECT_TRUE(m.probes[0].pin5);
  ASSERT_EQ(m.probes[0].spheres.size(), 2u);
  EXPECT_NEAR((m.probes[0].spheres[1].centre_m - Eigen::Vector3d(0.040, 0.005, -0.002)).norm(), 0,
              1e-15);
  EXPECT_DOUBLE_EQ(m.probes[0].spheres[1].radius_m, 0.0015);
}

std::string ErrorOf(const std::string& name, const std::string& from, const std::string& to) {
  try {
    testing::EditedLathe(name, [&](std::string y) { return testing::ReplaceOnce(y, from, to); });
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

TEST(ProbeStylusModel, BadKeysNameTheirYamlPath) {
  EXPECT_THAT(ErrorOf("probe_t", "- T: 3", "- T: 9"),
              HasSubstr("probe[0].T: no tool T9 D1 in nc: tools:"));
  EXPECT_THAT(ErrorOf("probe_t0", "- T: 3", "- T: 0"), HasSubstr("probe[0].T: must be >= 1"));
  EXPECT_THAT(ErrorOf("probe_link", "link: probe\n", "link: probes\n"),
              HasSubstr("probe[0].link: no link 'probes'"));
  EXPECT_THAT(ErrorOf("probe_contact", "contact: NO", "contact: 1"),
              HasSubstr("probe[0].contact: expected NO or NC"));
  EXPECT_THAT(ErrorOf("probe_pin", "pin: PIN4", "pin: 4"),
              HasSubstr("probe[0].pin: expected PIN4 or PIN5"));
  EXPECT_THAT(ErrorOf("probe_radius", "radius: 3}", "radius: 0}"),
              HasSubstr("probe[0].spheres[0].radius: must be in (0, 50] mm"));
  EXPECT_THAT(ErrorOf("probe_radius_huge", "radius: 3}", "radius: 60}"),
              HasSubstr("probe[0].spheres[0].radius: must be in (0, 50] mm"));
  EXPECT_THAT(ErrorOf("probe_centre_huge", "centre: [47, 0, 0]", "centre: [5000, 0, 0]"),
              HasSubstr("probe[0].spheres[0].centre: coordinates must be within +-1000 mm"));
  EXPECT_THAT(ErrorOf("probe_centre", "centre: [47, 0, 0]", "centre: [47, 0]"),
              HasSubstr("probe[0].spheres[0].centre"));
  const std::string six = "- {centre: [47, 0, 0], radius: 3}";
  EXPECT_THAT(
      ErrorOf("probe_six", six,
              "[" + std::string("{centre: [47, 0, 0], radius: 3}, ") +
                  "{centre: [47, 0, 0], radius: 3}, " + "{centre: [47, 0, 0], radius: 3}, " +
                  "{centre: [47, 0, 0], radius: 3}, " + "{centre: [47, 0, 0], radius: 3}, " +
                  "{centre: [47, 0, 0], radius: 3}]"),
      HasSubstr("probe[0].spheres: expected a list of 1 to 5 measuring spheres"));
  EXPECT_THAT(ErrorOf("probe_part", "sphere_parts: [probe_ruby]", "sphere_parts: [ruby]"),
              HasSubstr("probe[0].sphere_parts[0]: no <collision name=\"ruby\"> in link 'probe'"));
  EXPECT_THAT(ErrorOf("probe_pre", "pre_travel: 0.005", "pre_travel: -1"),
              HasSubstr("probe[0].pre_travel: must be in (0, 10] mm"));
  EXPECT_THAT(ErrorOf("probe_over", "over_travel: 1.0", "over_travel: 0.001"),
              HasSubstr("probe[0].over_travel: must be greater than pre_travel"));
  EXPECT_THAT(ErrorOf("probe_over_huge", "over_travel: 1.0", "over_travel: 80"),
              HasSubstr("probe[0].over_travel: must be greater than pre_travel, at most 50 mm"));
  EXPECT_THAT(ErrorOf("probe_input", "input: IPROBE_CONTACT", "input: QPROBE_ON"),
              HasSubstr("probe[0].input: 'QPROBE_ON' must be an input"));
  EXPECT_THAT(ErrorOf("probe_input2", "input: IPROBE_CONTACT", "input: IPROBE_NONE"),
              HasSubstr("probe[0].input: no I/O point 'IPROBE_NONE'"));
  EXPECT_THAT(ErrorOf("probe_ready", "ready: IPROBE_READY", "ready: IPROBE_CONTACT"),
              HasSubstr("probe[0].ready: is the switch's own input"));
  EXPECT_THAT(ErrorOf("probe_key", "    over_travel: 1.0", "    overtravel: 1.0"),
              HasSubstr("probe[0].overtravel: unknown key"));
  // The contact input is a switch of its own: not the actuator's ready switch as well.
  EXPECT_THAT(ErrorOf("probe_driven", "input: IPROBE_CONTACT", "input: ITURRET_INPOS"),
              HasSubstr("input 'ITURRET_INPOS' is the switch of more than one device"));
  std::string map_error;  // both styluses as entries of a map instead of a list
  try {
    testing::EditedLathe("probe_map", [](std::string y) {
      y = testing::ReplaceOnce(y, "probe:\n  - T: 3", "probe:\n  x:\n    T: 3");
      return testing::ReplaceOnce(y, "\n  - T: 7 ", "\n  y:\n    T: 7 ");
    });
  } catch (const ModelError& e) {
    map_error = e.what();
  }
  EXPECT_THAT(map_error, HasSubstr("probe: expected a list of up to four styluses"));
  // Two styluses: each its own T number and its own switch (TASTWERKZEUGPAGE 00001).
  EXPECT_THAT(ErrorOf("probe_same_t", "  - T: 7 ", "  - T: 3 "),
              HasSubstr("probe[1].T: a second stylus with this T number"));
  EXPECT_THAT(ErrorOf("probe_same_input", "input: IPROBE2_CONTACT", "input: IPROBE_CONTACT"),
              HasSubstr("probe[1].input: the switch input of another stylus"));
}

}  // namespace
}  // namespace vmt::sim
