// Calibrate, then measure the same surface again and again, with the ruby really touching the
// part and the drives latching (fast-measurement manual 5.1, 5.2, 7.3). With the drives'
// sampling clock fixed to the simulation's ticks every contact falls at the same point of the
// 250 us period and the calibration cancels the latch delay exactly; with the seeded sampling
// phase (scene `probe: {sampling_phase: seeded}`) the measured values scatter as on a real
// machine, within one period times the feed, and a seed gives the same values every run.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../sim_test_support.hpp"
#include "control/measure/measuring_pages.hpp"
#include "sim/backend/probe_wiring.hpp"
#include "sim/runner/runner.hpp"

namespace vmt::sim {
namespace {

constexpr int kRepetitions = 8;
constexpr double kFeedMmPerMin = 200;
constexpr double kEncoderIncrementMm = 1e-4;  // lathe-c1's X

struct Measured {
  std::vector<double> deviations;  ///< POINTPAGE 1..kRepetitions, mm (radius)
  std::vector<std::string> warnings;
  bool ok = false;
};

// The stylus T3 (sphere centre = axis X + 3 mm) calibrates X- on the d60 at F200, measures
// the same place kRepetitions times at F200 and once more at F400, each time from X40 Z115
// straight in and back out (approach variant 1).
Measured MeasureRepeatedly(const std::string& name, const std::string& probe) {
  const std::string dir = testing::OutputDir("measuring_scatter/" + name);
  std::ofstream program(dir + "/repeat.mtc");
  program << "N0010 SETTING(X,Z,,18,48,16,1)\n"
             "N0020 PROBE(,0,60,110,,X,-4,200,1,1,0)\n";
  for (int n = 1; n <= kRepetitions; ++n)
    program << "N" << (100 + n) << " PROBE(" << n << ",1,60,110,,X,-4,200,1,1,0)\n";
  program << "N0200 PROBE(" << kRepetitions + 1 << ",1,60,110,,X,-4,400,1,1,0)\n"
          << "N0210 RET\n";
  program.close();
  std::ofstream(dir + "/scene.yaml")
      << "scene: " << name << "\nmodel: " << testing::SourcePath("models/lathe-c1/machine.yaml")
      << "\nbackend: kinematic\nduration: 40\n" << probe
      << "workpiece:\n  z: 60\n  sections:\n    - {from: 0, to: 160, diameter: 60}\n"
         "initial: {Z: 115, X: 40, T: 60, W: 600}\n"
         "nc:\n  program: repeat.mtc\n  aux_handshake: true\n"
         "plc:\n  program: probe_block\n"
         "  constants: {QMFB1A00.ENABLE: true, QMFB1A00.ACHS_NR_1: 1, QMFB1A00.ACHS_NR_2: 2}\n"
         "timeline:\n  - nc: start\n  - wait_until: {nc: ended, timeout: 39}\n"
         "expect:\n  - {nc: ended}\n";
  Measured m;
  RunOptions options;
  options.snapshots = false;
  options.on_event = [&m](const nlohmann::ordered_json& e) {
    if (e["event"] == "measuring") m.warnings.push_back(e["warning"].get<std::string>());
  };
  const Scene scene = LoadScene(dir + "/scene.yaml");  // the run keeps a reference
  SceneRun run(scene, options);
  while (!run.done()) run.Step();
  const control::measure::MeasuringPages& pages = *run.measuring_pages();
  for (int n = 1; n <= kRepetitions; ++n) {
    const control::measure::PointPage* p = pages.Point(0, n);
    if (p) m.deviations.push_back(p->value.deviation);
  }
  m.ok = run.Finish().ok();
  return m;
}

// Fixed sampling: every contact falls at the same point of the period; the calibration at the
// same feed cancels the latch delay, and the repetitions agree to the last digit. The PROBE at
// F400 warns: its direction was calibrated at F200.
TEST(MeasuringScatterTest, FixedSamplingRepeatsExactlyAndAnotherFeedWarns) {
  const Measured m = MeasureRepeatedly("fixed", "");
  ASSERT_TRUE(m.ok);
  ASSERT_EQ(m.deviations.size(), static_cast<size_t>(kRepetitions));
  for (const double d : m.deviations) {
    EXPECT_EQ(d, m.deviations.front());
    EXPECT_LE(std::abs(d), kEncoderIncrementMm);
  }
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("repeat.mtc:" + std::to_string(kRepetitions + 3) + ":"),
            std::string::npos)
      << m.warnings[0];
  EXPECT_NE(m.warnings[0].find("warning: PROBE measures at F400"), std::string::npos)
      << m.warnings[0];
  EXPECT_NE(m.warnings[0].find("calibrated at F200"), std::string::npos) << m.warnings[0];
}

// Seeded sampling: the calibration's contact and each measurement's fall at random points of
// the period, so the deviation of a perfect surface scatters, within the feed times one period
// (the difference of two latch delays, each between -80 and +170 us, 7.3) plus an encoder
// increment; the same seed, the same values; another seed, others.
TEST(MeasuringScatterTest, SeededSamplingScattersWithinOnePeriodTimesTheFeed) {
  const Measured a = MeasureRepeatedly("seeded-7", "probe: {sampling_phase: seeded, seed: 7}\n");
  ASSERT_TRUE(a.ok);
  ASSERT_EQ(a.deviations.size(), static_cast<size_t>(kRepetitions));
  const double bound = kFeedMmPerMin / 60 * kProbeSamplePeriodS + kEncoderIncrementMm;
  for (const double d : a.deviations) EXPECT_LE(std::abs(d), bound) << d;
  const auto [lo, hi] = std::minmax_element(a.deviations.begin(), a.deviations.end());
  // A scatter a metrology engineer sees: more than two encoder increments wide, not all zero.
  EXPECT_GT(*hi - *lo, 2 * kEncoderIncrementMm);
  EXPECT_TRUE(std::any_of(a.deviations.begin(), a.deviations.end(),
                          [](double d) { return std::abs(d) > kEncoderIncrementMm / 2; }));

  const Measured again =
      MeasureRepeatedly("seeded-7-again", "probe: {sampling_phase: seeded, seed: 7}\n");
  EXPECT_EQ(again.deviations, a.deviations);
  const Measured other =
      MeasureRepeatedly("seeded-8", "probe: {sampling_phase: seeded, seed: 8}\n");
  EXPECT_NE(other.deviations, a.deviations);
}

}  // namespace
}  // namespace vmt::sim
