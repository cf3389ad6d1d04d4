#pragma once
// Shared by the channel tests (channel_*_test.cpp): the channel on an ideal machine (X and Z
// follow their setpoints; the spindle's feedback is the test's) with axes X and Z and a spindle,
// and a configuration with zero offsets and tools.

#include <gtest/gtest.h>

#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "control/channel/channel.hpp"
#include "control/nc/parser.hpp"
#include "tests/support/ideal_drive_bus.hpp"

namespace vmt::control::channel::testing {

inline ChannelAxis Axis(const std::string& name, int drive, double rapid_per_s) {
  ChannelAxis a;
  a.name = name;
  a.number = drive + 1;
  a.drive = drive;
  a.rapid_per_s = rapid_per_s;
  a.acceleration = 4000;
  return a;
}

struct Machine : test_support::IdealDriveBus {
  explicit Machine(const std::string& program, double x = 0, double z = 0,
                   const std::function<void(ChannelConfig&)>& configure = {},
                   nc::Dialect dialect = nc::Dialect::kMtc200)
      : IdealDriveBus(3) {
    parsed = nc::ParseProgram(program, dialect == nc::Dialect::kIsg ? "p.isg" : "p.mtc", dialect);
    EXPECT_TRUE(parsed.ok()) << nc::Format(parsed.errors[0], parsed.program.files);
    ChannelConfig config;
    config.axes = {Axis("X", 0, 400), Axis("Z", 1, 500)};
    config.spindle_drive = 2;
    if (configure) configure(config);
    channel = std::make_unique<Channel>(config, std::vector<const nc::Program*>{&parsed.program});
    channel_config = config;
    drives[0] = drives[1] = test_support::IdealDrive::Follow();
    at.feedback[0].position = x;
    at.feedback[1].position = z;
  }
  /// A channel whose program store holds `programs` (MTC200), the first the main program.
  explicit Machine(const std::vector<std::string>& programs) : Machine(programs.at(0)) {
    std::vector<const nc::Program*> store{&parsed.program};
    for (size_t i = 1; i < programs.size(); ++i) {
      more.push_back(
          nc::ParseProgram(programs[i], "p" + std::to_string(i) + ".mtc", nc::Dialect::kMtc200));
      EXPECT_TRUE(more.back().ok());
      store.push_back(&more.back().program);
    }
    channel = std::make_unique<Channel>(channel_config, store);
  }
  // One drive tick of the ideal machine.
  void Tick() {
    channel->Tick(at, mdt);
    Answer();
    t += 250e-6;
  }
  double RunUntilEnd(double limit = 60) {
    while (channel->state() != ChannelState::kEnded && channel->state() != ChannelState::kError &&
           t < limit)
      Tick();
    return t;
  }
  double X() const { return at.feedback[0].position; }
  double Z() const { return at.feedback[1].position; }

  nc::ParseResult parsed;
  std::deque<nc::ParseResult> more;  ///< the store's other programs (stable addresses)
  ChannelConfig channel_config;
  std::unique_ptr<Channel> channel;
  double t = 0;
};

inline void WithOffsetsAndTools(ChannelConfig& c) {
  c.zero_offsets.g54_to_g59[0] = {5, 100};   // G54: X+5, Z+100
  c.zero_offsets.g54_to_g59[1] = {-2, 200};  // G55
  c.tools.edges = {{1, 1, {0, 0}, 0.8, 3}, {2, 1, {1.5, -4}, 0.4, 3}};
}

}  // namespace vmt::control::channel::testing
