// The timeline step `jog: {axis, to}`: the operator sets the increment to the distance from
// where the axis stands and taps the key toward the position (the increment is completed), the
// way a REPOS study's retract goes to a tool change point.

#include <gtest/gtest.h>

#include <string>

#include "../sim_test_support.hpp"
#include "sim/runner/runner.hpp"

namespace vmt::sim {
namespace {

const std::string kNc = "backend: kinematic\n"
                        "initial: {Z: 250, X: 110, T: 0, W: 300}\n"
                        "nc:\n  program: " +
                        testing::SourcePath("scenes/nc/stepped_shaft.mtc") +
                        "\n  axes: [X, Z]\n  spindle: S1\n";

RunResult RunJogScene(const std::string& name, const std::string& body) {
  const std::string dir = testing::OutputDir("jog_to/" + name);
  const std::string path = testing::WriteLatheScene("jog_to/" + name, "scene", body);
  RunOptions options;
  options.out_dir = dir;
  options.snapshots = false;
  return RunScene(LoadScene(path), options);
}

TEST(JogToTest, EachAxisEndsAtItsPositionWhicheverWayItIs) {
  const RunResult r = RunJogScene("both_ways", kNc +
                                           "duration: 6\n"
                                           "timeline:\n"
                                           "  - nc: {mode: manual}\n"
                                           "  - wait: 0.1\n"  // the PLC's jog mode
                                           "  - jog: {axis: X, to: 150}\n"
                                           "  - wait_until: {signal: A01S.MVPOS, value: false}\n"
                                           "  - wait: 0.5\n"
                                           "  - jog: {axis: Z, to: 212.345}\n"
                                           "  - wait: 2\n"
                                           "expect:\n"
                                           "  - {axis: X, position: 150, tol: 0.001}\n"
                                           "  - {axis: Z, position: 212.345, tol: 0.001}\n");
  EXPECT_TRUE(r.ok()) << r.failures.size() << (r.failures.empty() ? "" : r.failures[0]);
}

TEST(JogToTest, AnAxisAlreadyThereIsNotJogged) {
  // No key: an increment of 0 would be continuous jogging, and the held key would run away
  // (Z, before any increment was set); nor is the increment of the jog before repeated (X, after
  // its jog to 120 left an increment of 10 set). That jog shows the step moves an axis that is
  // not there yet.
  const RunResult r = RunJogScene("already_there", kNc +
                                               "duration: 4\n"
                                               "timeline:\n"
                                               "  - nc: {mode: manual}\n"
                                               "  - wait: 0.1\n"
                                               "  - jog: {axis: Z, to: 250, hold: 1}\n"
                                               "  - wait: 0.3\n"
                                               "  - jog: {axis: X, to: 120}\n"
                                               "  - wait_until: {signal: A01S.MVPOS, value: false}\n"
                                               "  - wait: 0.3\n"
                                               "  - jog: {axis: X, to: 120, hold: 1}\n"
                                               "  - wait: 0.3\n"
                                               "expect:\n"
                                               "  - {axis: Z, position: 250, tol: 0.0001}\n"
                                               "  - {axis: X, position: 120, tol: 0.0001}\n");
  EXPECT_TRUE(r.ok()) << (r.failures.empty() ? "" : r.failures[0]);
}

TEST(JogToTest, ToIsAPositionOfADriveNotADirection) {
  const std::string head = kNc + "duration: 1\ntimeline:\n  - nc: {mode: manual}\n";
  EXPECT_NE(testing::SceneLoadError(testing::WriteLatheScene(
                "jog_to/both", "scene", head + "  - jog: {axis: X, to: 150, direction: +}\n"))
                .find("timeline[1].jog.direction: give direction or to, not both"),
            std::string::npos);
  EXPECT_NE(testing::SceneLoadError(testing::WriteLatheScene(
                "jog_to/fictive", "scene", head + "  - jog: {axis: X1, to: 10}\n"))
                .find("timeline[1].jog.to: a fictive axis has no drive position"),
            std::string::npos);
}

}  // namespace
}  // namespace vmt::sim
