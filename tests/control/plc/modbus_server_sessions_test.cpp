// The Modbus TCP server's connections: a client gone mid-request, a partial frame that must not
// block the simulation's poll, a PLC and a monitor at once, the client limit, and dropping every
// client (vmt serve's client_gone fault).

#include <gtest/gtest.h>
#include <modbus.h>

#include <chrono>

#include "control/plc/modbus_server.hpp"
#include "modbus_server_test_support.hpp"

namespace vmt::control::plc {
namespace {

using namespace testing;  // vmt::control::plc::testing

TEST_F(ModbusServerTest, DisconnectMidRequest) {
  const ModbusAddress& fovr = At(image_, "P00C.FOVR");
  const int64_t preset = image_.Int(image_.Require("P00C.FOVR"));
  ASSERT_NE(preset, 9);
  WhilePolling(server_, [&] {
    Client other(server_.port());
    Raw raw(server_.port());
    std::vector<uint8_t> pdu = Pdu(0x10, fovr.address, 1);
    pdu.insert(pdu.end(), {2, 0x00, 0x09});
    const std::vector<uint8_t> f = Frame(7, pdu);
    ASSERT_TRUE(raw.Send({f.begin(), f.end() - 1}));  // all but the last byte
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    raw.Close();
    uint16_t r = 0xFFFF;
    EXPECT_EQ(modbus_read_registers(other.ctx, fovr.address, 1, &r), 1);
    EXPECT_EQ(r, preset);  // the partial write of 9 was not applied
  });
  EXPECT_EQ(image_.Int(image_.Require("P00C.FOVR")), preset);
}

TEST_F(ModbusServerTest, PartialFrameDoesNotBlockPoll) {
  // No helper thread: the connection completes in the listen backlog, so this thread can be the
  // client and the server in turn. A server that waited for the rest of the frame would block.
  Raw raw(server_.port());
  for (int i = 0; i < 100 && server_.clients() == 0; ++i) server_.Poll(10);
  ASSERT_EQ(server_.clients(), 1);
  const std::vector<uint8_t> f = Frame(1, Pdu(0x03, 0, 1));
  ASSERT_TRUE(raw.Send({f.begin(), f.begin() + 8}));
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < 10; ++i) server_.Poll(0);
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::milliseconds(200));
  ASSERT_TRUE(raw.Send({f.begin() + 8, f.end()}));
  for (int i = 0; i < 100 && server_.stats().requests_served == 0; ++i) server_.Poll(10);
  EXPECT_EQ(raw.Receive(11).size(), 11u);
}

// The PLC writes and reads back while a monitor reads at the same time; the monitor's write is
// refused (the PLC role, modbus_server.hpp) and changes nothing.
TEST_F(ModbusServerTest, ThePlcWritesWhileAMonitorReads) {
  const int fovr = image_.Require("P00C.FOVR");
  const int dint = image_.Require("P00.MSG_WR_N");
  std::atomic<int> failures{0};
  std::atomic<bool> plc_wrote{false};
  std::atomic<bool> monitor_done{false};
  WhilePolling(server_, [&] {
    std::thread plc([&] {
      Client c(server_.port());
      for (int i = 1; i <= 200; ++i) {
        uint16_t w[2] = {0, static_cast<uint16_t>(i)};
        uint16_t r[2] = {};
        if (modbus_write_registers(c.ctx, At(image_, "P00.MSG_WR_N").address, 2, w) != 2 ||
            modbus_write_register(c.ctx, At(image_, "P00C.FOVR").address, i) != 1 ||
            modbus_read_registers(c.ctx, At(image_, "P00.MSG_WR_N").address, 2, r) != 2 ||
            r[1] != i) {
          ++failures;
        }
        plc_wrote = true;
      }
      // Connected until the monitor is done: a closed PLC leaves the role to the next writer.
      while (!monitor_done) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    });
    std::thread monitor([&] {
      Client c(server_.port());
      while (!plc_wrote) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      for (int i = 1; i <= 200; ++i) {
        uint16_t r[2] = {};
        if (modbus_read_registers(c.ctx, At(image_, "P00.MSG_WR_N").address, 2, r) != 2 ||
            modbus_read_registers(c.ctx, At(image_, "P00C.FOVR").address, 1, r) != 1) {
          ++failures;
        }
      }
      if (modbus_write_register(c.ctx, At(image_, "P00C.FOVR").address, 7) != -1 ||
          errno != EMBXILFUN) {
        ++failures;
      }
      monitor_done = true;
    });
    plc.join();
    monitor.join();
  });
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(image_.Int(fovr), 200);
  EXPECT_EQ(image_.Int(dint), 200);
  EXPECT_EQ(server_.stats().requests_served, 1000u);
  EXPECT_EQ(server_.stats().writes_refused, 1u);
}

// At the limit a new connection closes the longest idle one, never the PLC's: with room for one,
// a monitor gives way, the PLC does not.
TEST_F(ModbusServerTest, MaxClientsMakesRoomButNotFromThePlc) {
  ModbusServer::Options o;
  o.max_clients = 1;
  ModbusServer one(image_, o);
  WhilePolling(one, [&] {
    Raw monitor(one.port());
    Client plc(one.port());
    EXPECT_TRUE(monitor.Closed());
    ASSERT_EQ(modbus_write_register(plc.ctx, At(image_, "P00C.FOVR").address, 5), 1);
    Raw refused(one.port());
    EXPECT_TRUE(refused.Closed());
    uint16_t r;
    EXPECT_EQ(modbus_read_registers(plc.ctx, 0, 1, &r), 1);
  });
  EXPECT_EQ(one.stats().clients_evicted, 1u);
  EXPECT_EQ(one.stats().clients_refused, 1u);
}

// The PLC's link goes down (vmt serve's client_gone fault): every connection closes, and the
// server goes on accepting and serving.
TEST_F(ModbusServerTest, DropClientsClosesEveryConnectionAndServesNewOnes) {
  const ModbusAddress& fovr = At(image_, "P00C.FOVR");
  Raw a(server_.port());
  Raw b(server_.port());
  for (int i = 0; i < 200 && server_.clients() < 2; ++i) server_.Poll(10);
  ASSERT_EQ(server_.clients(), 2);
  // A request half sent when the link goes is discarded with it.
  const std::vector<uint8_t> f = Frame(1, Pdu(0x03, fovr.address, 1));
  ASSERT_TRUE(b.Send({f.begin(), f.begin() + 9}));
  server_.Poll(10);
  server_.DropClients();
  EXPECT_EQ(server_.clients(), 0);
  EXPECT_EQ(server_.stats().clients_dropped, 2u);
  EXPECT_TRUE(a.Closed());
  EXPECT_TRUE(b.Closed());
  server_.DropClients();  // none left: nothing happens
  EXPECT_EQ(server_.stats().clients_dropped, 2u);

  Raw c(server_.port());
  ASSERT_TRUE(c.Send(f));
  for (int i = 0; i < 200 && server_.stats().requests() == 0; ++i) server_.Poll(10);
  EXPECT_EQ(c.Receive(11).size(), 11u);
  EXPECT_EQ(server_.clients(), 1);
  EXPECT_EQ(server_.stats().clients_accepted, 3u);
  EXPECT_EQ(server_.stats().requests(), 1u);
}

}  // namespace
}  // namespace vmt::control::plc
