// The scene's `workpiece:`: the sections of a part whose true dimensions a measuring scene knows,
// a face groove among them, and `oversize:` on the sections marked machined (a diameter
// allowance; the calibration masters keep their size); every bad value names the file and the
// YAML path.

#include "sim/scene/workpiece_loader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "sim/scene/scene.hpp"
#include "tests/sim/sim_test_support.hpp"

namespace vmt::sim {
namespace {

using ::testing::HasSubstr;

constexpr double kMm = 1e-3;

std::string WriteScene(const std::string& name, const std::string& workpiece) {
  return testing::WriteLatheScene("workpiece_loader", name,
                                  "duration: 0.01\nworkpiece:\n" + workpiece);
}

Workpiece Load(const std::string& name, const std::string& workpiece) {
  return LoadScene(WriteScene(name, workpiece)).workpiece;
}

std::string ErrorOf(const std::string& name, const std::string& workpiece) {
  return testing::SceneLoadError(WriteScene(name, workpiece));
}

// The stepped shaft of measure-shaft: the d60 master, the d40 turned.
const char* kShaft =
    "  z: 60\n"
    "  sections:\n"
    "    - {from: 0, to: 130, diameter: 60}\n"
    "    - {from: 130, to: 160, diameter: 40, machined: true}\n";

// The face groove of measure-face-groove: inner d30, outer d46, 5 deep, core and ring machined.
const char* kFaceGroove =
    "  z: 60\n"
    "  sections:\n"
    "    - {from: 0, to: 155, diameter: 60}\n"
    "    - {from: 155, to: 160, diameter: 30, machined: true}\n"
    "    - {from: 155, to: 160, diameter: 60, bore: 46, machined: true}\n";

TEST(WorkpieceLoaderTest, SectionsAreTheTrueDimensions) {
  const Workpiece w = Load("shaft", kShaft);
  ASSERT_TRUE(w.present);
  ASSERT_EQ(w.part.sections.size(), 2u);
  EXPECT_NEAR(w.part.sections[0].z0_m, 60 * kMm, 1e-12);
  EXPECT_NEAR(w.part.sections[0].z1_m, 190 * kMm, 1e-12);
  EXPECT_NEAR(w.part.sections[0].r_outer_m, 30 * kMm, 1e-12);
  EXPECT_NEAR(w.part.sections[1].r_outer_m, 20 * kMm, 1e-12);
  EXPECT_EQ(w.part.sections[1].r_inner_m, 0);
}

TEST(WorkpieceLoaderTest, OversizeIsADiameterAllowanceOfTheMachinedSectionsOnly) {
  const Workpiece w = Load("shaft_oversize", std::string(kShaft) + "  oversize: 0.1\n");
  EXPECT_NEAR(w.part.sections[0].r_outer_m, 30 * kMm, 1e-12);     // the master as it is
  EXPECT_NEAR(w.part.sections[1].r_outer_m, 20.05 * kMm, 1e-12);  // d40.1
  EXPECT_NEAR(w.part.sections[1].z0_m, 190 * kMm, 1e-12);         // faces stay put
  EXPECT_NEAR(w.part.sections[1].z1_m, 220 * kMm, 1e-12);
  const Workpiece u = Load("shaft_undersize", std::string(kShaft) + "  oversize: -0.1\n");
  EXPECT_NEAR(u.part.sections[0].r_outer_m, 30 * kMm, 1e-12);
  EXPECT_NEAR(u.part.sections[1].r_outer_m, 19.95 * kMm, 1e-12);  // d39.9
}

TEST(WorkpieceLoaderTest, OversizeNarrowsAFaceGrooveFromBothWalls) {
  const Workpiece w = Load("groove_oversize", std::string(kFaceGroove) + "  oversize: 0.2\n");
  ASSERT_EQ(w.part.sections.size(), 3u);
  EXPECT_NEAR(w.part.sections[0].r_outer_m, 30 * kMm, 1e-12);
  EXPECT_NEAR(w.part.sections[1].r_outer_m, 15.1 * kMm, 1e-12);  // core d30.2
  EXPECT_NEAR(w.part.sections[2].r_inner_m, 22.9 * kMm, 1e-12);  // bore d45.8
  EXPECT_NEAR(w.part.sections[2].r_outer_m, 30.1 * kMm, 1e-12);  // the ring's outside d60.2
  EXPECT_NEAR(w.part.sections[1].z0_m, 215 * kMm, 1e-12);        // the groove's bottom
}

TEST(WorkpieceLoaderTest, BadValuesNameTheFileAndTheYamlPath) {
  EXPECT_THAT(ErrorOf("bad_machined",
                      "  z: 60\n  sections:\n"
                      "    - {from: 0, to: 10, diameter: 40, machined: 2}\n"),
              HasSubstr("workpiece.sections[0].machined: expected true or false"));
  EXPECT_THAT(ErrorOf("bad_oversize", std::string(kShaft) + "  oversize: big\n"),
              HasSubstr("workpiece.oversize: expected a number"));
  const std::string none = ErrorOf("oversize_none_machined",
                                   "  z: 60\n  sections:\n"
                                   "    - {from: 0, to: 10, diameter: 40}\n  oversize: 0.1\n");
  EXPECT_THAT(none, HasSubstr("oversize_none_machined.yaml"));
  EXPECT_THAT(none, HasSubstr("workpiece.oversize: no section is machined: true"));
  EXPECT_THAT(ErrorOf("oversize_stock", "  {diameter: 60, length: 100, z: 60, oversize: 0.1}\n"),
              HasSubstr("workpiece.oversize: needs sections, some of them machined: true"));
  EXPECT_THAT(ErrorOf("oversize_shut", std::string(kFaceGroove) + "  oversize: 16\n"),
              HasSubstr("workpiece.oversize: closes the gap between sections 1 and 2"));
  EXPECT_THAT(ErrorOf("oversize_bore",
                      "  z: 60\n  sections:\n"
                      "    - {from: 0, to: 10, diameter: 40, bore: 4,"
                      " machined: true}\n  oversize: 5\n"),
              HasSubstr("workpiece.oversize: closes the bore of section 0"));
  EXPECT_THAT(ErrorOf("oversize_gone", std::string(kShaft) + "  oversize: -40\n"),
              HasSubstr("workpiece.oversize: leaves section 1 without material"));
}

// A size beyond a lathe's is refused with its range: 1e20 made the mesh code loop for minutes.
TEST(WorkpieceLoaderTest, SizesBeyondALathesAreRefused) {
  EXPECT_THAT(ErrorOf("huge_stock", "  {diameter: 1e308, length: 100, z: 60}\n"),
              HasSubstr("workpiece.diameter: must be in"));
  EXPECT_THAT(ErrorOf("big_stock", "  {diameter: 5000, length: 100, z: 60}\n"),
              HasSubstr("workpiece.diameter: must be in (0, 2000] mm, got 5000"));
  EXPECT_THAT(ErrorOf("negative_stock", "  {diameter: -60, length: 100, z: 60}\n"),
              HasSubstr("workpiece.diameter: must be in (0, 2000] mm"));
  EXPECT_THAT(ErrorOf("long_stock", "  {diameter: 60, length: 20000, z: 60}\n"),
              HasSubstr("workpiece.length: must be in (0, 10000] mm"));
  EXPECT_THAT(ErrorOf("far_stock", "  {diameter: 60, length: 100, z: -20000}\n"),
              HasSubstr("workpiece.z: must be in [-10000, 10000] mm"));
  EXPECT_THAT(ErrorOf("huge_section",
                      "  z: 60\n  sections:\n"
                      "    - {from: 0, to: 10, diameter: 3000}\n"),
              HasSubstr("workpiece.sections[0].diameter: must be in (0, 2000] mm"));
  EXPECT_THAT(ErrorOf("far_section",
                      "  z: 60\n  sections:\n"
                      "    - {from: 0, to: 20000, diameter: 40}\n"),
              HasSubstr("workpiece.sections[0].to: must be in [-10000, 10000] mm"));
  EXPECT_THAT(ErrorOf("huge_oversize", std::string(kShaft) + "  oversize: 500\n"),
              HasSubstr("workpiece.oversize: must be in [-100, 100] mm"));
}

}  // namespace
}  // namespace vmt::sim
