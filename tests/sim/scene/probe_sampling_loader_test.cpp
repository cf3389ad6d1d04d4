// The scene's `probe:` key: the drives' probe sampling phase, fixed unless seeded; every bad
// entry names the YAML path.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "sim/scene/scene.hpp"
#include "tests/sim/sim_test_support.hpp"

namespace vmt::sim {
namespace {

using ::testing::HasSubstr;

std::string WriteScene(const std::string& name, const std::string& probe) {
  return testing::WriteLatheScene("probe_sampling_loader", name,
                                  "duration: 0.01\n" + probe);
}

TEST(ProbeSamplingLoaderTest, FixedUnlessSeeded) {
  EXPECT_FALSE(LoadScene(WriteScene("none", "")).probe_sampling.seeded);
  EXPECT_FALSE(
      LoadScene(WriteScene("fixed", "probe: {sampling_phase: fixed}\n")).probe_sampling.seeded);
  const Scene s = LoadScene(WriteScene("seeded", "probe: {sampling_phase: seeded, seed: 42}\n"));
  EXPECT_TRUE(s.probe_sampling.seeded);
  EXPECT_EQ(s.probe_sampling.seed, 42u);
  const Scene d = LoadScene(WriteScene("default-seed", "probe: {sampling_phase: seeded}\n"));
  EXPECT_TRUE(d.probe_sampling.seeded);
  EXPECT_EQ(d.probe_sampling.seed, 0u);
}

TEST(ProbeSamplingLoaderTest, BadEntriesNameTheirPath) {
  EXPECT_THAT(testing::SceneLoadError(WriteScene("word", "probe: {sampling_phase: random}\n")),
              HasSubstr("probe.sampling_phase: expected fixed or seeded, got \"random\""));
  EXPECT_THAT(testing::SceneLoadError(WriteScene("seed-fixed", "probe: {seed: 3}\n")),
              HasSubstr("probe.seed: a seed needs sampling_phase: seeded"));
  EXPECT_THAT(testing::SceneLoadError(
                  WriteScene("seed-frac", "probe: {sampling_phase: seeded, seed: 1.5}\n")),
              HasSubstr("probe.seed: expected a whole number"));
  EXPECT_THAT(testing::SceneLoadError(WriteScene("key", "probe: {phase: seeded}\n")),
              HasSubstr("phase"));
  EXPECT_THAT(testing::SceneLoadError(WriteScene("scalar", "probe: seeded\n")),
              HasSubstr("probe: expected a map"));
}

}  // namespace
}  // namespace vmt::sim
