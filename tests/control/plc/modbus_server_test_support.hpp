#pragma once
// Shared by the Modbus TCP server's tests (modbus_server_*_test.cpp): a small signal image, a
// libmodbus client as an external PLC connects, a raw TCP connection for frames libmodbus would
// not send, and a server polled on the test's thread.

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <modbus.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "control/plc/modbus_server.hpp"

namespace vmt::control::plc::testing {

using gateway::ModbusAddress;
using gateway::Signal;
using gateway::SignalImage;
using gateway::SignalType;

// A small machine: one process, a linear axis and a spindle, two I/O points; plus one REAL
// holding register, a type the catalog has no PLC-written family of.
inline SignalImage MakeImage() {
  gateway::GatewayLayout layout;
  layout.processes = {0};
  layout.axes = {{1, "X", false, false}, {2, "S1", true, false}};
  layout.io = {{"QVALVE", true, "Valve"}, {"ISWITCH", false, "Switch"}};
  std::vector<Signal> table = gateway::BuildSignalTable(layout);
  int next = 0;
  for (const Signal& s : table) {
    if (s.modbus.area == ModbusAddress::kHoldingRegister) {
      next = std::max(next, s.modbus.address + s.modbus.count);
    }
  }
  Signal real{};
  real.name = "TEST.REAL_W";
  real.type = SignalType::kReal;
  real.direction = gateway::Direction::kPlcToNc;
  real.modbus = {ModbusAddress::kHoldingRegister, next, 2};
  real.pattern = real.name;
  real.scope = gateway::Scope::kGlobal;
  real.instance = -1;
  table.push_back(real);
  return SignalImage(std::move(table));
}

inline int Extent(const SignalImage& image, ModbusAddress::Area area) {
  int end = 0;
  for (const Signal& s : image.table()) {
    if (s.modbus.area == area) end = std::max(end, s.modbus.address + s.modbus.count);
  }
  return end;
}

inline const ModbusAddress& At(const SignalImage& image, const char* name) {
  return image.table()[image.Require(name)].modbus;
}

// Runs `client` on its own thread while this thread polls the server, the way a simulation loop
// would; returns when the client is done.
inline void WhilePolling(ModbusServer& server, const std::function<void()>& client) {
  std::atomic<bool> done{false};
  std::thread t([&] {
    client();
    done = true;
  });
  while (!done) server.Poll(2);
  t.join();
}

// Polls until every client's disconnect has been seen (the client threads have closed theirs).
inline void Drain(ModbusServer& server) {
  for (int i = 0; i < 200 && server.clients() > 0; ++i) server.Poll(5);
}

// A libmodbus client, the way an external PLC connects.
struct Client {
  explicit Client(int port) : ctx(modbus_new_tcp("127.0.0.1", port)) {
    if (ctx == nullptr) throw std::runtime_error("modbus_new_tcp failed");
    if (modbus_connect(ctx) != 0) {
      modbus_free(ctx);
      throw std::runtime_error(std::string("modbus_connect: ") + modbus_strerror(errno));
    }
  }
  ~Client() {
    modbus_close(ctx);
    modbus_free(ctx);
  }
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;
  modbus_t* ctx;
};

// A plain TCP connection for frames libmodbus would not send.
struct Raw {
  explicit Raw(int port) : fd(socket(AF_INET, SOCK_STREAM, 0)) {
    if (fd < 0) throw std::runtime_error("socket failed");
    timeval tv{2, 0};  // a broken server fails the test instead of hanging it
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv) != 0 ||
        connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
      close(fd);
      throw std::runtime_error(std::string("raw connect: ") + std::strerror(errno));
    }
  }
  ~Raw() {
    if (fd >= 0) close(fd);
  }
  Raw(const Raw&) = delete;
  Raw& operator=(const Raw&) = delete;

  bool Send(const std::vector<uint8_t>& bytes) const {
    return send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(bytes.size());
  }
  // Up to n bytes; fewer if the server closes the connection (or after the 2 s guard).
  std::vector<uint8_t> Receive(size_t n) const {
    std::vector<uint8_t> out(n);
    size_t have = 0;
    while (have < n) {
      const ssize_t r = recv(fd, out.data() + have, n - have, 0);
      if (r <= 0) break;
      have += static_cast<size_t>(r);
    }
    out.resize(have);
    return out;
  }
  // True if the server closed the connection (EOF or reset) rather than answer.
  bool Closed() const {
    uint8_t b;
    const ssize_t r = recv(fd, &b, 1, 0);
    return r == 0 || (r < 0 && errno == ECONNRESET);
  }
  void Close() {
    close(fd);
    fd = -1;
  }
  int fd;
};

inline std::vector<uint8_t> Frame(uint16_t tid, const std::vector<uint8_t>& pdu,
                                  uint16_t protocol = 0, int length = -1) {
  const int len = length >= 0 ? length : static_cast<int>(pdu.size()) + 1;
  std::vector<uint8_t> f(7 + pdu.size());
  f[0] = static_cast<uint8_t>(tid >> 8);
  f[1] = static_cast<uint8_t>(tid);
  f[2] = static_cast<uint8_t>(protocol >> 8);
  f[3] = static_cast<uint8_t>(protocol);
  f[4] = static_cast<uint8_t>(len >> 8);
  f[5] = static_cast<uint8_t>(len);
  f[6] = 0x01;  // unit id
  for (size_t i = 0; i < pdu.size(); ++i) f[7 + i] = pdu[i];
  return f;
}

inline std::vector<uint8_t> Pdu(uint8_t function, int a, int b) {
  return {function, static_cast<uint8_t>(a >> 8), static_cast<uint8_t>(a),
          static_cast<uint8_t>(b >> 8), static_cast<uint8_t>(b)};
}

// The exception reply to Frame(tid, {function, ...}).
inline std::vector<uint8_t> ExceptionReply(uint16_t tid, uint8_t function, uint8_t code) {
  return {static_cast<uint8_t>(tid >> 8),
          static_cast<uint8_t>(tid),
          0,
          0,
          0,
          3,
          0x01,
          static_cast<uint8_t>(function | 0x80),
          code};
}

inline std::vector<uint16_t> Registers(const SignalImage& image, int id) {
  std::vector<uint16_t> w(image.table()[id].modbus.count);
  ToRegisters(image, id, w);
  return w;
}

class ModbusServerTest : public ::testing::Test {
 protected:
  SignalImage image_ = MakeImage();
  ModbusServer server_{image_, {}};
};

}  // namespace vmt::control::plc::testing
