#pragma once
// The operator station beside one serve run: it collects the run's events, starts the HTTP
// server once the run exists, takes the page's inputs at the start of a PLC cycle (keys and
// signals through SceneRun::Operate, run control for the serve loop) and publishes frames at
// most 60 times a second of wall time, so that streaming costs the simulation little.

#include <chrono>
#include <deque>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sim/runner/runner.hpp"
#include "sim/station/station_frames.hpp"
#include "sim/station/station_hub.hpp"
#include "sim/station/station_server.hpp"

namespace vmt::sim::station {

/// What the page asked of the serve loop's clock.
struct RunControl {
  bool running = false;
  std::optional<double> seek;  ///< a replay: go to this simulated time (s)
  double speed = 1;      ///< real-time factor while running; 0: as fast as the machine allows
  int64_t steps = 0;     ///< PLC cycles to run while paused
  bool changed = false;  ///< running or speed changed since the last TakeInputs: re-anchor
};

class StationSession {
 public:
  /// Before the run: `Event` must be the run's RunOptions::on_event (or called by it).
  StationSession() = default;
  void Event(const nlohmann::ordered_json& event);
  /// Starts serving `run` (model, keys, signals). `pace` is shown on the page; a non-empty
  /// `run_control_refused` answers the page's run control with 409.
  void Open(SceneRun& run, StationServerOptions options, const std::string& pace,
            const std::string& run_control_refused);
  int port() const { return server_ ? server_->port() : 0; }

  /// Takes the queued inputs: keys and signals are set now (at the start of the PLC cycle the
  /// run is at), run control goes to control(). A refused one is printed, never thrown. A
  /// signal changes at most once a cycle: a press and its release in one batch (a quick click,
  /// or a click while paused) are taken a cycle apart, so the PLC sees the key; what follows
  /// waits for the next cycle, in order.
  void TakeInputs(SceneRun& run);
  RunControl& control() { return control_; }
  /// Publishes the state (and the signals, if a page watches them) when a page has asked for
  /// one lately and a 60th of a second has passed since the last, or at once with `force`. `state`:
  /// "running", "paused", "ended".
  void Publish(SceneRun& run, const std::string& state, bool force = false);
  void Wait(std::chrono::milliseconds timeout) { hub_.WaitForInput(timeout); }
  /// The station as the run's clock: takes the inputs, and returns true when a PLC cycle is due
  /// now (a step asked for, or running and its wall time at the real-time factor has come).
  /// Otherwise it publishes, waits at most 20 ms for an input and returns false.
  bool CycleDue(SceneRun& run);
  /// After a cycle that CycleDue allowed: publishes (at once after a step).
  void Published(SceneRun& run);
  /// Marks from a run's events without listing the events (a replay lists the recorded ones).
  void Mark(const nlohmann::ordered_json& event) { marks_.Note(event); }
  void ClearMarks() { marks_ = {}; }
  /// Lists an event recorded earlier (a replay's events.jsonl line).
  void Listed(std::string json) {
    ++events_;
    hub_.AddEvent(std::move(json));
  }
  /// Discards what the pages sent (the run has ended: nothing to act on).
  void DropInputs() {
    hub_.TakeInputs();
    waiting_.clear();
  }

 private:
  StationHub hub_;
  std::deque<StationInput> waiting_;  ///< taken from the hub, due at a later cycle
  std::vector<std::string> changed_;  ///< signals set at tick changed_tick_
  int64_t changed_tick_ = -1;
  StationMarks marks_;
  size_t events_ = 0;
  RunControl control_;
  std::unique_ptr<StationServer> server_;
  std::chrono::steady_clock::time_point published_{}, signals_published_{};
  std::chrono::steady_clock::time_point anchor_{};  ///< wall time of anchor_tick_ while running
  int64_t anchor_tick_ = 0;
  int64_t stock_published_ = -1;  ///< the turned stock's version the hub has
  std::chrono::steady_clock::time_point stock_at_{};
};

}  // namespace vmt::sim::station
