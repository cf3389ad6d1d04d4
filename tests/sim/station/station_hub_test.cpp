// The hub between the simulation and the station's HTTP threads: the latest frame wins, the
// input queue and the event list are bounded, and events are handed out in pages from any
// number on.

#include "sim/station/station_hub.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <thread>

namespace vmt::sim::station {
namespace {

TEST(StationHubTest, TheLatestFrameWins) {
  StationHub hub;
  EXPECT_FALSE(hub.StateWanted());
  EXPECT_EQ(hub.State(), "{}");
  EXPECT_TRUE(hub.StateWanted());
  hub.PublishState(R"({"t":1})");
  hub.PublishState(R"({"t":2})");
  EXPECT_EQ(hub.State(), R"({"t":2})");
}

TEST(StationHubTest, SignalsAreBuiltOnlyWhileAPageAsksForThem) {
  StationHub hub;
  EXPECT_FALSE(hub.SignalsWanted());
  EXPECT_EQ(hub.Signals(), R"({"signals":[]})");
  EXPECT_TRUE(hub.SignalsWanted());
}

TEST(StationHubTest, InputsAreBoundedAndTakenInOrder) {
  StationHub hub;
  for (size_t i = 0; i < StationHub::kMaxInputs; ++i)
    ASSERT_TRUE(hub.Push({StationInput::Kind::kSignal, "k", static_cast<double>(i)}));
  EXPECT_FALSE(hub.Push({StationInput::Kind::kSignal, "k", -1}));
  const std::vector<StationInput> taken = hub.TakeInputs();
  ASSERT_EQ(taken.size(), StationHub::kMaxInputs);
  EXPECT_EQ(taken.front().value, 0);
  EXPECT_EQ(taken.back().value, StationHub::kMaxInputs - 1.0);
  EXPECT_TRUE(hub.TakeInputs().empty());
}

TEST(StationHubTest, AWaitEndsWhenAnInputArrives) {
  StationHub hub;
  std::thread page([&] { hub.Push({StationInput::Kind::kStep, "", 0}); });
  hub.WaitForInput(std::chrono::seconds(30));  // returns at the push, not after 30 s
  page.join();
  EXPECT_EQ(hub.TakeInputs().size(), 1u);
}

TEST(StationHubTest, EventsComeInPagesAndTheOldestAreDropped) {
  StationHub hub;
  for (int i = 0; i < 2500; ++i) hub.AddEvent(R"({"n":)" + std::to_string(i) + "}");
  nlohmann::json page = nlohmann::json::parse(hub.Events(0));
  EXPECT_EQ(page["total"], 2500);
  EXPECT_EQ(page["first"], 0);
  ASSERT_EQ(page["events"].size(), StationHub::kMaxEventsPerAnswer);
  EXPECT_EQ(page["events"][0]["n"], 0);
  page = nlohmann::json::parse(hub.Events(2400));
  ASSERT_EQ(page["events"].size(), 100u);
  EXPECT_EQ(page["events"][99]["n"], 2499);
  EXPECT_EQ(nlohmann::json::parse(hub.Events(99999))["events"].size(), 0u);

  StationHub full;
  for (size_t i = 0; i < StationHub::kMaxEvents + 5; ++i) full.AddEvent(std::to_string(i));
  page = nlohmann::json::parse(full.Events(0));
  EXPECT_EQ(page["first"], 5);
  EXPECT_EQ(page["events"][0], 5);  // the oldest kept
}

}  // namespace
}  // namespace vmt::sim::station
