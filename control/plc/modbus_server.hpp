#pragma once
// A Modbus TCP server that exposes the signal image to an external PLC (DESIGN.md, plc/): the
// signal table's Modbus addresses (signal_table.hpp) become coils, discrete inputs, holding and
// input registers. Single-threaded: the caller's loop calls Poll or ServeUntil, which never block
// longer than asked and never throw because of what a client sends. Optionally a cycle register
// lets the client step the simulation in lockstep with its own scan.
//
// Function codes: 1, 2, 3, 4 (read), 5, 6, 15, 16 (write), 23 (write then read registers).
// Anything else is answered with exception 01 ILLEGAL FUNCTION. FC23 reads back the registers
// it has just written as sent (libmodbus copies them), not as the image decoded them: they
// differ only in a STRING's bytes after its NUL.
//
// Unit id: the server answers Options::unit_id and 0 and 255, the two values a Modbus TCP
// client uses for "the server at this address" (Modbus Messaging on TCP/IP 4.4.2); any other
// is answered with exception 0B GATEWAY TARGET DEVICE FAILED TO RESPOND, as a gateway answers
// for a device it does not have, and nothing is done. The reply echoes the request's unit id.
//
// The PLC role (docs/plc.md, "Who may connect and write"): one connection at a time may write. A
// write (FC 5, 6, 15, 16, 23, the cycle register and the AXD_WR block included) from any other
// connection is answered with exception 01 ILLEGAL FUNCTION ("not an allowable action for the
// server in its state") and changes nothing. The first connection whose write succeeds takes
// the role; it keeps it until its connection closes or, with Options::plc_role_timeout_ms, until
// it has written nothing for that long (a PLC reconnecting over a half-open connection). Reads
// are open to every connection. Signals vmt drives (NC->PLC, MACHINE->PLC) lie in the read-only
// areas (discrete inputs, input registers), so no connection can write them: the constructor
// refuses a table that puts one in a coil or holding register.
//
// Connections: at most Options::max_clients. When that many are open, a new connection closes
// the one that has been idle longest (the PLC role's holder never), so a PLC can always
// reconnect; a connection that sends no request for Options::client_timeout_ms is closed.
// Listening on an address other than loopback needs Options::allow_remote; with
// Options::allowed_clients, connections from other addresses (loopback excepted) are closed at
// accept.
//
// Work per call: requests are served one per connection in turn, so a client with many
// requests in flight does not starve the others, and ServeUntil stops serving at its deadline,
// leaving the rest in the connections' buffers for the next call: the caller's cycle comes first.
//
// Requests are checked completely before anything is applied; a request answered with an
// exception changes nothing:
//  - 03 ILLEGAL DATA VALUE: a quantity outside the protocol's limits (1..2000 bits and 1..125
//    registers read, 1..1968 bits and 1..123 registers written, 1..121 written by FC23), a byte
//    count that does not match the quantity, a PDU whose length does not match its function
//    code, an FC5 value other than 0x0000 / 0xFF00, a wrong cycle number (below).
//  - 02 ILLEGAL DATA ADDRESS: a read reaching outside the area (a read may cover part of a
//    multi-register signal), a write to an address no signal of the coil / holding area owns,
//    and a register write that covers only part of a multi-register signal (one word of a DINT,
//    REAL, LREAL or STRING): a signal is written whole or not at all, so the NC never sees half
//    a value. The cycle register is written alone (FC6, or FC16 of exactly that register).
//  - 04 SERVER DEVICE FAILURE: the cycle callback threw.
// A frame whose MBAP header is wrong (protocol id not 0, length field outside 2..254) cannot be
// answered or skipped reliably: the server closes that connection, as it does for a client that
// disconnects (a partly received request is discarded) or does not take its replies.
//
// Lockstep handshake (Options::cycle_register): the cycle register holds the number of the last
// completed simulation cycle, modulo 65536 (0 before the first). To run a cycle the client writes
// the next number (last + 1, modulo 65536) to it, FC6 or FC16 of that one register. The server
// calls on_cycle with the cycle's full number (1, 2, ...) and sends the reply only after the
// callback has returned: when the client's write completes, the cycle has run and reading the
// image shows its result. Any other value is answered with 03 and runs nothing (a repeated write
// after a lost reply is therefore refused, not run twice; reading the register tells whether it
// ran). The client writes its outputs before the cycle write and reads its inputs after it.
//
// AXD_WR block (Options::axd_wr_register + axd_wr): the SPS's system function AXD_WR
// (axd_wr.hpp; fast-measurement 7.2), which writes a drive parameter over the SERCOS service
// channel, for a PLC that is not embedded. Six holding registers from the block's address B:
//   B+0 axis number 1..32       B+1 ident number 1..65535 (S-0-ident)
//   B+2..B+3 value, DINT (most significant word first, as the table's DINTs)
//   B+4 result (read only): 0 none yet, 1 done, 2 no axis, 3 refused (AxdWrStatus + 1)
//   B+5 count of AXD_WRs run, modulo 65536 (read only)
// Writing B..B+3 in one request (FC16 of exactly those four registers, or FC23 whose write part
// is exactly those four) runs AXD_WR; the reply is sent after the drive has answered, so the
// result is in B+4 when the write completes (FC23 can read it back in the same transaction).
// B+5 tells after a lost reply whether the write ran. Exceptions, nothing run: 02 for any other
// write touching the block (part of it, FC6, B+4 / B+5); 03 for axis 0 or above 32, ident 0;
// 04 if the writer throws. A refusal by the drive is a result (3), not an exception: the PLC's
// block turns it into its own error number (QMFB1Axx FEHLER_NR 28..40).
//
// Status block (Options::status_register + status_count): input registers beside the signals'
// that the caller fills with SetStatus (vmt serve: the NC status block, nc_status_block.hpp,
// after every cycle). Read with FC04, also in one request with signals' input registers where
// the two are adjacent; they read 0 until the first SetStatus.

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "control/gateway/signal_image.hpp"
#include "control/plc/axd_wr.hpp"

