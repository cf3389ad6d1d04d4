#include "sim/cli/serve.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "common/json_text.hpp"
#include "common/output_file.hpp"
#include "control/gateway/nc_status_block.hpp"
#include "control/plc/modbus_server.hpp"
#include "sim/cli/serve_modbus.hpp"
#include "sim/runner/runner.hpp"
#include "sim/station/station_session.hpp"

namespace vmt::sim {
namespace {

std::atomic<bool> g_stop{false};

void OnSignal(int) { g_stop = true; }

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size())))];
}

std::string Fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// The real-time PLC link watchdog: a PLC that sends nothing for the timeout is lost. It counts
// PLC cycles, so that the event falls at the simulated time the timeout ends, and it also
// waits for the wall time: after a late stretch the cycles catch up faster than the wall clock
// and the PLC has had no chance to be heard.
struct PlcLinkWatch {
  int64_t timeout_cycles = 1;
  std::chrono::steady_clock::duration timeout{};
  uint64_t seen_requests = 0;  ///< the PLC's writes so far
  int64_t heard_cycle = 0;     ///< cycle before which the last request was seen
  std::chrono::steady_clock::time_point heard_at;
  bool lost = false;
  int losses = 0;
};

/// `option` HOST:PORT as a host and a port (0..65535).
std::pair<std::string, int> HostPort(const std::string& option, const std::string& endpoint) {
  const size_t colon = endpoint.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == endpoint.size())
    throw std::invalid_argument(option + " " + endpoint + ": expected HOST:PORT");
  int port = -1;
  try {
    size_t used = 0;
    port = std::stoi(endpoint.substr(colon + 1), &used);
    if (used != endpoint.size() - colon - 1) port = -1;
  } catch (const std::exception&) {
  }
  if (port < 0 || port > 65535)
    throw std::invalid_argument(option + " " + endpoint + ": the port is not a number 0..65535");
  return {endpoint.substr(0, colon), port};
}

/// Lockstep: the client is the clock, each cycle it writes runs one PLC cycle inside Poll.
/// There is no link watchdog, but a client that vanished must not keep serve waiting for ever.
/// Returns why it stopped.
std::string ServeLockstep(const ServeOptions& o, SceneRun& run, control::plc::ModbusServer& server,
                          const std::function<void()>& drop_if_asked,
                          station::StationSession* station) {
  using Clock = std::chrono::steady_clock;
  const auto idle =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(o.idle_timeout_s));
  const int poll_ms = static_cast<int>(std::clamp(o.idle_timeout_s * 1000, 1.0, 100.0));
  uint64_t cycles = 0;
  auto cycle_at = Clock::now();
  while (!run.done()) {
    if (g_stop) return "signal";
    server.Poll(station ? std::min(poll_ms, 15) : poll_ms);
    drop_if_asked();
    if (station) station->Publish(run, "running");
    const auto now = Clock::now();
    if (server.stats().cycles != cycles) {
      cycles = server.stats().cycles;
      cycle_at = now;
    } else if (now - cycle_at >= idle) {
      return "idle timeout: no cycle written for " + Fmt(o.idle_timeout_s) + " s";
    }
  }
  return "end of scene";
}

