// Every planned motion ends: random tiny (down to below a femtometre, and none at all) and huge
// moves of every axis under every G code that moves (G00, G01, G02/G03, G33, G74), with and
// without a jerk limit, reach the end of their block within a bound of NC cycles; and a target
// computed from a measured value a hair from where the axis stands is a move like any other.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"
#include "control/measure/measuring_pages.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

constexpr double kTick = 250e-6;
constexpr double kCycle = 4 * kTick;
constexpr int kX = 0, kZ = 1, kC = 2, kS = 3;

// X, Z and the rotary axis C on an ideal machine (actual = setpoint), the spindle on drive 3
// turning up at 7200 deg/s^2 to its speed.
struct Rig : test_support::IdealDriveBus {
  Rig(const std::string& program, const std::vector<double>& start, bool jerk,
      const std::vector<double>& reference = {})
      : IdealDriveBus(4) {
    parsed = nc::ParseProgram(program, "p.mtc", nc::Dialect::kMtc200);
    EXPECT_TRUE(parsed.ok()) << program
                             << (parsed.ok() ? "" : nc::Format(parsed.errors[0], parsed.program.files));
    ChannelConfig config;
    config.axes = {Axis("X", kX, 400), Axis("Z", kZ, 500), Axis("C", kC, 1200)};
    config.axes[kC].rotary = true;
    config.axes[kC].acceleration = 6000;
    if (jerk) {
      config.axes[kX].jerk = config.axes[kZ].jerk = 200000;
      config.axes[kC].jerk = 300000;
    }
    for (size_t a = 0; a < reference.size(); ++a) config.axes[a].reference_position = reference[a];
    config.spindle_drive = kS;
    channel = std::make_unique<Channel>(config, std::vector<const nc::Program*>{&parsed.program});
    for (test_support::IdealDrive& d : drives) {
      d = test_support::IdealDrive::Servo(7200);
      d.at_speed = true;
    }
    for (size_t a = 0; a < start.size(); ++a) at.feedback[a].position = start[a];
  }
  void Tick() {
    channel->Tick(at, mdt);
    Answer();
  }
  /// NC cycles until the program ended or failed; -1 if it is still running after `limit`.
  long RunUntilEnd(long limit) {
    channel->Start();
    for (long ticks = 0; ticks < 4 * limit; ++ticks) {
      if (channel->state() == ChannelState::kEnded || channel->state() == ChannelState::kError)
        return ticks / 4;
      Tick();
    }
    return -1;
  }

  nc::ParseResult parsed;
  std::unique_ptr<Channel> channel;
};

std::string Number(double v) {
  char s[40];
  std::snprintf(s, sizeof s, "%.17g", v);
  return s;
}

double LogUniform(std::mt19937_64& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(std::log(lo), std::log(hi));
  return std::exp(u(rng));
}

// A move's length: none, below and around the planning's thresholds, sub-micrometre, or long.
double Distance(std::mt19937_64& rng, double huge) {
  std::uniform_real_distribution<double> u(0, 1);
  const double pick = u(rng);
  const double d = pick < 0.1    ? 0
                   : pick < 0.35 ? LogUniform(rng, 1e-15, 1e-10)
                   : pick < 0.6  ? LogUniform(rng, 1e-10, 1e-3)
                                 : LogUniform(rng, 1, huge);
  return u(rng) < 0.5 ? -d : d;
}

