#pragma once
// vmt serve's Modbus side: the server's options from serve's (endpoint, unit id, timeouts, who
// may connect), the warning for a server reachable from the network, the counts serve.json
// reports, and real time's record of late cycles (docs/plc.md, docs/cli.md).

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "control/plc/modbus_server.hpp"
#include "sim/cli/serve.hpp"
#include "sim/runner/runner.hpp"

namespace vmt::sim {

/// The Modbus server's options for `o`: --modbus HOST:PORT (an IPv6 address in brackets,
/// [::1]:5020), --unit-id, --client-timeout, --allow-remote, --allow-client; in real time the
/// PLC role passes on after --plc-timeout without a write. Throws std::invalid_argument naming
/// the option and its allowed range.
control::plc::ModbusServerOptions ModbusServerOptionsOf(const ServeOptions& o);

/// "127.0.0.1:5020", "[::1]:5020", "*:5020" (every address).
std::string ModbusEndpointText(const control::plc::ModbusServerOptions& mb, int port);

/// Prints to stderr that clients on the network may connect (and which) when `server` listens
/// off loopback.
void WarnIfRemote(const control::plc::ModbusServer& server,
                  const control::plc::ModbusServerOptions& mb);

/// serve.json's "modbus" object.
nlohmann::ordered_json ModbusStatsJson(const control::plc::ModbusServer::Stats& st);

/// Real time held or not: a cycle that starts more than limit_ms after its time is late. The
/// first late cycle of a stretch records {"event":"realtime","state":"late","late_ms",
/// "limit_ms"}, the first on time after it {"event":"realtime","state":"on_time",
/// "late_ms_max"} (events.jsonl).
struct RealtimeLateness {
  double limit_ms = 50;
  int64_t late_cycles = 0;
  int stretches = 0;
  bool late = false;
  double stretch_max_ms = 0;
  double max_ms = 0;

  void Note(SceneRun& run, double late_ms);
  bool held() const { return late_cycles == 0; }
  /// "real time not held: 12 cycles more than 50 ms late (max 73.2 ms)".
  std::string Failure() const;
  /// Adds limit_ms, late_cycles, late_stretches to serve.json's "cycle_lateness_ms" and
  /// "realtime_held".
  void AddTo(nlohmann::ordered_json& serve) const;
};

}  // namespace vmt::sim