/// Real time: each PLC cycle starts at its wall-clock time; between cycles the server answers
/// its clients, never past the next cycle's time (the cycle comes first). `lateness_ms` gets
/// how long after its time each cycle started, `late` the cycles beyond its limit; `link`
/// watches the PLC's requests. Returns why it stopped.
std::string ServeRealtime(const ServeOptions& o, SceneRun& run, control::plc::ModbusServer& server,
                          const std::function<void()>& cycle,
                          const std::function<void()>& drop_if_asked,
                          std::vector<double>& lateness_ms, RealtimeLateness& late,
                          PlcLinkWatch& link, station::StationSession* station) {
  using Clock = std::chrono::steady_clock;
  const auto period = std::chrono::microseconds(run.ticks_per_plc_cycle() * 250);
  const int64_t timeout_us = std::llround(o.plc_timeout_ms * 1000);
  link.timeout_cycles = std::max<int64_t>(1, (timeout_us + period.count() - 1) / period.count());
  link.timeout = std::chrono::microseconds(timeout_us);
  const std::string lost =
      "Modbus: no write from the PLC for " + Fmt(o.plc_timeout_ms) + " ms, the PLC link is lost";
  // The clock starts with the PLC: a PLC started a moment after vmt would otherwise find the NC
  // already in error (the link lost before it ever came).
  if (o.wait_for_plc) {
    std::printf("vmt serve: waiting for the PLC's first write before the clock starts\n");
    std::fflush(stdout);
    while (server.stats().writes == 0) {
      if (g_stop) return "signal";
      server.Poll(50);
      if (station) station->Publish(run, "paused");
    }
  }
  const auto start = Clock::now();
  link.heard_at = start;
  for (int64_t n = 0; !run.done(); ++n) {
    if (g_stop) return "signal";
    const auto due = start + n * period;
    server.ServeUntil(due);
    const auto now = Clock::now();
    lateness_ms.push_back(std::chrono::duration<double, std::milli>(now - due).count());
    late.Note(run, lateness_ms.back());
    // The link watchdog looks at the start of the cycle, where the embedded PLC's scans. The PLC
    // is the client that writes its outputs: monitors that only read keep no dead PLC alive.
    if (server.stats().writes != link.seen_requests) {
      link.seen_requests = server.stats().writes;
      link.heard_cycle = n;
      link.heard_at = now;
      if (link.lost) {
        link.lost = false;
        run.PlcRunning();
        std::fprintf(stderr, "vmt serve: %.4f s: the PLC answers again\n", run.time_s());
      }
    } else if (!link.lost && n - link.heard_cycle >= link.timeout_cycles &&
               now - link.heard_at >= link.timeout) {
      link.lost = true;
      ++link.losses;
      run.PlcLost(lost);
      std::fprintf(stderr, "vmt serve: %.4f s: %s\n", run.time_s(), lost.c_str());
    }
    cycle();
    drop_if_asked();
    if (station) station->Publish(run, "running");
  }
  return "end of scene";
}

/// Without an external PLC the station is the clock: paused, stepped a PLC cycle at a time, or
/// running at the page's real-time factor (0: as fast as the machine allows). Keys and signals
/// are taken at the start of a cycle. Returns why it stopped.
std::string ServeStation(SceneRun& run, station::StationSession& station,
                         const std::function<void()>& cycle) {
  while (!run.done()) {
    if (g_stop) return "signal";
    if (!station.CycleDue(run)) continue;
    cycle();
    station.Published(run);
  }
  return "end of scene";
}

// How the serving loop ended, and what it measured of real time and of the PLC's link.
struct ServeOutcome {
  std::string stop_reason;
  bool stopped_early = false;
  std::vector<double> lateness_ms;
  RealtimeLateness late;
  PlcLinkWatch link;
};

// serve.json: how the serve went, beside the run's own files.
nlohmann::ordered_json ServeJson(const ServeOptions& o, const SceneRun& run, const RunResult& r,
                                 const ServeOutcome& out, const control::plc::ModbusServer* server,
                                 const station::StationSession* station) {
  nlohmann::ordered_json serve = {
      {"scene", run.scene().name},          {"mode", o.lockstep ? "lockstep" : "realtime"},
      {"stopped_early", out.stopped_early}, {"stop_reason", out.stop_reason},
      {"simulated_time_s", run.time_s()},   {"trace_digest", r.trace_digest}};
  if (server) serve["modbus"] = ModbusStatsJson(server->stats());
  if (station)
    serve["station"] = {{"port", station->port()}, {"operator_steps", run.operated().size()}};
  if (server && o.lockstep) {
    serve["idle_timeout_s"] = o.idle_timeout_s;
  } else if (server) {
    serve["cycle_lateness_ms"] = {{"p50", Percentile(out.lateness_ms, 0.5)},
                                  {"p99", Percentile(out.lateness_ms, 0.99)},
                                  {"max", Percentile(out.lateness_ms, 1.0)}};
    out.late.AddTo(serve);
    serve["plc_link"] = {{"timeout_ms", o.plc_timeout_ms},
                         {"timeout_cycles", out.link.timeout_cycles},
                         {"lost", out.link.losses}};
  }
  return serve;
}

