// The scene's `measuring_pages:`: presets of TASTWERKZEUGPAGE and EICHWERTEPAGE, the model's
// probe as the default stylus page, bad values with the file and YAML path; the runner's channel
// reads the pages with MTD(...).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "sim/runner/runner.hpp"
#include "sim/scene/scene.hpp"
#include "tests/sim/sim_test_support.hpp"

namespace vmt::sim {
namespace {

using ::testing::HasSubstr;
using testing::OutputDir;

std::string WriteScene(const std::string& name, const std::string& body,
                       const std::string& duration = "0.05") {
  return testing::WriteLatheScene("measuring_pages", name, "duration: " + duration + "\n" + body);
}

std::string NcSection(const std::string& program_name, const std::string& program) {
  const std::string nc_path = OutputDir("measuring_pages") + "/" + program_name + ".mtc";
  std::ofstream(nc_path) << program;
  return "nc:\n  program: " + nc_path + "\n  axes: [X, Z]\n";
}

std::string ErrorOf(const std::string& name, const std::string& body) {
  return testing::SceneLoadError(WriteScene(name, body));
}

TEST(MeasuringPagesLoaderTest, StylusPageDefaultsToTheModelsProbe) {
  // lathe-c1: probe T3, NO contact, PIN4, one ruby of radius 3 mm.
  const Scene s = LoadScene(WriteScene("default", NcSection("default", "RET\n")));
  const auto& page = s.nc.measuring_pages.stylus[0];
  EXPECT_EQ(page.tool_number, 3);
  EXPECT_FALSE(page.normally_closed);
  EXPECT_FALSE(page.pin5);
  EXPECT_DOUBLE_EQ(page.sphere_radius[0], 3);
  EXPECT_EQ(page.sphere_radius[1], 0);
  // Stylus 2: the axial probe T7 on the drives' pin 5; there are no styluses 3 and 4.
  const auto& axial = s.nc.measuring_pages.stylus[1];
  EXPECT_EQ(axial.tool_number, 7);
  EXPECT_FALSE(axial.normally_closed);
  EXPECT_TRUE(axial.pin5);
  EXPECT_DOUBLE_EQ(axial.sphere_radius[0], 3);
  EXPECT_EQ(s.nc.measuring_pages.stylus[2].tool_number, 0);
}

TEST(MeasuringPagesLoaderTest, PresetsReplaceTheStylusPagesAndFillCalibration) {
  const Scene s = LoadScene(WriteScene(
      "preset", NcSection("preset", "RET\n") +
                    "measuring_pages:\n"
                    "  stylus:\n"
                    "    - {tool_number: 1, normally_closed: true, pin5: true, "
                    "sphere_radius: [2.5, 1]}\n"
                    "  calibration:\n"
                    "    - {stylus: 1, sphere: 2, measuring_direction: [1, -1, 2, -2, 0, 0],\n"
                    "       measuring_feed: [100, 200, 300, 400, 0, 0]}\n"));
  const auto& p = s.nc.measuring_pages;
  EXPECT_EQ(p.stylus[0].tool_number, 1);
  EXPECT_TRUE(p.stylus[0].normally_closed);
  EXPECT_TRUE(p.stylus[0].pin5);
  EXPECT_DOUBLE_EQ(p.stylus[0].sphere_radius[1], 1);
  EXPECT_DOUBLE_EQ(p.calibration[0][1].measuring_direction[3], -2);
  EXPECT_DOUBLE_EQ(p.calibration[0][1].measuring_feed[2], 300);
  EXPECT_EQ(p.calibration[0][0].measuring_feed[0], 0);
}

TEST(MeasuringPagesLoaderTest, BadValuesNameTheFileAndYamlPath) {
  const std::string nc = NcSection("bad", "RET\n");
  struct Case {
    std::string body, path, message;
  };
  const Case cases[] = {
      {"measuring_pages:\n  stylus:\n    - {tool_number: 3, sphere_radius: [3, -1]}\n",
       "measuring_pages.stylus[0].sphere_radius[1]", "must be > 0"},
      {"measuring_pages:\n  stylus:\n    - {tool_number: 9, sphere_radius: [3]}\n",
       "measuring_pages.stylus[0].tool_number", "T9 D1 is not in the tool list"},
      {"measuring_pages:\n  stylus:\n    - {tool_number: 3, sphere_radius: [3], pin: 5}\n",
       "measuring_pages.stylus[0].pin", "unknown key 'pin'"},
      {"measuring_pages:\n  calibration:\n    - {stylus: 5, sphere: 1}\n",
       "measuring_pages.calibration[0].stylus", "must be in 1..4"},
      {"measuring_pages:\n  calibration:\n    - {stylus: 1, sphere: 1, measuring_feed: [1, 2]}\n",
       "measuring_pages.calibration[0].measuring_feed", "expected 6 numbers"},
      {"measuring_pages:\n  calibration:\n    - {stylus: 1, sphere: 1}\n    - {stylus: 1, "
       "sphere: 1}\n",
       "measuring_pages.calibration[1]", "stylus 1 sphere 1 listed twice"},
  };
  for (const Case& c : cases) {
    const std::string e = ErrorOf("bad", nc + c.body);
    EXPECT_THAT(e, HasSubstr("bad.yaml:")) << c.body;
    EXPECT_THAT(e, HasSubstr(c.path + ": " + c.message)) << e;
  }
  EXPECT_THAT(ErrorOf("no_nc", "measuring_pages: {}\n"), HasSubstr("the scene needs nc:"));
}

TEST(MeasuringPagesLoaderTest, TheRunnersChannelReadsThePages) {
  // The program moves X to the stylus' sphere radius read with MTD (page 102 = TASTWERKZEUGPAGE).
  const Scene s = LoadScene(
      WriteScene("run",
                 NcSection("run", "@100 = MTD(102,1,,4) * 10\nG15 G53 G47 G01 X@100 F6000\nRET\n") +
                     "backend: kinematic\ninitial: {Z: 300, X: 100}\nexpect:\n  - {nc: ended}\n"
                     "  - {axis: X, position: 30, tol: 0.01}\n"
                     "timeline:\n  - nc: start\n  - wait_until: {nc: ended, timeout: 1.9}\n",
                 "2"));
  RunOptions options;
  options.snapshots = false;
  const RunResult r = RunScene(s, options);
  for (const std::string& f : r.failures) ADD_FAILURE() << f;
}

}  // namespace
}  // namespace vmt::sim
