#include "sim/station/http_access.hpp"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/json_text.hpp"
#include "sim/station/station_server.hpp"

namespace vmt::sim::station {

void Reply(httplib::Response& res, int status, const std::string& body) {
  res.status = status;
  res.set_header("Cache-Control", "no-store");
  res.set_content(body, "application/json");
}

void Fail(httplib::Response& res, int status, const std::string& error) {
  Reply(res, status,
        nlohmann::json{{"error", error}}.dump(-1, ' ', false, common::kReplaceBadUtf8));
}

void CheckAccess(const std::string& host, const std::string& token) {
  if (!IsLoopback(host) && token.empty())
    throw std::invalid_argument("--http " + host +
                                ": an address other than loopback needs --http-token");
}

void RequireToken(httplib::Server& http, const std::string& token) {
  if (token.empty()) return;
  http.set_pre_routing_handler([token](const httplib::Request& req, httplib::Response& res) {
    // The page is opened with ?token=; its scripts and images cannot carry that, so the answer
    // sets it as a cookie, which the browser sends with each of them (a cookie is per host,
    // not per port: a study's index and the replays it opens share it).
    const std::string cookie = "vmt_token=" + token;
    const bool in_param = req.get_param_value("token") == token;
    const bool ok = in_param || req.get_header_value("Authorization") == "Bearer " + token ||
                    req.get_header_value("Cookie").find(cookie) != std::string::npos;
    if (in_param) res.set_header("Set-Cookie", cookie + "; Path=/; HttpOnly; SameSite=Strict");
    if (ok) return httplib::Server::HandlerResponse::Unhandled;
    Fail(res, 401, "this station needs its token");
    return httplib::Server::HandlerResponse::Handled;
  });
}

int Bind(httplib::Server& http, const std::string& host, int port) {
  const int bound =
      port == 0 ? http.bind_to_any_port(host) : (http.bind_to_port(host, port) ? port : -1);
  if (bound <= 0)
    throw std::runtime_error("--http " + host + ":" + std::to_string(port) +
                             ": cannot listen there");
  return bound;
}

}  // namespace vmt::sim::station
