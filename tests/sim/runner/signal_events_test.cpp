// A run that writes no events.jsonl may ask for the events of a few signals only (a study's
// case reads the NC's message number): the other events, the chosen signals' events and the
// trace stay as in the full run; no other signal makes an event.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <vector>

#include "../sim_test_support.hpp"
#include "sim/runner/runner.hpp"

namespace vmt::sim {
namespace {

using testing::SourcePath;

struct Events {
  std::vector<nlohmann::ordered_json> signals, others;
  std::string digest;
};

Events RunWith(const Scene& scene, std::function<bool(const std::string&)> signal_events,
               const std::string& out_dir = "") {
  Events got;
  RunOptions options;
  options.backend = BackendKind::kKinematic;
  options.snapshots = false;
  options.out_dir = out_dir;
  options.signal_events = std::move(signal_events);
  options.on_event = [&](const nlohmann::ordered_json& e) {
    (e.value("event", "") == "signal" ? got.signals : got.others).push_back(e);
  };
  got.digest = RunScene(scene, options).trace_digest;
  return got;
}

bool Moving(const std::string& name) { return name.ends_with("S.MVPOS"); }

TEST(SignalEvents, OnlyTheChosenSignalsMakeEventsAndNothingElseChanges) {
  const Scene scene = LoadScene(SourcePath("scenes/jog.yaml"));
  const Events all = RunWith(scene, {});
  const Events some = RunWith(scene, Moving);
  std::vector<nlohmann::ordered_json> moving;
  for (const auto& e : all.signals)
    if (Moving(e["name"])) moving.push_back(e);
  ASSERT_FALSE(moving.empty());
  EXPECT_GT(all.signals.size(), moving.size());
  EXPECT_EQ(some.signals, moving);
  EXPECT_EQ(some.others, all.others);
  EXPECT_EQ(some.digest, all.digest);
}

TEST(SignalEvents, ARunThatWritesItsEventsWritesThemAll) {
  const Scene scene = LoadScene(SourcePath("scenes/jog.yaml"));
  const std::string dir = testing::OutputDir("signal_events_written");
  const Events all = RunWith(scene, {});
  const Events written = RunWith(scene, Moving, dir);
  EXPECT_EQ(written.signals, all.signals);
  EXPECT_EQ(written.others, all.others);
}

}  // namespace
}  // namespace vmt::sim
