// The recorder writes a signal event, built without its JSON object, as the same line Event
// writes for it, and hands it only to the observers that take signal events.
#include "sim/runner/run_recorder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

struct SignalCase {
  double t;
  std::string name;
  double value;
};

const std::vector<SignalCase> kCases = {
    {0.0, "P00S.RUN", 1},
    {3.4995000000000003, "A04S.MVNEG", 0},
    {1234.56725, "P00.distance_from_program_start", 12345.678901234567},
    {7.25, "quote\" back\\slash", -1e-7},
    {7.5, "bad \xff utf8", 1e21},
    {8.0, "P00.nan", std::numeric_limits<double>::quiet_NaN()},
    {9.0, "P00.tiny", 5e-324},
};

std::vector<std::string> Lines(const std::string& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(RunRecorder, ASignalEventIsTheLineEventWrites) {
  const std::string by_event = testing::OutputDir("run_recorder_event");
  const std::string by_signal = testing::OutputDir("run_recorder_signal");
  RunRecorder a, b;
  a.Open(by_event);
  b.Open(by_signal);
  for (const SignalCase& c : kCases) {
    a.Event({{"t", c.t}, {"event", "signal"}, {"name", c.name}, {"value", c.value}});
    b.Signal(c.t, c.name, c.value);
  }
  a.Close();
  b.Close();
  const std::vector<std::string> expected = Lines(by_event + "/events.jsonl");
  ASSERT_EQ(expected.size(), kCases.size());
  EXPECT_EQ(Lines(by_signal + "/events.jsonl"), expected);
}

TEST(RunRecorder, SignalEventsGoOnlyToTheObserversThatTakeThem) {
  // As text: a NaN is not equal to itself.
  auto text = [](const nlohmann::ordered_json& e) {
    return e.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  };
  RunRecorder recorder;
  std::vector<std::string> all, others, by_event;
  recorder.AddObserver([&](const nlohmann::ordered_json& e) { all.push_back(text(e)); });
  recorder.AddObserver([&](const nlohmann::ordered_json& e) { others.push_back(text(e)); },
                       false);
  RunRecorder reference;
  reference.AddObserver([&](const nlohmann::ordered_json& e) { by_event.push_back(text(e)); });
  for (const SignalCase& c : kCases) {
    recorder.Signal(c.t, c.name, c.value);
    reference.Event({{"t", c.t}, {"event", "signal"}, {"name", c.name}, {"value", c.value}});
  }
  recorder.Event({{"t", 1.0}, {"event", "nc"}, {"state", "running"}});
  ASSERT_EQ(all.size(), kCases.size() + 1);
  EXPECT_EQ(std::vector<std::string>(all.begin(), all.end() - 1), by_event);
  ASSERT_EQ(others.size(), 1u);
  EXPECT_EQ(others[0], all.back());
}

}  // namespace
}  // namespace vmt::sim
