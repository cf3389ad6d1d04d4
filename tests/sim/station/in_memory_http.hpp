#pragma once
// An httplib::Server that answers raw request bytes in memory, as it would answer them on one
// keep-alive connection, without a socket or a thread: the station's routes (station_routes.hpp)
// are checked and fuzzed byte for byte this way, including requests no HTTP client would send.

#include <httplib.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <string_view>

namespace vmt::sim::station::testing {

class InMemoryHttp : public httplib::Server {
 public:
  /// Everything the server writes back for `requests` (status lines, headers, bodies).
  std::string Answer(std::string_view requests) {
    Connection c(requests);
    // As httplib's own loop per connection: request after request until it closes or fails.
    while (c.Unread() > 0) {
      const size_t before = c.Unread();
      bool closed = false;
      if (!process_request(c, false, closed, [](httplib::Request&) {})) break;
      if (closed || c.Unread() == before) break;
    }
    return c.written;
  }

 private:
  struct Connection : httplib::Stream {
    explicit Connection(std::string_view in) : input(in) {}
    size_t Unread() const { return input.size() - at; }

    using httplib::Stream::write;
    bool is_readable() const override { return true; }
    bool is_writable() const override { return true; }
    ssize_t read(char* ptr, size_t size) override {
      const size_t n = std::min(size, Unread());
      std::memcpy(ptr, input.data() + at, n);
      at += n;
      return static_cast<ssize_t>(n);
    }
    ssize_t write(const char* ptr, size_t size) override {
      written.append(ptr, size);
      return static_cast<ssize_t>(size);
    }
    void get_remote_ip_and_port(std::string& ip, int& port) const override {
      ip = "127.0.0.1";
      port = 40000;
    }
    void get_local_ip_and_port(std::string& ip, int& port) const override {
      ip = "127.0.0.1";
      port = 8080;
    }
    socket_t socket() const override { return INVALID_SOCKET; }

    std::string_view input;
    size_t at = 0;
    std::string written;
  };
};

}  // namespace vmt::sim::station::testing
