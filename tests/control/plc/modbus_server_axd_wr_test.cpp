// The Modbus TCP server's AXD_WR block (modbus_server.hpp): an external PLC writes a drive
// parameter (axis, ident number, value) in one request, the reply comes after the drive has
// answered, the result and a count read back; anything else touching the block is an exception
// and runs nothing.

#include <gtest/gtest.h>
#include <modbus.h>

#include <stdexcept>
#include <tuple>
#include <vector>

#include "control/plc/modbus_server.hpp"
#include "modbus_server_test_support.hpp"

namespace vmt::control::plc {
namespace {

using namespace testing;  // vmt::control::plc::testing

// A drive on axis 1 that takes S-0-0170 (probe control) values 0..3 and nothing else, as vmt's
// drives take the probe parameters (sim/runner/probe_glue).
struct Drive {
  std::vector<std::tuple<int, int, int64_t>> writes;
  bool fail = false;
  AxdWrStatus operator()(int axis, int ident, int64_t value) {
    if (fail) throw std::runtime_error("the drive bus failed");
    writes.emplace_back(axis, ident, value);
    if (axis != 1) return AxdWrStatus::kNoAxis;
    if (ident != 170 || value < 0 || value > 3) return AxdWrStatus::kRefused;
    return AxdWrStatus::kDone;
  }
};

struct AxdServer {
  AxdServer() : image(MakeImage()) {
    cycle = Extent(image, ModbusAddress::kHoldingRegister);
    block = cycle + 1;
    ModbusServer::Options o;
    o.cycle_register = cycle;
    o.on_cycle = [](uint32_t) {};
    o.axd_wr_register = block;
    o.axd_wr = [this](int axis, int ident, int64_t value) { return drive(axis, ident, value); };
    server = std::make_unique<ModbusServer>(image, o);
  }
  SignalImage image;
  int cycle = 0;
  int block = 0;
  Drive drive;
  std::unique_ptr<ModbusServer> server;
};

TEST(ModbusServerAxdWrTest, WriteRunsAxdWrAndTheResultReadsBack) {
  AxdServer s;
  WhilePolling(*s.server, [&] {
    Client c(s.server->port());
    uint16_t r[6] = {9, 9, 9, 9, 9, 9};
    ASSERT_EQ(modbus_read_registers(c.ctx, s.block, 6, r), 6);
    EXPECT_EQ(std::vector<uint16_t>(r, r + 6), (std::vector<uint16_t>{0, 0, 0, 0, 0, 0}));
    // Axis 1, S-0-0170, value 1: done; the drive has it when the write returns.
    const uint16_t req[4] = {1, 170, 0, 1};
    ASSERT_EQ(modbus_write_registers(c.ctx, s.block, 4, req), 4);
    ASSERT_EQ(s.drive.writes.size(), 1u);
    EXPECT_EQ(s.drive.writes[0], std::make_tuple(1, 170, int64_t{1}));
    ASSERT_EQ(modbus_read_registers(c.ctx, s.block, 6, r), 6);
    EXPECT_EQ(std::vector<uint16_t>(r, r + 6), (std::vector<uint16_t>{1, 170, 0, 1, 1, 1}));
    // A value the drive refuses is a result (3), not an exception; the count goes on.
    const uint16_t refused[4] = {1, 170, 0, 7};
    ASSERT_EQ(modbus_write_registers(c.ctx, s.block, 4, refused), 4);
    ASSERT_EQ(modbus_read_registers(c.ctx, s.block + 4, 2, r), 2);
    EXPECT_EQ(r[0], 3);
    EXPECT_EQ(r[1], 2);
    // An axis without a drive: 2.
    const uint16_t no_axis[4] = {5, 170, 0, 1};
    ASSERT_EQ(modbus_write_registers(c.ctx, s.block, 4, no_axis), 4);
    ASSERT_EQ(modbus_read_registers(c.ctx, s.block + 4, 1, r), 1);
    EXPECT_EQ(r[0], 2);
    // The value is a DINT, most significant word first: -2 reaches the drive as -2.
    const uint16_t negative[4] = {1, 170, 0xFFFF, 0xFFFE};
    ASSERT_EQ(modbus_write_registers(c.ctx, s.block, 4, negative), 4);
    EXPECT_EQ(s.drive.writes.back(), std::make_tuple(1, 170, int64_t{-2}));
    const uint16_t big[4] = {1, 169, 0x0001, 0x0002};
    ASSERT_EQ(modbus_write_registers(c.ctx, s.block, 4, big), 4);
    EXPECT_EQ(s.drive.writes.back(), std::make_tuple(1, 169, int64_t{0x10002}));
    // FC23: the write and the result in one transaction.
    ASSERT_EQ(modbus_write_and_read_registers(c.ctx, s.block, 4, req, s.block, 6, r), 6);
    EXPECT_EQ(std::vector<uint16_t>(r, r + 6), (std::vector<uint16_t>{1, 170, 0, 1, 1, 6}));
    // Readable together with the cycle register before it.
    uint16_t rr[3] = {};
    ASSERT_EQ(modbus_read_registers(c.ctx, s.cycle, 3, rr), 3);
    EXPECT_EQ(rr[1], 1);
    EXPECT_EQ(rr[2], 170);
  });
  EXPECT_EQ(s.server->stats().axd_writes, 6u);
  EXPECT_EQ(s.server->stats().cycles, 0u);
}

TEST(ModbusServerAxdWrTest, BadRequestsAreExceptionsAndRunNothing) {
  AxdServer s;
  WhilePolling(*s.server, [&] {
    Client c(s.server->port());
    const uint16_t req[6] = {1, 170, 0, 1, 0, 0};
    // Part of the block, more than the written part, the read-only registers, FC6: 02.
    EXPECT_EQ(modbus_write_registers(c.ctx, s.block, 3, req), -1);
    EXPECT_EQ(errno, EMBXILADD);
    EXPECT_EQ(modbus_write_registers(c.ctx, s.block + 1, 4, req), -1);
    EXPECT_EQ(errno, EMBXILADD);
    EXPECT_EQ(modbus_write_registers(c.ctx, s.block, 5, req), -1);
    EXPECT_EQ(errno, EMBXILADD);
    EXPECT_EQ(modbus_write_registers(c.ctx, s.block, 6, req), -1);
    EXPECT_EQ(errno, EMBXILADD);
    EXPECT_EQ(modbus_write_registers(c.ctx, s.block + 4, 2, req), -1);
    EXPECT_EQ(errno, EMBXILADD);
    EXPECT_EQ(modbus_write_register(c.ctx, s.block, 1), -1);
    EXPECT_EQ(errno, EMBXILADD);
    EXPECT_EQ(modbus_write_register(c.ctx, s.block + 4, 1), -1);
    EXPECT_EQ(errno, EMBXILADD);
    // Together with the signal registers before the cycle register: 02.
    std::vector<uint16_t> wide(s.block + 4 - (s.cycle - 2), 0);
    EXPECT_EQ(
        modbus_write_registers(c.ctx, s.cycle - 2, static_cast<int>(wide.size()), wide.data()), -1);
    EXPECT_EQ(errno, EMBXILADD);
    // FC23 writing part of the block: 02.
    uint16_t r[6] = {};
    EXPECT_EQ(modbus_write_and_read_registers(c.ctx, s.block, 2, req, s.block, 6, r), -1);
    EXPECT_EQ(errno, EMBXILADD);
    // Past the block: no register there.
    EXPECT_EQ(modbus_read_registers(c.ctx, s.block + 6, 1, r), -1);
    EXPECT_EQ(errno, EMBXILADD);
    // Axis 0, axis 33, ident 0: 03.
    const uint16_t axis0[4] = {0, 170, 0, 1};
    const uint16_t axis33[4] = {33, 170, 0, 1};
    const uint16_t ident0[4] = {1, 0, 0, 1};
    for (const uint16_t* bad : {axis0, axis33, ident0}) {
      EXPECT_EQ(modbus_write_registers(c.ctx, s.block, 4, bad), -1);
      EXPECT_EQ(errno, EMBXILVAL);
      EXPECT_EQ(modbus_write_and_read_registers(c.ctx, s.block, 4, bad, s.block, 6, r), -1);
      EXPECT_EQ(errno, EMBXILVAL);
    }
    // Nothing ran: the block still reads as before the first AXD_WR.
    ASSERT_EQ(modbus_read_registers(c.ctx, s.block, 6, r), 6);
    EXPECT_EQ(std::vector<uint16_t>(r, r + 6), (std::vector<uint16_t>{0, 0, 0, 0, 0, 0}));
  });
  EXPECT_TRUE(s.drive.writes.empty());
  // A writer that throws: 04, and the request does not count.
  s.drive.fail = true;
  WhilePolling(*s.server, [&] {
    Client c(s.server->port());
    const uint16_t req[4] = {1, 170, 0, 1};
    EXPECT_EQ(modbus_write_registers(c.ctx, s.block, 4, req), -1);
    EXPECT_EQ(errno, EMBXSFAIL);
    uint16_t r = 9;
    ASSERT_EQ(modbus_read_registers(c.ctx, s.block + 5, 1, &r), 1);
    EXPECT_EQ(r, 0);
  });
  EXPECT_EQ(s.server->stats().axd_writes, 0u);
}

TEST(ModbusServerAxdWrTest, OptionsThatMakeNoSenseAreRefused) {
  SignalImage image = MakeImage();
  const int end = Extent(image, ModbusAddress::kHoldingRegister);
  const AxdWriter writer = [](int, int, int64_t) { return AxdWrStatus::kDone; };
  ModbusServer::Options o;
  o.axd_wr_register = end;  // no writer
  EXPECT_THROW(ModbusServer(image, o), std::invalid_argument);
  o.axd_wr_register.reset();
  o.axd_wr = writer;  // no register
  EXPECT_THROW(ModbusServer(image, o), std::invalid_argument);
  o.axd_wr_register = end - 1;  // a signal's register
  EXPECT_THROW(ModbusServer(image, o), std::invalid_argument);
  o.axd_wr_register = end;
  o.cycle_register = end + 5;  // inside the block
  EXPECT_THROW(ModbusServer(image, o), std::invalid_argument);
  o.cycle_register.reset();
  o.axd_wr_register = 65531;  // B+5 beyond 65535
  EXPECT_THROW(ModbusServer(image, o), std::invalid_argument);
  o.axd_wr_register = -1;
  EXPECT_THROW(ModbusServer(image, o), std::invalid_argument);
  o.axd_wr_register = end;
  EXPECT_NO_THROW(ModbusServer(image, o));
}

}  // namespace
}  // namespace vmt::control::plc
