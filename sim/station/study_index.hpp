#pragma once
// A study folder in the browser (vmt view STUDY_DIR): its report.html and pictures, where each
// case links to `replay?case=ID`; following the link saves the case's run if it is not saved
// yet, opens a replay station for it on a port of its own (once per case) and redirects there,
// so that several cases can be watched side by side.

#include <functional>
#include <memory>
#include <string>

namespace vmt::sim::station {

struct StudyIndexOptions {
  std::string host = "127.0.0.1";
  int port = 8080;    ///< 0 picks a free one
  std::string token;  ///< required off loopback, as for a station
  std::string study_dir;
  /// The port of case `id`'s replay station, opened on the first call. Throws
  /// std::out_of_range for a case the study does not have (404); anything else is a 500.
  std::function<int(const std::string& id)> open_case;
};

class StudyIndexServer {
 public:
  /// Binds and starts serving; throws as StationServer does.
  explicit StudyIndexServer(StudyIndexOptions options);
  ~StudyIndexServer();
  StudyIndexServer(const StudyIndexServer&) = delete;
  StudyIndexServer& operator=(const StudyIndexServer&) = delete;
  int port() const { return port_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int port_ = 0;
};

}  // namespace vmt::sim::station
