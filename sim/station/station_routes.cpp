// The operator station's routes: the page's files, the JSON API of docs/station.md and the token
// check, on an httplib::Server that StationServer binds (and a fuzz target feeds in memory).

#include "sim/station/station_routes.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "sim/station/http_access.hpp"

namespace vmt::sim::station {
namespace {

using Json = nlohmann::json;

/// The request's JSON object, or a 400 answered and nullopt.
std::optional<Json> Body(const httplib::Request& req, httplib::Response& res) {
  Json body = Json::parse(req.body, nullptr, false);
  if (body.is_discarded() || !body.is_object()) {
    Fail(res, 400, "expected a JSON object");
    return std::nullopt;
  }
  return body;
}

/// `j` if it is a whole number within lo..hi. JSON keeps those above int64 unsigned: read as
/// int64, 2^64 - 1 would pass as -1.
std::optional<int64_t> WholeNumberIn(const Json& j, int64_t lo, int64_t hi) {
  if (j.is_number_unsigned()) {
    const uint64_t v = j.get<uint64_t>();
    if (hi < 0 || v > static_cast<uint64_t>(hi)) return std::nullopt;
    return static_cast<int64_t>(v);
  }
  if (!j.is_number_integer()) return std::nullopt;
  const int64_t v = j.get<int64_t>();
  if (v < lo || v > hi) return std::nullopt;
  return v;
}

/// The member `key` if it is text, else "" (a member of another type is not an action).
std::string TextOr(const Json& object, const char* key) {
  const auto it = object.find(key);
  return it != object.end() && it->is_string() ? it->get<std::string>() : "";
}

// The JSON API's reads: the model, the latest frames and the events.
void RouteReads(httplib::Server& http, StationHub& hub, const StationServerOptions& o) {
  http.Get("/api/model", [model = o.model_json](const httplib::Request&, httplib::Response& res) {
    Reply(res, 200, model);
  });
  http.Get("/api/state", [&hub](const httplib::Request&, httplib::Response& res) {
    Reply(res, 200, hub.State());
  });
  http.Get("/api/stock", [&hub](const httplib::Request&, httplib::Response& res) {
    Reply(res, 200, hub.Stock());
  });
  http.Get("/api/signals", [&hub](const httplib::Request&, httplib::Response& res) {
    Reply(res, 200, hub.Signals());
  });
  http.Get("/api/events", [&hub](const httplib::Request& req, httplib::Response& res) {
    size_t from = 0;
    if (req.has_param("from")) {
      const std::string text = req.get_param_value("from");
      char* end = nullptr;
      const unsigned long long n = std::strtoull(text.c_str(), &end, 10);
      if (text.empty() || *end != '\0' || text[0] == '-')
        return Fail(res, 400, "from: expected a whole number >= 0");
      from = static_cast<size_t>(n);
    }
    Reply(res, 200, hub.Events(from));
  });
}

// The JSON API's inputs: keys, handwheels, signals and run control, queued for the next PLC cycle.
void RouteInputs(httplib::Server& http, StationHub& hub, const StationServerOptions& o) {
  http.Post("/api/key", [&hub, keys = o.keys, refused = o.operate_refused](
                            const httplib::Request& req, httplib::Response& res) {
    const auto body = Body(req, res);
    if (!body) return;
    const auto name = body->find("name");
    const auto pressed = body->find("pressed");
    if (name == body->end() || !name->is_string() || pressed == body->end() ||
        !pressed->is_boolean())
      return Fail(res, 400, R"(expected {"name": KEY, "pressed": true | false})");
    if (!refused.empty()) return Fail(res, 403, refused);
    if (std::find(keys.begin(), keys.end(), name->get<std::string>()) == keys.end())
      return Fail(res, 404, "no machine key " + name->get<std::string>());
    if (!hub.Push({StationInput::Kind::kSignal, *name, pressed->get<bool>() ? 1.0 : 0.0}))
      return Fail(res, 429, "too many inputs waiting for the next PLC cycle");
    Reply(res, 200, R"({"ok":true})");
  });
  http.Post("/api/handwheel", [&hub, axes = o.handwheel_axes, refused = o.operate_refused](
                                  const httplib::Request& req, httplib::Response& res) {
    const auto body = Body(req, res);
    if (!body) return;
    const auto axis = body->find("axis");
    const auto counts_member = body->find("counts");
    int64_t counts = 0;  // missing or out of range: refused below as 0 is
    if (counts_member != body->end())
      if (const std::optional<int64_t> n = WholeNumberIn(*counts_member, -10000, 10000))
        counts = *n;
    if (axis == body->end() || !axis->is_string() || counts == 0)
      return Fail(res, 400, R"(expected {"axis": AXIS, "counts": -10000..10000, not 0})");
    if (!refused.empty()) return Fail(res, 403, refused);
    if (std::find(axes.begin(), axes.end(), axis->get<std::string>()) == axes.end())
      return Fail(res, 404, "no handwheel axis " + axis->get<std::string>());
    if (!hub.Push({StationInput::Kind::kHandwheel, *axis, static_cast<double>(counts)}))
      return Fail(res, 429, "too many inputs waiting for the next PLC cycle");
    Reply(res, 200, R"({"ok":true})");
  });
  http.Post("/api/signal", [&hub, check = o.check_signal](const httplib::Request& req,
                                                          httplib::Response& res) {
    const auto body = Body(req, res);
    if (!body) return;
    const auto name = body->find("name");
    const auto value = body->find("value");
    if (name == body->end() || !name->is_string() || value == body->end() ||
        !(value->is_number() || value->is_boolean()))
      return Fail(res, 400, R"(expected {"name": SIGNAL, "value": number | true | false})");
    const double v = value->is_boolean() ? (value->get<bool>() ? 1 : 0) : value->get<double>();
    if (const std::string error = check ? check(*name, v) : "no signals"; !error.empty())
      return Fail(res, error.rfind("no signal", 0) == 0 ? 404 : 403, error);
    if (!hub.Push({StationInput::Kind::kSignal, *name, v}))
      return Fail(res, 429, "too many inputs waiting for the next PLC cycle");
    Reply(res, 200, R"({"ok":true})");
  });
  http.Post("/api/run", [&hub, refused = o.run_control_refused, seekable = o.seekable](
                            const httplib::Request& req, httplib::Response& res) {
    const auto body = Body(req, res);
    if (!body) return;
    const std::string action = TextOr(*body, "action");
    const StationInput::Kind kind = action == "run"                ? StationInput::Kind::kRun
                                    : action == "pause"            ? StationInput::Kind::kPause
                                    : action == "step"             ? StationInput::Kind::kStep
                                    : action == "seek" && seekable ? StationInput::Kind::kSeek
                                                                   : StationInput::Kind::kSignal;
    if (kind == StationInput::Kind::kSignal)
      return Fail(res, 400,
                  seekable ? R"(expected {"action": "run" | "pause" | "step" | "seek"})"
                           : R"(expected {"action": "run" | "pause" | "step", "speed": factor})");
    // Run's speed: a real-time factor, 0 for as fast as the machine allows; seek's time.
    double value = 1;
    if (kind == StationInput::Kind::kSeek) {
      const auto t = body->find("t");
      if (t == body->end() || !t->is_number() || !(t->get<double>() >= 0 && t->get<double>() < 1e9))
        return Fail(res, 400, "t: expected the simulated time to go to, seconds >= 0");
      value = t->get<double>();
    } else if (const auto speed = body->find("speed"); speed != body->end()) {
      if (!speed->is_number() || !(speed->get<double>() >= 0 && speed->get<double>() <= 1000))
        return Fail(res, 400, "speed: expected a real-time factor from 0 (fastest) to 1000");
      value = speed->get<double>();
    }
    if (!refused.empty()) return Fail(res, 409, refused);
    if (!hub.Push({kind, "", value})) return Fail(res, 429, "too many inputs waiting");
    Reply(res, 200, R"({"ok":true})");
  });
}

}  // namespace

void RouteStation(httplib::Server& http, StationHub& hub, const StationServerOptions& o) {
  http.set_payload_max_length(64 * 1024);
  RequireToken(http, o.token);
  http.set_mount_point("/", o.web_dir);
  if (std::filesystem::is_directory(o.three_dir))
    http.set_mount_point("/vendor/three", o.three_dir);
  if (std::filesystem::is_directory(o.chart_dir))
    http.set_mount_point("/vendor/chart.js", o.chart_dir);
  http.set_file_extension_and_mimetype_mapping("mjs", "text/javascript");
  RouteReads(http, hub, o);
  RouteInputs(http, hub, o);
  http.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (res.body.empty()) Fail(res, res.status, "not found");
  });
}

}  // namespace vmt::sim::station