// After the loop: serve.json, the console's summary, the station kept up on the ended run
// until Ctrl-C, and the exit code.
int Conclude(const ServeOptions& o, SceneRun& run, const RunResult& r, const ServeOutcome& out,
             const control::plc::ModbusServer* server, station::StationSession* station) {
  std::vector<std::string> write_errors = r.write_errors;
  try {
    if (!o.out_dir.empty())
      common::WriteFileAtomically(
          o.out_dir + "/serve.json",
          ServeJson(o, run, r, out, server, station).dump(2, ' ', false, common::kReplaceBadUtf8) +
              '\n');
  } catch (const common::WriteError& e) {
    write_errors.push_back(e.what());
  }
  std::printf("%s: %.3f s simulated, trace digest %s", run.scene().name.c_str(), run.time_s(),
              r.trace_digest.c_str());
  if (server)
    std::printf(", %llu Modbus requests, %llu exceptions",
                static_cast<unsigned long long>(server->stats().requests_served),
                static_cast<unsigned long long>(server->stats().exceptions_sent));
  std::printf("\n");
  if (server && !o.lockstep)
    std::printf("cycle lateness: p50 %.3f ms, p99 %.3f ms, max %.3f ms\n",
                Percentile(out.lateness_ms, 0.5), Percentile(out.lateness_ms, 0.99),
                Percentile(out.lateness_ms, 1.0));
  for (const std::string& f : r.failures) std::fprintf(stderr, "FAILED: %s\n", f.c_str());
  // Real time not held is a failed run, as a failed expectation is: what the PLC saw was not
  // the machine's timing.
  const bool late_failed = server && !o.lockstep && !out.late.held() && !o.allow_late;
  if (late_failed) std::fprintf(stderr, "FAILED: %s\n", out.late.Failure().c_str());
  if (station && !out.stopped_early) {
    // The page keeps showing the end of the run; what it sends now has no run to act on.
    std::printf("vmt serve: the scene has ended; the operator station stays up until Ctrl-C\n");
    std::fflush(stdout);
    while (!g_stop) {
      station->DropInputs();
      station->Publish(run, "ended", true);
      station->Wait(std::chrono::milliseconds(100));
    }
  }
  for (const std::string& e : write_errors)
    std::fprintf(stderr, "vmt serve: error: %s\n", e.c_str());
  if (out.stopped_early)
    std::fprintf(stderr, "vmt serve: stopped early at %.4f s: %s\n", run.time_s(),
                 out.stop_reason.c_str());
  if (!write_errors.empty()) return 2;  // a lost file outweighs an early stop
  if (out.stopped_early) return kServeStoppedEarly;
  return r.ok() && !late_failed ? 0 : 1;
}

station::StationServerOptions StationServerOptionsOf(const ServeOptions& o) {
  station::StationServerOptions http;
  std::tie(http.host, http.port) = HostPort("--http", o.http);
  http.token = o.http_token;
  http.web_dir = station::DefaultWebDir();
  return http;
}

void CheckTimeouts(const ServeOptions& o) {
  if (!(o.plc_timeout_ms > 0) || o.plc_timeout_ms > 3.6e6)
    throw std::invalid_argument("--plc-timeout " + Fmt(o.plc_timeout_ms) +
                                ": expected milliseconds, > 0 and at most an hour");
  if (!(o.idle_timeout_s > 0) || o.idle_timeout_s > 8.64e4)
    throw std::invalid_argument("--idle-timeout " + Fmt(o.idle_timeout_s) +
                                ": expected seconds, > 0 and at most a day");
}

// Where the external PLC finds the server and its blocks, on standard output.
void AnnounceModbus(const std::string& scene, const control::plc::ModbusServerOptions& mb, int port,
                    bool lockstep, int64_t ticks) {
  std::printf("vmt serve: %s, Modbus TCP on %s, %s", scene.c_str(),
              ModbusEndpointText(mb, port).c_str(), lockstep ? "lockstep" : "real time");
  if (lockstep)
    std::printf(" (write cycle n+1 to holding register %d to run a PLC cycle of %.1f ms)",
                *mb.cycle_register, ticks * 0.25);
  std::printf("; AXD_WR block at holding register %d", *mb.axd_wr_register);
  std::printf("; NC status block at input register %d", *mb.status_register);
  std::printf("\n");
}

}  // namespace

