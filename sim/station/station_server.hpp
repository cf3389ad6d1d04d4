#pragma once
// The operator station's HTTP server (cpp-httplib, Debian's libcpp-httplib-dev: one header, a
// thread pool, static files and JSON routes, no event loop to integrate with the simulation's).
// It serves the page from web/, three.js and Chart.js from Debian's packages, and the JSON API
// of docs/station.md from a StationHub. Its threads read frames and queue inputs; they never
// touch the run.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sim/station/station_hub.hpp"

namespace vmt::sim::station {

struct StationServerOptions {
  std::string host = "127.0.0.1";
  int port = 8080;  ///< 0 picks a free one
  /// Required when `host` is not a loopback address: every request then carries it as
  /// "Authorization: Bearer TOKEN" or "?token=TOKEN".
  std::string token;
  std::string web_dir;  ///< the page's files
  std::string three_dir = "/usr/share/javascript/three";
  std::string chart_dir = "/usr/share/javascript/chart.js";
  std::string model_json;         ///< GET /api/model
  std::vector<std::string> keys;  ///< the machine keys POST /api/key accepts
  std::vector<std::string> handwheel_axes;  ///< the axes POST /api/handwheel accepts
  /// Why the page may not set `signal` to `value`, or "" (checked before anything is queued).
  std::function<std::string(const std::string& signal, double value)> check_signal;
  /// Why the page may not pause, run or step, or "" (an external PLC is the lockstep clock).
  std::string run_control_refused;
  /// Why the page may not press keys, or "" (a replay is watched, not operated).
  std::string operate_refused;
  /// POST /api/run {"action": "seek", "t": s} goes to a time (a replay).
  bool seekable = false;
};

class StationServer {
 public:
  /// Binds and starts serving. Throws std::runtime_error when the address cannot be bound,
  /// std::invalid_argument for a non-loopback host without a token or a missing web_dir.
  StationServer(StationHub& hub, StationServerOptions options);
  ~StationServer();
  StationServer(const StationServer&) = delete;
  StationServer& operator=(const StationServer&) = delete;
  int port() const { return port_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int port_ = 0;
};

/// True for 127.0.0.0/8, ::1 and "localhost".
bool IsLoopback(const std::string& host);

/// Where the page's files are: $VMT_WEB_DIR, else web/ of the source tree vmt was built from,
/// else share/vmt/web beside the executable's prefix.
std::string DefaultWebDir();

}  // namespace vmt::sim::station
