// libFuzzer target for the Modbus TCP server's request handling: any bytes, as a peer sends them
// over one connection, to a server with lathe-c1's signal table and everything vmt serve adds
// (lockstep cycle register, AXD_WR block, NC status block). Every request is answered, or the
// connection closed; the replies are well-formed Modbus TCP frames; never a crash, a sanitizer
// report or a hang.
//
// Input: the first byte is the segment size (0: the whole stream in one write), the rest the
// stream. The stream is written in segments of that size with the server polled after each,
// so a request may arrive split anywhere and several may arrive together (pipelined), as TCP
// delivers them. The server is polled on this thread over a loopback connection: its requests
// are only reachable through its sockets (modbus_server.hpp keeps its state private).

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "control/gateway/nc_status_block.hpp"
#include "control/gateway/signal_image.hpp"
#include "control/gateway/signal_table.hpp"
#include "control/plc/modbus_server.hpp"
#include "sim/model/gateway_layout.hpp"
#include "sim/model/machine_model.hpp"

namespace {

using vmt::control::gateway::SignalImage;
using vmt::control::plc::AxdWrStatus;
using vmt::control::plc::ModbusServer;

// The MBAP header: transaction id, protocol id, length (unit id + PDU), unit id.
constexpr size_t kMbapBytes = 7;
// Polls without progress before the server is taken to be done with what it has.
constexpr int kIdlePolls = 2;
// Sends the socket refuses in a row (the server reads nothing) before that is a finding.
constexpr size_t kStalledSends = 1000;

// Lathe-c1's signal image as vmt serve builds it; each input starts from a copy.
const SignalImage& Pristine() {
  static const SignalImage image(vmt::control::gateway::BuildSignalTable(vmt::sim::GatewayLayoutOf(
      vmt::sim::LoadMachineModel(VMT_SOURCE_DIR "/models/lathe-c1/machine.yaml"))));
  return image;
}

ModbusServer::Options OptionsFor(const SignalImage& image) {
  ModbusServer::Options o;
  o.cycle_register = vmt::control::gateway::LockstepCycleRegister(image.table());
  o.on_cycle = [](uint32_t) {};
  o.axd_wr_register = vmt::control::gateway::AxdWrRegister(image.table());
  // Each of the drive's answers, and a drive that fails (the 04 exception), by axis.
  o.axd_wr = [](int axis, int, int64_t) {
    if (axis == 1) return AxdWrStatus::kDone;
    if (axis == 2) return AxdWrStatus::kRefused;
    if (axis == 3) throw std::runtime_error("drive failed");
    return AxdWrStatus::kNoAxis;
  };
  const auto status = vmt::control::gateway::NcStatusLayoutOf(image.table());
  o.status_register = status.address;
  o.status_count = status.count();
  return o;
}

int Connect(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (fd < 0 || connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    std::perror("modbus_server_fuzz: connect");
    std::abort();
  }
  // Closed with a reset, not FIN: no TIME_WAIT, so a long run does not use up the ports.
  const linger reset{1, 0};
  setsockopt(fd, SOL_SOCKET, SO_LINGER, &reset, sizeof reset);
  return fd;
}

// What has arrived of the replies, without waiting.
void Receive(int fd, std::vector<uint8_t>& replies) {
  uint8_t buf[4096];
  for (;;) {
    const ssize_t n = recv(fd, buf, sizeof buf, MSG_DONTWAIT);
    if (n <= 0) return;
    replies.insert(replies.end(), buf, buf + n);
  }
}

// Polls until the server has served what it has been sent (it reads at most its buffer per
// poll) and collects the replies.
void Settle(ModbusServer& server, int fd, std::vector<uint8_t>& replies) {
  for (int idle = 0; idle < kIdlePolls;) {
    const uint64_t before = server.stats().requests() + server.stats().clients_dropped;
    server.Poll(0);
    Receive(fd, replies);
    const uint64_t after = server.stats().requests() + server.stats().clients_dropped;
    idle = after == before ? idle + 1 : 0;
  }
}

// Every reply is a whole frame: protocol 0, a length field the PDU fills, a function code.
void CheckReplies(const std::vector<uint8_t>& replies, uint64_t answered) {
  size_t at = 0;
  uint64_t frames = 0;
  while (at + kMbapBytes <= replies.size()) {
    const uint8_t* f = replies.data() + at;
    const int protocol = f[2] << 8 | f[3];
    const size_t length = static_cast<size_t>(f[4] << 8 | f[5]);
    if (protocol != 0 || length < 2 || at + 6 + length > replies.size()) break;
    at += 6 + length;
    ++frames;
  }
  if (at != replies.size() || frames != answered) {
    std::fprintf(stderr, "modbus_server_fuzz: %zu reply bytes, %zu in %llu frames, %llu answered\n",
                 replies.size(), at, static_cast<unsigned long long>(frames),
                 static_cast<unsigned long long>(answered));
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  SignalImage image = Pristine();
  ModbusServer server(image, OptionsFor(image));
  const int fd = Connect(server.port());
  server.Poll(0);  // accepts
  const size_t segment = data[0] == 0 ? size : data[0];
  std::vector<uint8_t> replies;
  for (size_t at = 1, stalled = 0; at < size;) {
    const size_t n = std::min(segment, size - at);
    const ssize_t sent = send(fd, data + at, n, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (sent < 0 && errno != EAGAIN) break;  // the server closed the connection
    if (sent > 0) at += static_cast<size_t>(sent);
    stalled = sent > 0 ? 0 : stalled + 1;
    if (stalled > kStalledSends) {
      std::fprintf(stderr, "modbus_server_fuzz: the server stopped reading\n");
      std::abort();
    }
    Settle(server, fd, replies);
  }
  // The peer goes away: what it sent completely is still answered, a partial request is not.
  shutdown(fd, SHUT_WR);
  Settle(server, fd, replies);
  CheckReplies(replies, server.stats().requests());
  close(fd);
  return 0;
}
