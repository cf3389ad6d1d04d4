#pragma once
// vmt serve: a scene with its PLC outside, over Modbus TCP. In lockstep the external PLC steps
// the simulation one PLC cycle per write of the cycle register; in real time the simulation
// runs against the wall clock and reports how late its cycles were.
//
// A PLC that goes away is met as on the machine. In real time the NC watches the link: a PLC
// that sends no request (read or write, any client) for plc_timeout_ms is lost (SceneRun::
// PlcLost: its outputs drop, the NC stops with message 505, an event records it); a client
// that answers again later is recorded as the PLC running again. In lockstep the PLC is the
// clock, so nothing runs without it: after idle_timeout_s of wall time without a cycle write
// serve stops early, writes everything computed so far and exits with kServeStoppedEarly.
// The scene's `fault: {plc: client_gone}` step disconnects every Modbus client.
//
// With --http the operator station (sim/station/) serves a web page beside the run: the page
// presses keys and writes signals at the start of a PLC cycle, and without an external PLC it
// is the clock (run at a real-time factor, pause, step). At the scene's end the station stays
// up, showing the final state, until SIGINT or SIGTERM.

#include <string>
#include <vector>

namespace vmt::sim {

/// Exit code of a serve that stopped before the scene's end: the lockstep idle timeout, or
/// SIGINT / SIGTERM. (0: the run ended and passed; 1: it ended with failures; 2: bad input.)
inline constexpr int kServeStoppedEarly = 3;

struct ServeOptions {
  std::string scene;
  /// Serve the signal image over Modbus TCP at `endpoint` to an external PLC. Without it the
  /// scene's own PLC program (plc:) runs, and the operator station is the clock.
  bool modbus = true;
  std::string endpoint = "127.0.0.1:5020";  ///< HOST:PORT; port 0 picks a free one
  /// HOST:PORT of the operator station (docs/station.md); empty: none. Port 0 picks a free one.
  std::string http;
  std::string http_token;                   ///< required for an address other than loopback
  bool lockstep = true;                     ///< else real time
  double until_s = 0;                       ///< 0: the scene's duration
  std::string out_dir = "out";
  /// Real time: the PLC link's timeout, as a field bus's (ms, > 0): no write from the PLC for
  /// that long (a reading monitor does not count). Checked in whole PLC cycles (rounded up) and
  /// against the wall clock, so a late cycle does not trip it.
  double plc_timeout_ms = 100;
  /// Real time with Modbus: the clock starts at the PLC's first write, not at once.
  bool wait_for_plc = true;
  /// Lockstep: wall time without a cycle write after which serve stops early (s, > 0).
  double idle_timeout_s = 30;
  /// The Modbus unit id answered besides 0 and 255 (1..247); others get exception 0B.
  int unit_id = 1;
  /// A Modbus connection that sends no request for this long is closed (s, 0: never).
  double client_timeout_s = 30;
  /// --modbus on an address other than loopback needs it (a warning is printed).
  bool allow_remote = false;
  /// With allow_remote: the client addresses that may connect besides loopback; empty: any.
  std::vector<std::string> allow_clients;
  /// Real time: a cycle that starts later than this after its time is late (ms, > 0); a run
  /// with a late cycle fails (exit 1) unless allow_late.
  double late_limit_ms = 50;
  bool allow_late = false;
};

/// Serves until the scene's end; returns the exit code (0 ok, 1 failed expectations or, in real
/// time, a cycle later than late_limit_ms without allow_late, kServeStoppedEarly). Writes
/// serve.json beside the run's files: mode, stopped_early, stop_reason ("end of scene",
/// "signal", "idle timeout: no cycle written for 30 s"), Modbus counts, and in real time the
/// cycle lateness, whether real time was held and the PLC link's losses. Throws on bad input
/// (scene, endpoint, timeouts) and when it cannot listen.
int Serve(const ServeOptions& options);

}  // namespace vmt::sim
