#include "sim/station/study_index.hpp"

#include <filesystem>
#include <stdexcept>
#include <thread>

#include "sim/station/http_access.hpp"

namespace vmt::sim::station {
namespace {

// The host the browser reached this server by ("127.0.0.1:8080" -> "127.0.0.1"), so that the
// redirect to a replay's port goes the same way.
std::string HostOf(const httplib::Request& req, const std::string& bound) {
  std::string host = req.get_header_value("Host");
  const size_t colon = host.rfind(':');
  if (colon != std::string::npos && host.find(']', colon) == std::string::npos) host.resize(colon);
  return host.empty() ? bound : host;
}

}  // namespace

struct StudyIndexServer::Impl {
  httplib::Server http;
  std::thread thread;
};

StudyIndexServer::StudyIndexServer(StudyIndexOptions o) : impl_(std::make_unique<Impl>()) {
  CheckAccess(o.host, o.token);
  if (!std::filesystem::exists(o.study_dir + "/report.html"))
    throw std::invalid_argument(o.study_dir + ": no report.html (not a study folder)");
  httplib::Server& http = impl_->http;
  http.new_task_queue = [] { return new httplib::ThreadPool(8); };
  http.set_payload_max_length(64 * 1024);
  http.set_read_timeout(5, 0);
  http.set_write_timeout(5, 0);
  RequireToken(http, o.token);
  http.Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_redirect("/report.html");
  });
  http.Get("/replay", [o](const httplib::Request& req, httplib::Response& res) {
    const std::string id = req.get_param_value("case");
    if (id.empty()) return Fail(res, 400, "expected replay?case=ID");
    int port = 0;
    try {
      port = o.open_case(id);
    } catch (const std::out_of_range& e) {
      return Fail(res, 404, e.what());
    } catch (const std::exception& e) {
      return Fail(res, 500, e.what());
    }
    res.set_redirect("http://" + HostOf(req, o.host) + ":" + std::to_string(port) + "/" +
                     (o.token.empty() ? "" : "?token=" + o.token));
  });
  http.set_mount_point("/", o.study_dir);
  http.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (res.body.empty()) Fail(res, res.status, "not found");
  });
  port_ = Bind(http, o.host, o.port);
  impl_->thread = std::thread([this] { impl_->http.listen_after_bind(); });
}

StudyIndexServer::~StudyIndexServer() {
  impl_->http.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
}

}  // namespace vmt::sim::station
