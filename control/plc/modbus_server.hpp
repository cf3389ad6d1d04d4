#pragma once
// A Modbus TCP server that exposes the signal image to an external PLC (DESIGN.md, plc/): the
// signal table's Modbus addresses (signal_table.hpp) become coils, discrete inputs, holding and
// input registers. Single-threaded: the caller's loop calls Poll, which never blocks longer than
// its timeout and never throws because of what a client sends. Optionally a cycle register lets
// the client step the simulation in lockstep with its own scan.
//
// Function codes: 1, 2, 3, 4 (read), 5, 6, 15, 16 (write), 23 (write then read registers).
// Anything else is answered with exception 01 ILLEGAL FUNCTION. The unit id is not checked and
// is echoed. FC23 reads back the registers it has just written as sent (libmodbus copies them),
// not as the image decoded them: they differ only in a STRING's bytes after its NUL.
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

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "control/gateway/signal_image.hpp"
#include "control/plc/axd_wr.hpp"

namespace vmt::control::plc {

struct ModbusServerOptions {
  std::string host = "127.0.0.1";  ///< numeric address or name to listen on; "" = every address
  int port = 0;                    ///< 0: a free ephemeral port (see ModbusServer::port())
  int max_clients = 8;             ///< further connections are closed right after accept
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
  uint64_t clients_refused = 0;  ///< closed at once because max_clients were connected
  uint64_t cycles = 0;           ///< cycle register writes that ran a cycle
  uint64_t axd_writes = 0;       ///< AXD_WR block writes that reached the drive
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
  /// owns, max_clients < 1, an AXD_WR block without its writer or overlapping a signal or the
  /// cycle register, a status block of no registers or overlapping a signal).
  ModbusServer(gateway::SignalImage& image, Options options);
  ~ModbusServer();
  ModbusServer(ModbusServer&&) noexcept;
  ModbusServer& operator=(ModbusServer&&) noexcept;

  /// Waits at most `timeout_ms` (negative: until something happens) for a connection or data,
  /// accepts new clients, serves every complete request that has arrived, and returns.
  void Poll(int timeout_ms);

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
  /// Number of the last completed cycle (the cycle register shows it modulo 65536).
  uint32_t cycle() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace vmt::control::plc
