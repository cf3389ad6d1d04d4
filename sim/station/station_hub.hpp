#pragma once
// What the simulation and the operator station's HTTP threads exchange. The simulation publishes
// its latest frame (state, signals) and its events, and takes the station's inputs at the start
// of a PLC cycle. It never waits for a browser: a frame replaces the one before (a slow page
// skips frames), events are kept up to a bound, and inputs wait in a bounded queue.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace vmt::sim::station {

/// One request of a page: a key or signal value (`signal`, `value`), a handwheel's turn
/// (`signal` the axis, `value` the counts), or run control.
struct StationInput {
  enum class Kind { kSignal, kHandwheel, kRun, kPause, kStep, kSeek };
  Kind kind = Kind::kSignal;
  std::string signal;
  double value = 0;
};

class StationHub {
 public:
  static constexpr size_t kMaxInputs = 256;      ///< queued inputs; beyond, requests get 429
  static constexpr size_t kMaxEvents = 200'000;  ///< kept events; the oldest are dropped
  static constexpr size_t kMaxEventsPerAnswer = 1000;

  // The simulation's side.
  void PublishState(std::string json);
  void PublishSignals(std::string json);
  void PublishStock(std::string json);
  /// A page has asked for the state (the signals) within the last two seconds: worth building.
  bool StateWanted() const;
  bool SignalsWanted() const;
  void AddEvent(std::string json);
  std::vector<StationInput> TakeInputs();
  /// Returns once an input is queued or `timeout` has passed (a paused run idles here).
  void WaitForInput(std::chrono::milliseconds timeout);

  // The HTTP threads' side.
  std::string State() const;
  std::string Signals();
  std::string Stock() const;
  /// {"total": N, "first": F, "events": [...]}: events from number `from` on (0-based over the
  /// run; `first` is the oldest still kept), at most kMaxEventsPerAnswer.
  std::string Events(size_t from) const;
  /// False, and nothing queued, when kMaxInputs are waiting.
  bool Push(StationInput input);

 private:
  mutable std::mutex mutex_;
  std::condition_variable input_queued_;
  std::shared_ptr<const std::string> state_, signals_, stock_;
  mutable std::chrono::steady_clock::time_point state_asked_{};
  std::chrono::steady_clock::time_point signals_asked_{};
  std::deque<std::string> events_;
  size_t events_dropped_ = 0;
  std::deque<StationInput> inputs_;
};

}  // namespace vmt::sim::station
