// The Modbus TCP server's lockstep handshake: a write of the next number to the cycle register
// runs one simulation cycle, the number wraps at 65536, and a cycle may not drop the clients.

#include <gtest/gtest.h>
#include <modbus.h>

#include "control/plc/modbus_server.hpp"
#include "modbus_server_test_support.hpp"

namespace vmt::control::plc {
namespace {

using namespace testing;  // vmt::control::plc::testing

TEST(ModbusServerCycleTest, DropClientsFromInsideACycleAborts) {
  SignalImage image = MakeImage();
  ModbusServer::Options o;
  o.cycle_register = Extent(image, ModbusAddress::kHoldingRegister);
  ModbusServer* self = nullptr;
  o.on_cycle = [&self](uint32_t) { self->DropClients(); };
  ModbusServer server(image, o);
  self = &server;
  EXPECT_DEATH(
      {
        Raw raw(server.port());
        raw.Send(Frame(1, Pdu(0x06, *o.cycle_register, 1)));
        for (int i = 0; i < 200; ++i) server.Poll(10);
      },
      "DropClients called from inside Poll");
}

TEST(ModbusServerCycleTest, HandshakeRunsOneCyclePerWrite) {
  SignalImage image = MakeImage();
  const int holding = Extent(image, ModbusAddress::kHoldingRegister);
  const int count_r = image.Require("P00.mc_cmd_bs_pos_start_count_r");  // INT input register
  const int count_address = image.table()[count_r].modbus.address;
  std::atomic<int> calls{0};
  std::vector<uint32_t> seen;
  bool fail_next = false;
  ModbusServer::Options o;
  o.cycle_register = holding;
  o.on_cycle = [&](uint32_t cycle) {
    if (fail_next) {
      fail_next = false;
      throw std::runtime_error("the simulation failed");
    }
    seen.push_back(cycle);
    // The cycle's result: visible to the client as soon as its write has completed.
    image.SetInt(count_r, static_cast<int64_t>(cycle) * 10);
    ++calls;
  };
  ModbusServer server(image, o);

  WhilePolling(server, [&] {
    Client c(server.port());
    uint16_t r = 0xFFFF;
    ASSERT_EQ(modbus_read_registers(c.ctx, holding, 1, &r), 1);
    EXPECT_EQ(r, 0);
    // FC6 with the next number: the cycle has run when the write returns.
    ASSERT_EQ(modbus_write_register(c.ctx, holding, 1), 1);
    EXPECT_EQ(calls, 1);
    ASSERT_EQ(modbus_read_input_registers(c.ctx, count_address, 1, &r), 1);
    EXPECT_EQ(r, 10);
    // The same number again (a retry after a lost reply): refused, nothing runs.
    EXPECT_EQ(modbus_write_register(c.ctx, holding, 1), -1);
    EXPECT_EQ(errno, EMBXILVAL);
    EXPECT_EQ(modbus_write_register(c.ctx, holding, 3), -1);
    EXPECT_EQ(errno, EMBXILVAL);
    EXPECT_EQ(calls, 1);
    // FC16 of exactly the cycle register.
    const uint16_t two = 2;
    ASSERT_EQ(modbus_write_registers(c.ctx, holding, 1, &two), 1);
    EXPECT_EQ(calls, 2);
    ASSERT_EQ(modbus_read_input_registers(c.ctx, count_address, 1, &r), 1);
    EXPECT_EQ(r, 20);
    // Together with another register: refused.
    const uint16_t pair[2] = {0, 3};
    EXPECT_EQ(modbus_write_registers(c.ctx, holding - 1, 2, pair), -1);
    EXPECT_EQ(errno, EMBXILADD);
    // Readable together with the signals before it.
    uint16_t rr[2] = {};
    ASSERT_EQ(modbus_read_registers(c.ctx, holding - 1, 2, rr), 2);
    EXPECT_EQ(rr[1], 2);
    // FC23 does not drive the cycle.
    EXPECT_EQ(modbus_write_and_read_registers(c.ctx, holding, 1, &pair[1], holding, 1, rr), -1);
    EXPECT_EQ(errno, EMBXILADD);
    EXPECT_EQ(calls, 2);
  });
  // A callback that throws: exception 04 to the client, the cycle does not count.
  fail_next = true;
  WhilePolling(server, [&] {
    Client c(server.port());
    EXPECT_EQ(modbus_write_register(c.ctx, holding, 3), -1);
    EXPECT_EQ(errno, EMBXSFAIL);
    EXPECT_EQ(modbus_write_register(c.ctx, holding, 3), 1);
  });
  EXPECT_EQ(seen, (std::vector<uint32_t>{1, 2, 3}));
  EXPECT_EQ(server.cycle(), 3u);
  EXPECT_EQ(server.stats().cycles, 3u);
}

TEST(ModbusServerCycleTest, CycleNumberWrapsAt65536) {
  SignalImage image = MakeImage();
  const int holding = Extent(image, ModbusAddress::kHoldingRegister);
  uint32_t last = 0;
  ModbusServer::Options o;
  o.cycle_register = holding;
  o.on_cycle = [&](uint32_t cycle) { last = cycle; };
  ModbusServer server(image, o);
  // Drive the counter to 65535 over a raw socket without a round trip per cycle: pipelined
  // writes, one frame each, replies read in bulk.
  WhilePolling(server, [&] {
    Raw raw(server.port());
    std::vector<uint8_t> batch;
    constexpr int kBatch = 256;
    for (int v = 1; v <= 65536; ++v) {
      const std::vector<uint8_t> f =
          Frame(static_cast<uint16_t>(v), Pdu(0x06, holding, static_cast<uint16_t>(v)));
      batch.insert(batch.end(), f.begin(), f.end());
      if (v % kBatch == 0) {
        ASSERT_TRUE(raw.Send(batch));
        ASSERT_EQ(raw.Receive(batch.size()), batch) << "at " << v;  // FC6 replies echo
        batch.clear();
      }
    }
  });
  EXPECT_EQ(last, 65536u);
  EXPECT_EQ(server.cycle(), 65536u);
  WhilePolling(server, [&] {
    Client c(server.port());
    uint16_t r = 0xFFFF;
    ASSERT_EQ(modbus_read_registers(c.ctx, holding, 1, &r), 1);
    EXPECT_EQ(r, 0);
    EXPECT_EQ(modbus_write_register(c.ctx, holding, 1), 1);
  });
  EXPECT_EQ(last, 65537u);
}

}  // namespace
}  // namespace vmt::control::plc
