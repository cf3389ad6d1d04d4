#include "sim/station/station_server.hpp"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include "sim/station/http_access.hpp"
#include "sim/station/station_routes.hpp"

namespace vmt::sim::station {

bool IsLoopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

std::string DefaultWebDir() {
  if (const char* dir = std::getenv("VMT_WEB_DIR"); dir && *dir) return dir;
#ifdef VMT_SOURCE_WEB_DIR
  if (std::filesystem::is_directory(VMT_SOURCE_WEB_DIR)) return VMT_SOURCE_WEB_DIR;
#endif
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? "web" : (exe.parent_path().parent_path() / "share/vmt/web").string();
}

struct StationServer::Impl {
  httplib::Server http;
  std::thread thread;
};

StationServer::StationServer(StationHub& hub, StationServerOptions o)
    : impl_(std::make_unique<Impl>()) {
  CheckAccess(o.host, o.token);
  if (!std::filesystem::is_directory(o.web_dir))
    throw std::invalid_argument("the operator station's page is not in " + o.web_dir +
                                " (set VMT_WEB_DIR)");
  httplib::Server& http = impl_->http;
  // Enough workers that five pages (a browser opens up to six connections each) are served at
  // once; a stalled page holds a worker only until the keep-alive and read timeouts.
  http.new_task_queue = [] { return new httplib::ThreadPool(32); };
  http.set_keep_alive_timeout(2);
  http.set_read_timeout(5, 0);
  http.set_write_timeout(5, 0);
  RouteStation(http, hub, o);

  port_ = Bind(http, o.host, o.port);
  impl_->thread = std::thread([this] { impl_->http.listen_after_bind(); });
}

StationServer::~StationServer() {
  impl_->http.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
}

}  // namespace vmt::sim::station
