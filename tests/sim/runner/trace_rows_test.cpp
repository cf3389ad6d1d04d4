// The trace's rows are the bytes the scene digests pin: every value written as printf's "%.6f"
// writes it (a field cut at 31 characters with its comma), -0 as 0, the spindle's rpm and the
// parameter set where the drive has them.

#include "sim/runner/trace_rows.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace vmt::sim {
namespace {

/// The reference: the row as snprintf formats it.
std::string Printf(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, ",%.6f", v == 0 ? 0.0 : v);
  return buf;
}

MachineModel TwoDrives() {
  MachineModel m;
  DriveParams x;
  x.info.name = "X";
  x.info.kind = control::AxisKind::kLinear;
  DriveParams s;
  s.info.name = "S1";
  s.spindle = true;
  s.parameter_sets.resize(2);
  m.drives = {x, s};
  return m;
}

TEST(TraceRows, ValuesAreWrittenAsPrintfWritesThem) {
  const MachineModel m = TwoDrives();
  EXPECT_EQ(TraceHeader(m, false), "t,X.cmd,X.pos,X.vel,S1.cmd,S1.pos,S1.vel,S1.rpm,S1.set\n");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> values = {0.0,
                                      -0.0,
                                      1e-7,
                                      -1e-7,
                                      5e-7,
                                      -5e-7,
                                      1.5e-6,
                                      0.1,
                                      -2.5,
                                      123.4567895,
                                      -987654.3210001,
                                      1e22,
                                      1e23,
                                      -1e25,
                                      1e300,
                                      -1.7976931348623157e308,
                                      4.9e-324,
                                      nan,
                                      -nan,
                                      inf,
                                      -inf,
                                      2.0000005,
                                      1234567.0000005};
  for (double v : values) {
    control::AmplifierTelegram at;
    at.feedback.resize(2);
    at.feedback[0].position = v;
    at.feedback[0].velocity = -v;
    at.feedback[1].velocity = v;
    at.feedback[1].parameter_set = 1;
    control::MasterTelegram mdt;
    mdt.setpoints.resize(2);
    mdt.setpoints[0] = {control::DriveMode::kPosition, v, 0};
    mdt.setpoints[1] = {control::DriveMode::kOff, v, 0};
    char t[32];
    std::snprintf(t, sizeof t, "%.6f", v);
    const std::string want = std::string(t) + Printf(v) + Printf(v) + Printf(-v) + Printf(0) +
                             Printf(0) + Printf(v) + Printf(v / 6.0) + Printf(1) + "\n";
    EXPECT_EQ(TraceRow(v, m, at, mdt, {}, nullptr), want) << "value " << v;
  }
}

// The one-drive row's position field, which the general path and the integer path both write.
std::string PositionField(double v) {
  MachineModel m = TwoDrives();
  m.drives.resize(1);
  control::AmplifierTelegram at;
  at.feedback.resize(1);
  at.feedback[0].position = v;
  control::MasterTelegram mdt;
  mdt.setpoints.resize(1);
  const std::string row = TraceRow(0, m, at, mdt, {}, nullptr);
  const size_t first = row.find(',', row.find(',') + 1);
  return row.substr(first, row.find(',', first + 1) - first);
}

// Printf rounds the double's exact value to six decimals, ties to even: the values whose
// millionths end in exactly one half (odd multiples of 2^-7, such as 0.0078125) round to the
// even neighbour, every other one to the nearest. Random doubles of every magnitude a trace
// holds, from denormals to past the integer path's range, must come out as printf writes them.
TEST(TraceRows, EveryMagnitudeIsRoundedAsPrintfRoundsIt) {
  std::vector<double> values;
  for (int k = -2000; k <= 2000; ++k) values.push_back((2 * k + 1) / 128.0);  // exact ties
  for (int k = -2000; k <= 2000; ++k) values.push_back(k / 1e6);
  for (double big : {8.999999999999e12, 9e12, 9.000000000001e12, 4503599627370496.5,
                     9007199254740993.0, 1e15, 1e18})
    values.push_back(big), values.push_back(-big);
  std::mt19937_64 random(20261202);
  for (int i = 0; i < 400000; ++i) {
    // A random mantissa under a random exponent from 2^-1074 to 2^50, either sign.
    const uint64_t mantissa = random() & ((uint64_t{1} << 52) - 1);
    const uint64_t biased = random() % (1023 + 51);
    const uint64_t sign = (random() & 1) << 63;
    values.push_back(std::bit_cast<double>(sign | (biased << 52) | mantissa));
  }
  std::uniform_real_distribution<double> millimetres(-2000, 2000);
  for (int i = 0; i < 200000; ++i) values.push_back(millimetres(random));
  int wrong = 0;
  for (double v : values)
    if (PositionField(v) != Printf(v) && ++wrong < 10) ADD_FAILURE() << "value " << v;
  EXPECT_EQ(wrong, 0);
}

TEST(TraceRows, ClutchesAndTheChannelCloseTheRow) {
  MachineModel m = TwoDrives();
  m.drives.resize(1);
  control::AmplifierTelegram at;
  at.feedback.resize(1);
  at.feedback[0].position = 12.25;
  control::MasterTelegram mdt;
  mdt.setpoints.resize(1);
  const std::vector<ClutchState> clutches = {static_cast<ClutchState>(2)};
  EXPECT_EQ(TraceRow(0.001, m, at, mdt, clutches, nullptr),
            "0.001000,0.000000,12.250000,0.000000,2.000000\n");
}

// A run's writer copies the fields whose bits did not change since the row before: row after
// row it must write what a row on its own writes, whichever fields hold, move, swap between
// the integer and the general path, or turn from 0 to -0 (written 0) and back.
TEST(TraceRows, ARunsRowsAreTheRowsOnTheirOwn) {
  const MachineModel m = TwoDrives();
  const std::vector<double> pool = {0.0,   -0.0,       1.5,
                                    -1.5,  123.456789, 1e300,
                                    -1e23, 4.9e-324,   std::numeric_limits<double>::quiet_NaN(),
                                    1e22,  7.0000005};
  std::mt19937_64 random(20261203);
  TraceRowWriter writer;
  control::AmplifierTelegram at;
  at.feedback.resize(2);
  control::MasterTelegram mdt;
  mdt.setpoints.resize(2);
  double t = 0;
  const std::vector<ClutchState> clutches = {static_cast<ClutchState>(1)};
  int held = 0;
  for (int row = 0; row < 3000; ++row) {
    // Each value holds with probability 3/4, else takes another from the pool.
    auto next = [&](double& v) {
      if (random() % 4 == 0)
        v = pool[random() % pool.size()];
      else
        ++held;
    };
    if (random() % 4 == 0) t = pool[random() % pool.size()];  // the first field's own cut
    next(at.feedback[0].position);
    next(at.feedback[0].velocity);
    next(at.feedback[1].position);
    next(at.feedback[1].velocity);
    next(mdt.setpoints[0].value);
    at.feedback[1].parameter_set = static_cast<int>(random() % 2);
    mdt.setpoints[1].mode = random() % 2 ? control::DriveMode::kOff : control::DriveMode::kVelocity;
    ASSERT_EQ(writer.Row(t, m, at, mdt, clutches, nullptr),
              TraceRow(t, m, at, mdt, clutches, nullptr))
        << "row " << row;
  }
  EXPECT_GT(held, 5000);  // most fields were copied, not formatted
}

}  // namespace
}  // namespace vmt::sim
