#pragma once
// The Modbus TCP server's state, shared by its parts (private to control/plc): the connections
// (modbus_connections.cpp: accepting, reading, the client limit, idle connections, the polling
// loop), the requests (modbus_requests.cpp: checking, applying and answering one frame) and the
// set-up (modbus_server.cpp). modbus_server.hpp says what the server does.

#include <modbus.h>
#include <netinet/in.h>
#include <poll.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <vector>

#include "control/gateway/signal_image.hpp"
#include "control/plc/modbus_server.hpp"

namespace vmt::control::plc::modbus_detail {

using Clock = std::chrono::steady_clock;
using gateway::ModbusAddress;

// MBAP header: transaction id, protocol id, length (unit id + PDU), unit id.
inline constexpr int kMbapBytes = 7;
inline constexpr int kMaxLengthField = 1 + MODBUS_MAX_PDU_LENGTH;
// Room for many pipelined requests; a partial frame left over is always < 260 bytes. A client
// whose buffer holds unserved requests is not read from: TCP holds the rest back.
inline constexpr size_t kClientBuffer = 4096;
inline constexpr int kMaxAcceptsPerPoll = 16;

// The AXD_WR block (modbus_server.hpp): B+0 axis, B+1 ident, B+2..3 value written together;
// B+4, B+5 read.
inline constexpr int kAxdRegisters = 6;

inline int Word(const uint8_t* p) { return p[0] << 8 | p[1]; }

struct Client {
  int fd = -1;
  uint64_t id = 0;  // never reused: the PLC role names its holder by it
  std::vector<uint8_t> buf = std::vector<uint8_t>(kClientBuffer);
  size_t at = 0;                 // start of the first unserved byte in buf
  size_t have = 0;               // end of the received bytes in buf
  Clock::time_point heard_at{};  // accept, then the last complete request
  bool peer_closed = false;      // EOF seen: closed once its buffered requests are served
  bool closed = false;
};

enum class Reply { kSent, kDrop };

struct ServerState {
  gateway::SignalImage* image = nullptr;
  ModbusServerOptions options;
  int listen_fd = -1;
  int port = 0;
  bool remote = false;
  std::vector<in6_addr> allowed;  // Options::allowed_clients, IPv4 as v4-mapped
  modbus_t* ctx = nullptr;        // formats and sends replies; never reads from a socket
  modbus_mapping_t* mapping = nullptr;
  // By ModbusAddress::Area, by address: the id of the signal there, -1 for none.
  std::array<std::vector<int>, 4> owner;
  int cycle_register = -1;
  uint32_t cycle = 0;
  int axd_register = -1;                      // B, -1: no AXD_WR block
  std::array<uint16_t, kAxdRegisters> axd{};  // what B..B+5 read
  int status_register = -1;                   // -1: no status block
  std::vector<uint16_t> status_words;         // what the status block reads
  std::vector<Client> clients;                // closed ones until the end of a poll
  int open_clients = 0;
  uint64_t next_client_id = 1;
  uint64_t plc_client = 0;  // id of the PLC role's holder, 0: none
  Clock::time_point plc_written_at{};
  size_t next_turn = 0;  // the client served first in the next round
  std::vector<pollfd> fds;
  ModbusServerStats stats;
  bool polling = false;  // inside Poll: the clients vector is being worked on

  ServerState() = default;
  ServerState(const ServerState&) = delete;
  ServerState& operator=(const ServerState&) = delete;
  ~ServerState();

  // modbus_requests.cpp
  const gateway::Signal& Sig(int id) const { return image->table()[id]; }
  int Owner(ModbusAddress::Area area, int address) const {
    const std::vector<int>& o = owner[area];
    return address >= 0 && address < static_cast<int>(o.size()) ? o[address] : -1;
  }
  // Serves one complete frame of `c` (header checked, `length` = 7 + the PDU's length >= 1).
  Reply Serve(Client& c, uint8_t* adu, int length);

  // modbus_connections.cpp
  void Drop(Client& c);
  // One round: waits up to `timeout_ms` (clipped to `deadline`), reads, accepts, serves the
  // buffered requests in turn until they are done or the deadline has passed, closes idle ones.
  // With `first_turn` every client with a request has one answered even past the deadline.
  void PollOnce(int timeout_ms, Clock::time_point deadline, bool first_turn = false);

 private:
  // modbus_requests.cpp
  bool InAxd(int a) const;
  bool InStatus(int a) const;
  bool Readable(ModbusAddress::Area area, int address, int quantity) const;
  bool WholeSignals(int address, int quantity) const;
  void FillBits(ModbusAddress::Area area, int address, int quantity, uint8_t* tab) const;
  void FillRegisters(ModbusAddress::Area area, int address, int quantity, uint16_t* tab) const;
  void ApplyRegisters(int address, int quantity, const uint8_t* data);
  bool MayWrite(const Client& c) const;
  Reply Send(Client& c, const uint8_t* adu, int length);
  Reply Exception(Client& c, uint8_t* adu, int code);
  Reply Cycle(Client& c, uint8_t* adu, int length, int value);
  int Axd(const uint8_t* data);
  Reply ServeWrite(Client& c, uint8_t* adu, int length);

  // modbus_connections.cpp
  bool ServeOneBuffered(Client& c);
  bool HasFrame(const Client& c) const;
  void ServeInTurn(Clock::time_point deadline, bool first_turn);
  void Read(Client& c);
  void Accept();
  bool Allowed(const sockaddr_storage& peer) const;
  bool MakeRoom();
  void CloseIdle(Clock::time_point now);
};

}  // namespace vmt::control::plc::modbus_detail
