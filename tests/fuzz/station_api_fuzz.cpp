// libFuzzer target for the operator station's HTTP API: any bytes as what a browser sends on
// one connection (requests one after another, keep-alive), answered by the station's routes
// (sim/station/station_routes.hpp) in memory, with no socket or thread. Every request gets an
// answer or closes the connection; no handler throws (httplib would answer with the exception's
// raw text); never a crash, a sanitizer report or a hang.
//
// Each input goes to two stations: an open one (loopback, a replay that seeks, keys and signals
// allowed) and a guarded one (a token, run control and operating refused), so that both the
// token check and the refusals are reached.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

#include "sim/station/station_hub.hpp"
#include "sim/station/station_routes.hpp"
#include "tests/sim/station/in_memory_http.hpp"

namespace {

using vmt::sim::station::StationHub;
using vmt::sim::station::StationServerOptions;
using vmt::sim::station::testing::InMemoryHttp;

// A run's frames and a few events, as a page finds them.
void Publish(StationHub& hub) {
  hub.PublishState(R"({"t":1.25,"state":"running","axes":{"X":150,"Z":300}})");
  hub.PublishSignals(R"({"P00C.FOVR":100,"P00C.START":false})");
  hub.PublishStock(R"({"version":1,"profile":[[0,30],[160,30]]})");
  for (int i = 0; i < 3; ++i)
    hub.AddEvent(R"({"t":0.5,"event":"nc_line","line":)" + std::to_string(i + 1) + "}");
}

StationServerOptions Options(bool guarded) {
  StationServerOptions o;
  o.web_dir = VMT_SOURCE_DIR "/web";
  o.model_json = R"({"name":"lathe-c1"})";
  o.keys = {"CYCLE_START", "FEED_HOLD", "RESET"};
  o.handwheel_axes = {"X", "Z"};
  o.check_signal = [](const std::string& signal, double value) -> std::string {
    if (signal != "P00C.FOVR") return "no signal " + signal;
    return value >= 0 && value <= 255 ? "" : "P00C.FOVR: 0..255";
  };
  o.seekable = !guarded;
  if (guarded) {
    o.token = "fuzz-token";
    o.run_control_refused = "an external PLC is the clock";
    o.operate_refused = "a replay is watched, not operated";
  }
  return o;
}

struct Station {
  explicit Station(bool guarded) {
    Publish(hub);
    vmt::sim::station::RouteStation(http, hub, Options(guarded));
    http.set_exception_handler(
        [](const httplib::Request& req, httplib::Response&, std::exception_ptr e) {
          try {
            std::rethrow_exception(e);
          } catch (const std::exception& x) {
            std::fprintf(stderr, "station_api_fuzz: %s %s threw: %s\n", req.method.c_str(),
                         req.path.c_str(), x.what());
          } catch (...) {
            std::fprintf(stderr, "station_api_fuzz: %s %s threw\n", req.method.c_str(),
                         req.path.c_str());
          }
          std::abort();
        });
  }
  StationHub hub;
  InMemoryHttp http;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static Station open(false), guarded(true);
  const std::string_view requests(reinterpret_cast<const char*>(data), size);
  for (Station* s : {&open, &guarded}) {
    (void)s->http.Answer(requests);
    // The run takes what was queued, as at a PLC cycle: the queue's bound stays reachable by
    // one input, not by what earlier inputs left.
    (void)s->hub.TakeInputs();
  }
  return 0;
}