namespace vmt::control::plc {

struct ModbusServerOptions {
  std::string host = "127.0.0.1";  ///< numeric address or name to listen on; "" = every address
  int port = 0;                    ///< 0: a free ephemeral port (see ModbusServer::port())
  /// Open connections at most (1..1024): a further one closes the longest idle connection that
  /// does not hold the PLC role, or is closed itself if there is none.
  int max_clients = 8;
  /// The unit id answered besides 0 and 255 (1..247); others get exception 0B.
  int unit_id = 1;
  /// A connection that sends no complete request for this long is closed (ms, 0: never).
  int client_timeout_ms = 30000;
  /// The PLC role passes to another connection's write once its holder has written nothing for
  /// this long (ms; 0: only when the holder's connection closes).
  int plc_role_timeout_ms = 0;
  /// Listening on an address that is not loopback (127.0.0.0/8, ::1) throws without it.
  bool allow_remote = false;
  /// Numeric addresses (IPv4 or IPv6) that may connect; empty: any. Loopback always may.
  std::vector<std::string> allowed_clients;
  /// Holding register address of the lockstep cycle register; it must not belong to a signal
  /// (one past the table's last holding register is the usual choice).
  std::optional<int> cycle_register;
  /// Runs one simulation cycle; called from Poll. Must not call Poll.
  std::function<void(uint32_t cycle)> on_cycle;
  /// Holding register address of the AXD_WR block (six registers, none a signal's nor the cycle
  /// register; vmt serve puts it right after the cycle register). Both or neither of these two.
  std::optional<int> axd_wr_register;
  /// Writes the drive parameter; called from Poll. Must not call Poll.
  AxdWriter axd_wr;
  /// Input register address of the status block (`status_count` registers, none a signal's).
  std::optional<int> status_register;
  int status_count = 0;
};

struct ModbusServerStats {
  uint64_t requests_served = 0;  ///< requests answered with a normal reply
  uint64_t exceptions_sent = 0;  ///< requests answered with an exception reply
  uint64_t clients_accepted = 0;
  /// Connections closed after being accepted: the peer disconnected, sent a bad MBAP header, or
  /// did not take its replies.
  uint64_t clients_dropped = 0;
  /// Closed at once: max_clients were connected, all but the PLC's busy or none to close, or
  /// the address is not among Options::allowed_clients.
  uint64_t clients_refused = 0;
  uint64_t clients_not_allowed = 0;  ///< of clients_refused: not an allowed address
  uint64_t clients_evicted = 0;  ///< closed to make room for a new connection (in clients_dropped)
  uint64_t clients_timed_out = 0;  ///< closed after client_timeout_ms idle (in clients_dropped)
  /// Writes refused with exception 01 because another connection holds the PLC role.
  uint64_t writes_refused = 0;
  uint64_t wrong_unit = 0;  ///< requests answered with exception 0B (another unit id)
  uint64_t cycles = 0;      ///< cycle register writes that ran a cycle
  uint64_t axd_writes = 0;  ///< AXD_WR block writes that reached the drive
  /// Write requests answered normally (coils, holding registers): the PLC writing its outputs.
  /// A monitor that only reads never moves it.
  uint64_t writes = 0;
  /// Every request answered, normally or with an exception.
  uint64_t requests() const { return requests_served + exceptions_sent; }
};

class ModbusServer {
 public:
  using Options = ModbusServerOptions;
  using Stats = ModbusServerStats;

  /// Binds and listens. `image` must outlive the server. Throws std::runtime_error naming
  /// host:port and the system's reason if it cannot listen, std::invalid_argument for options
  /// that make no sense (port or cycle register outside 0..65535, a cycle register a signal
  /// owns, max_clients outside 1..1024, an AXD_WR block without its writer or overlapping a signal
  /// or the cycle register, a status block of no registers or overlapping a signal, a unit id
  /// outside 1..247, a negative timeout, an allowed client that is not a numeric address, a
  /// signal vmt drives in a writable area, an address off loopback without allow_remote).
  ModbusServer(gateway::SignalImage& image, Options options);
  ~ModbusServer();
  ModbusServer(ModbusServer&&) noexcept;
  ModbusServer& operator=(ModbusServer&&) noexcept;

  /// Waits at most `timeout_ms` (negative: until something happens) for a connection or data,
  /// accepts new clients, serves the complete requests that have arrived, and returns.
  void Poll(int timeout_ms);

  /// Accepts and serves until `deadline`, and returns then (vmt serve --realtime: the next
  /// cycle's time). A request is started after it only in the call's first turn, one per client
  /// that has one waiting, so that a late caller still hears its PLC; the caller is late by that
  /// turn at most. Requests still waiting are served by the next call.
  void ServeUntil(std::chrono::steady_clock::time_point deadline);

  /// The status block's registers from now on; `words` has Options::status_count of them.
  void SetStatus(std::span<const uint16_t> words);

  /// Closes every client connection (each counts in clients_dropped), as when the PLC's link
  /// goes down; the server keeps listening and accepts new clients. A request partly received
  /// is discarded. Call it between Polls: from inside Poll (on_cycle) it aborts, since Poll is
  /// then working on those connections.
  void DropClients();

  int port() const;  ///< the bound port
  const Stats& stats() const;
  int clients() const;  ///< connected clients
  /// Listening on an address other than loopback (Options::allow_remote was needed).
  bool remote() const;
  /// Number of the last completed cycle (the cycle register shows it modulo 65536).
  uint32_t cycle() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace vmt::control::plc