TEST(ChannelMotionEndTest, EveryMoveOfAnyLengthReachesItsBlockEnd) {
  std::mt19937_64 rng(27001);
  std::uniform_real_distribution<double> u(0, 1);
  const char* const kAxes[] = {"X", "Z", "C"};
  int runs = 0, tiny = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const int g = std::uniform_int_distribution<int>(0, 5)(rng);  // G00 G01 G02 G03 G33 G74
    const bool jerk = u(rng) < 0.7;
    std::vector<double> start = {LogUniform(rng, 1, 200) * (u(rng) < 0.5 ? -1 : 1),
                                 LogUniform(rng, 1, 200) * (u(rng) < 0.5 ? -1 : 1),
                                 LogUniform(rng, 1, 300)};
    std::vector<double> target = start, reference = start;
    std::string move, setup;
    // Time bound: the length at the slowest rate that may limit it, the ramps, a margin.
    double length = 0, rate = 400, feed_mm_per_min = 6000;
    if (g <= 1 || g == 5) {
      // Linear moves and homing: a random set of axes, each its own distance.
      int mask = std::uniform_int_distribution<int>(1, 7)(rng);
      move = g == 0 ? "G00" : g == 1 ? "G01" : "G74";
      for (int a = 0; a < 3; ++a) {
        if (!(mask >> a & 1)) continue;
        const double d = Distance(rng, g == 5 ? 50 : 500);
        if (g == 5) {
          reference[a] = start[a] + d;
          target[a] = reference[a];
          move += std::string(" ") + kAxes[a] + "0";  // G74's value is a placeholder
        } else {
          target[a] = start[a] + d;
          move += std::string(" ") + kAxes[a] + Number(target[a]);
        }
        length += std::abs(target[a] - start[a]);
      }
      if (g == 1) {
        feed_mm_per_min = LogUniform(rng, 100, 20000);
        move += " F" + Number(feed_mm_per_min);
        rate = feed_mm_per_min / 60;
      }
      if (g == 5) rate = 40;  // the homing speed: a tenth of the rapid rate
    } else if (g <= 3) {
      // An arc in G18 (Z-X) from where the axes stand, by I/K, turned by a random angle: none
      // or a hair is the full circle.
      const double r = LogUniform(rng, 0.1, 100);
      const double phi0 = u(rng) * 2 * std::numbers::pi;
      const double sweep = std::abs(Distance(rng, 6)) / std::max(1.0, r);
      const double phi1 = phi0 + (g == 2 ? -sweep : sweep);
      const double cz = start[kZ] - r * std::cos(phi0), cx = start[kX] - r * std::sin(phi0);
      target[kZ] = cz + r * std::cos(phi1);
      target[kX] = cx + r * std::sin(phi1);
      feed_mm_per_min = LogUniform(rng, 100, 20000);
      move = std::string(g == 2 ? "G02" : "G03") + " X" + Number(target[kX]) + " Z" +
             Number(target[kZ]) + " I" + Number(cx - start[kX]) + " K" +
             Number(cz - start[kZ]) + " F" + Number(feed_mm_per_min);
      length = 2 * std::numbers::pi * r;
      rate = std::min(feed_mm_per_min / 60, std::sqrt(4000 * r));
    } else {
      // G33 along Z (a taper when X moves too) at 600 rpm: the lead gives the rate.
      setup = "N1 M3 S600\n";
      target[kZ] = start[kZ] + Distance(rng, 60);
      if (u(rng) < 0.3) target[kX] = start[kX] + Distance(rng, 5) * 0.01;
      move = "G33 X" + Number(target[kX]) + " Z" + Number(target[kZ]) + " F1.5";
      length = std::abs(target[kZ] - start[kZ]) + std::abs(target[kX] - start[kX]);
      rate = 1.5 * 10;
    }
    const std::string program = setup + "N2 " + move + "\nN3 RET\n";
    Rig rig(program, start, jerk, reference);
    const long bound = static_cast<long>((2 * length / rate + 2) / kCycle) + 100;
    const long cycles = rig.RunUntilEnd(bound);
    SCOPED_TRACE(program + (jerk ? "(jerk limited)" : "(no jerk limit)"));
    ASSERT_GE(cycles, 0) << "still running after " << bound << " cycles";
    // A thread shorter than its spindle-synchronous ramps is refused at its block: an end too.
    if (g == 4 && rig.channel->state() == ChannelState::kError &&
        rig.channel->error().find("shorter than its ramp-in and run-out") != std::string::npos) {
      ++runs;
      continue;
    }
    ASSERT_EQ(rig.channel->state(), ChannelState::kEnded) << rig.channel->error();
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(rig.at.feedback[a].position, target[a], 1e-9) << kAxes[a];
    ++runs;
    if (length < 1e-10) ++tiny;
  }
  EXPECT_EQ(runs, 600);
  EXPECT_GT(tiny, 50);  // the moves that froze the channel are well represented
}

TEST(ChannelMotionEndTest, ATargetFromAMeasuredValueAHairAwayIsReached) {
  // A probe's result (a correction value of 3e-12 mm) added to where an axis stands: the G00 of
  // X to it moves by that; so does the G01 of Z, which the look-ahead blends into the G01 on
  // along Z after it. The program goes on to its end.
  measure::MeasuringPages pages;
  pages.Result(0, 2)->correction_value = 3e-12;
  Machine m(
      "N1 G00 X10 Z5\n"
      "N2 @100 = 10 + MTD(105,,2,13)\n"
      "N3 G00 X@100\n"
      "N4 @101 = 5 + MTD(105,,2,13)\n"
      "N5 G01 Z@101 F1000\n"
      "N6 G01 Z10\n"
      "N7 RET\n",
      0, 0, [](ChannelConfig& c) {
        for (ChannelAxis& a : c.axes) a.jerk = 200000;
      });
  m.channel->SetMeasuringPages(&pages);
  m.channel->Start();
  m.RunUntilEnd(2);
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_EQ(m.X(), 10 + 3e-12);
  EXPECT_EQ(m.Z(), 10);
}

}  // namespace
}  // namespace vmt::control::channel
