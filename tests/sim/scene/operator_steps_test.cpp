// operator.yaml as vmt run --operator reads it: whole ticks in order, known keys only, and
// errors that name the file and YAML path.

#include "sim/scene/operator_steps.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

TEST(OperatorStepsTest, OperatorFilesAreCheckedAsTheyAreRead) {
  const std::string dir = testing::OutputDir("operator-files");
  auto error_of = [&](const std::string& text) {
    const std::string path = dir + "/bad.yaml";
    std::ofstream(path) << text;
    try {
      ReadOperatorSteps(path);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(
      error_of("operator:\n  - {tick: 1.5, signal: mAUTO, value: 1}\n").find("operator[0].tick"),
      std::string::npos);
  EXPECT_NE(error_of("operator:\n  - {tick: 32, signal: a, value: 1}\n  - {tick: 16, signal: b, "
                     "value: 0}\n")
                .find("goes back in time"),
            std::string::npos);
  EXPECT_NE(error_of("operator:\n  - {tick: 3, signal: a, value: 1, extra: 2}\n").find("extra"),
            std::string::npos);
  EXPECT_NE(error_of("nothing: 1\n").find("nothing"), std::string::npos);
  EXPECT_EQ(error_of("operator: []\n"), "");
}

TEST(OperatorStepsTest, ReadsTheStepsInOrder) {
  const std::string path = testing::OutputDir("operator-files") + "/good.yaml";
  std::ofstream(path) << "scene: x\noperator:\n  - {tick: 16, signal: mAUTO, value: 1}\n"
                         "  - {tick: 16, signal: mAUTO, value: 0}\n"
                         "  - {tick: 32, handwheel: X, counts: -3}\n";
  const std::vector<OperatorStep> steps = ReadOperatorSteps(path);
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(steps[2].handwheel, "X");
  EXPECT_EQ(steps[2].value, -3);
  EXPECT_TRUE(steps[2].signal.empty());
  EXPECT_EQ(steps[0].tick, 16);
  EXPECT_EQ(steps[0].signal, "mAUTO");
  EXPECT_EQ(steps[1].value, 0);
}

}  // namespace
}  // namespace vmt::sim