int Serve(const ServeOptions& o) {
  if (!o.modbus && o.http.empty())
    throw std::invalid_argument("vmt serve needs --modbus, --http or both");
  control::plc::ModbusServerOptions mb;
  if (o.modbus) mb = ModbusServerOptionsOf(o);
  station::StationServerOptions http;
  if (!o.http.empty()) http = StationServerOptionsOf(o);
  CheckTimeouts(o);

  const Scene scene = LoadScene(o.scene);
  std::unique_ptr<station::StationSession> station;
  if (!o.http.empty()) station = std::make_unique<station::StationSession>();
  RunOptions run_options;
  run_options.external_plc = o.modbus;
  // The fault step runs inside a cycle, which in lockstep runs inside Poll: the connections are
  // dropped once that Poll has returned.
  bool drop_clients = false;
  run_options.on_plc_client_gone = [&drop_clients] { drop_clients = true; };
  if (station)
    run_options.on_event = [s = station.get()](const nlohmann::ordered_json& e) { s->Event(e); };
  run_options.out_dir = o.out_dir;
  if (o.until_s > 0) run_options.until_s = o.until_s;
  // Against the wall clock a picture (tens of ms) would make several PLC cycles late.
  run_options.snapshots_after_run = !o.lockstep || (station && !o.modbus);
  SceneRun run(scene, run_options);
  // The station's server threads read the run (its signal checks): they stop before it goes.
  struct StationStop {
    std::unique_ptr<station::StationSession>& session;
    ~StationStop() { session.reset(); }
  } station_stop{station};
  control::gateway::SignalImage* image = run.image();
  if (o.modbus && !image)
    throw std::invalid_argument(o.scene + ": vmt serve --modbus needs a scene with an nc: section");
  const int64_t ticks = run.ticks_per_plc_cycle();
  std::unique_ptr<control::plc::ModbusServer> server;
  // The NC status block (read only): refreshed after every cycle, so what a client reads
  // between two cycles is the state the last one left.
  control::gateway::NcStatusLayout nc_status;
  std::vector<uint16_t> nc_status_words;
  const auto refresh_nc_status = [&] {
    if (!server || !run.channel()) return;
    control::gateway::EncodeNcStatus(
        nc_status,
        control::gateway::NcStatusOf(nc_status, *run.channel(), run.feedback(), run.time_s()),
        nc_status_words);
    server->SetStatus(nc_status_words);
  };
  // The station's keys and signals are taken at the start of a PLC cycle.
  const std::function<void()> cycle = [&] {
    if (station) station->TakeInputs(run);
    for (int64_t k = 0; k < ticks && !run.done(); ++k) run.Step();
    refresh_nc_status();
  };
  if (o.modbus) {
    if (o.lockstep) {
      mb.cycle_register = control::gateway::LockstepCycleRegister(image->table());
      mb.on_cycle = [&](uint32_t) { cycle(); };
    }
    // AXD_WR (fast-measurement 7.2): the external PLC writes drive parameters the way the
    // embedded one does, through the Modbus AXD_WR block (modbus_server.hpp), in lockstep and
    // real time.
    mb.axd_wr_register = control::gateway::AxdWrRegister(image->table());
    mb.axd_wr = [&run](int axis, int ident, int64_t value) {
      return run.AxdWrite(axis, ident, value);
    };
    nc_status = control::gateway::NcStatusLayoutOf(image->table());
    nc_status_words.assign(static_cast<size_t>(nc_status.count()), 0);
    mb.status_register = nc_status.address;
    mb.status_count = nc_status.count();
    server = std::make_unique<control::plc::ModbusServer>(*image, mb);
    refresh_nc_status();
    WarnIfRemote(*server, mb);
    AnnounceModbus(scene.name, mb, server->port(), o.lockstep, ticks);
  }
  if (station) {
    const std::string pace = o.modbus ? (o.lockstep ? "external PLC, lockstep" : "real time")
                                      : (o.lockstep ? "lockstep" : "real time");
    // The external PLC is the lockstep clock and keeps the real-time link alive: the page
    // watches and operates, but does not pause it.
    const std::string refused =
        o.modbus ? "the PLC over Modbus runs the clock: the page cannot pause or step it" : "";
    station->control().running = !o.modbus && !o.lockstep;
    station->Open(run, http, pace, refused);
    std::printf("vmt serve: %s, operator station on http://%s:%d/ (%s)\n", scene.name.c_str(),
                http.host.c_str(), station->port(), pace.c_str());
  }
  std::fflush(stdout);

  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  const std::function<void()> drop_if_asked = [&] {
    if (!drop_clients) return;
    drop_clients = false;
    if (server) server->DropClients();
    std::fprintf(stderr, "vmt serve: %.4f s: fault: every Modbus client dropped\n", run.time_s());
  };
  ServeOutcome out;
  out.late.limit_ms = o.late_limit_ms;
  out.stop_reason = !server ? ServeStation(run, *station, cycle)
                    : o.lockstep
                        ? ServeLockstep(o, run, *server, drop_if_asked, station.get())
                        : ServeRealtime(o, run, *server, cycle, drop_if_asked, out.lateness_ms,
                                        out.late, out.link, station.get());
  out.stopped_early = !run.done();  // Finish makes the tick it is at the run's last
  return Conclude(o, run, run.Finish(out.stop_reason), out, server.get(), station.get());
}

}  // namespace vmt::sim
