#include "sim/cli/serve_modbus.hpp"

#include <arpa/inet.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace vmt::sim {
namespace {

// A numeric address other than loopback (a name is resolved, and checked, by the server).
bool NumericRemote(const std::string& host) {
  in_addr v4{};
  in6_addr v6{};
  if (inet_pton(AF_INET, host.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) != 127;
  if (inet_pton(AF_INET6, host.c_str(), &v6) == 1) return !IN6_IS_ADDR_LOOPBACK(&v6);
  return false;
}

std::string Fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

control::plc::ModbusServerOptions ModbusServerOptionsOf(const ServeOptions& o) {
  control::plc::ModbusServerOptions mb;
  const std::string& e = o.endpoint;
  const size_t colon = e.rfind(':');
  std::string host = colon == std::string::npos ? "" : e.substr(0, colon);
  // [::1]:5020: the brackets keep an IPv6 address's colons apart from the port's.
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']')
    host = host.substr(1, host.size() - 2);
  int port = -1;
  if (colon != std::string::npos && !host.empty() && colon + 1 < e.size()) {
    try {
      size_t used = 0;
      port = std::stoi(e.substr(colon + 1), &used);
      if (used != e.size() - colon - 1) port = -1;
    } catch (const std::exception&) {
    }
  } else {
    throw std::invalid_argument("--modbus " + e + ": expected HOST:PORT ([ADDRESS]:PORT for IPv6)");
  }
  if (port < 0 || port > 65535)
    throw std::invalid_argument("--modbus " + e + ": the port is not a number 0..65535");
  mb.host = host;
  mb.port = port;
  if (o.unit_id < 1 || o.unit_id > 247)
    throw std::invalid_argument("--unit-id " + std::to_string(o.unit_id) + ": expected 1..247");
  mb.unit_id = o.unit_id;
  if (!(o.client_timeout_s >= 0) || o.client_timeout_s > 8.64e4)
    throw std::invalid_argument("--client-timeout " + Fmt(o.client_timeout_s) +
                                ": expected seconds, 0 (never) up to a day");
  mb.client_timeout_ms = static_cast<int>(std::ceil(o.client_timeout_s * 1000));
  if (!(o.late_limit_ms > 0) || o.late_limit_ms > 3.6e6)
    throw std::invalid_argument("--late-limit " + Fmt(o.late_limit_ms) +
                                ": expected milliseconds, > 0 and at most an hour");
  // In real time a PLC that has written nothing for the link timeout is lost: a reconnecting
  // PLC may then write while its old connection still looks open.
  if (!o.lockstep) mb.plc_role_timeout_ms = static_cast<int>(std::ceil(o.plc_timeout_ms));
  if (NumericRemote(host) && !o.allow_remote)
    throw std::invalid_argument("--modbus " + e +
                                ": not a loopback address, clients on the network could connect "
                                "and write; give --allow-remote (and --allow-client ADDR)");
  mb.allow_remote = o.allow_remote;
  if (!o.allow_clients.empty() && !o.allow_remote)
    throw std::invalid_argument(
        "--allow-client needs --allow-remote (loopback clients may always "
        "connect)");
  mb.allowed_clients = o.allow_clients;
  return mb;
}

std::string ModbusEndpointText(const control::plc::ModbusServerOptions& mb, int port) {
  const std::string h = mb.host.empty() ? "*" : mb.host;
  if (h.find(':') != std::string::npos) return "[" + h + "]:" + std::to_string(port);
  return h + ":" + std::to_string(port);
}

void WarnIfRemote(const control::plc::ModbusServer& server,
                  const control::plc::ModbusServerOptions& mb) {
  if (!server.remote()) return;
  std::string who = "any address";
  if (!mb.allowed_clients.empty()) {
    who.clear();
    for (const std::string& a : mb.allowed_clients) who += (who.empty() ? "" : ", ") + a;
  }
  std::fprintf(stderr,
               "vmt serve: warning: Modbus on %s is reachable from the network; clients from %s "
               "(and loopback) may connect, the first to write is the PLC\n",
               ModbusEndpointText(mb, server.port()).c_str(), who.c_str());
}

nlohmann::ordered_json ModbusStatsJson(const control::plc::ModbusServer::Stats& st) {
  return {{"requests", st.requests_served},
          {"exceptions", st.exceptions_sent},
          {"clients_accepted", st.clients_accepted},
          {"clients_dropped", st.clients_dropped},
          {"clients_refused", st.clients_refused},
          {"clients_not_allowed", st.clients_not_allowed},
          {"clients_evicted", st.clients_evicted},
          {"clients_timed_out", st.clients_timed_out},
          {"writes_refused", st.writes_refused},
          {"wrong_unit", st.wrong_unit},
          {"cycles", st.cycles}};
}

void RealtimeLateness::Note(SceneRun& run, double late_ms) {
  max_ms = std::max(max_ms, late_ms);
  if (late_ms > limit_ms) {
    ++late_cycles;
    stretch_max_ms = std::max(stretch_max_ms, late_ms);
    if (late) return;
    late = true;
    ++stretches;
    stretch_max_ms = late_ms;
    run.RecordEvent(
        {{"event", "realtime"}, {"state", "late"}, {"late_ms", late_ms}, {"limit_ms", limit_ms}});
    std::fprintf(stderr, "vmt serve: %.4f s: a cycle started %.1f ms late (limit %g ms)\n",
                 run.time_s(), late_ms, limit_ms);
  } else if (late) {
    late = false;
    run.RecordEvent({{"event", "realtime"}, {"state", "on_time"}, {"late_ms_max", stretch_max_ms}});
  }
}

std::string RealtimeLateness::Failure() const {
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "real time not held: %lld cycles more than %g ms late (max %.1f ms)",
                static_cast<long long>(late_cycles), limit_ms, max_ms);
  return buf;
}

void RealtimeLateness::AddTo(nlohmann::ordered_json& serve) const {
  nlohmann::ordered_json& l = serve["cycle_lateness_ms"];
  l["limit"] = limit_ms;
  l["late_cycles"] = late_cycles;
  l["late_stretches"] = stretches;
  serve["realtime_held"] = held();
}

}  // namespace vmt::sim
