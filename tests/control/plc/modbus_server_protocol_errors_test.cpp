// The Modbus TCP server against bad requests: exception replies to well-framed requests it cannot
// serve, malformed frames that drop only their own connection, and random PDUs and bytes.

#include <gtest/gtest.h>
#include <modbus.h>

#include "control/plc/modbus_server.hpp"
#include "modbus_server_test_support.hpp"

namespace vmt::control::plc {
namespace {

using namespace testing;  // vmt::control::plc::testing

TEST_F(ModbusServerTest, RawFramesGetExceptions) {
  const ModbusAddress& start = At(image_, "P00C.START");
  const ModbusAddress& fovr = At(image_, "P00C.FOVR");
  WhilePolling(server_, [&] {
    Raw raw(server_.port());
    // Unknown function codes, including one with the exception bit, and FC22 (mask write),
    // which libmodbus would serve but this server does not offer.
    for (uint8_t fc : {0x00, 0x07, 0x11, 0x16, 0x2B, 0x41, 0x90, 0xFF}) {
      ASSERT_TRUE(raw.Send(Frame(fc, {fc, 0, 0, 0, 1})));
      EXPECT_EQ(raw.Receive(9), ExceptionReply(fc, fc, 0x01)) << int(fc);
    }
    // FC5 with a value other than 0x0000 / 0xFF00.
    ASSERT_TRUE(raw.Send(Frame(0x100, Pdu(0x05, start.address, 0x0001))));
    EXPECT_EQ(raw.Receive(9), ExceptionReply(0x100, 0x05, 0x03));
    // PDU length wrong for the function code (FC3 with one byte missing, one byte extra).
    ASSERT_TRUE(raw.Send(Frame(0x101, {0x03, 0, 0, 0})));
    EXPECT_EQ(raw.Receive(9), ExceptionReply(0x101, 0x03, 0x03));
    ASSERT_TRUE(raw.Send(Frame(0x102, {0x03, 0, 0, 0, 1, 0})));
    EXPECT_EQ(raw.Receive(9), ExceptionReply(0x102, 0x03, 0x03));
    // Quantities outside the protocol's limits.
    ASSERT_TRUE(raw.Send(Frame(0x103, Pdu(0x03, 0, 0))));
    EXPECT_EQ(raw.Receive(9), ExceptionReply(0x103, 0x03, 0x03));
    ASSERT_TRUE(raw.Send(Frame(0x104, Pdu(0x01, 0, 2001))));
    EXPECT_EQ(raw.Receive(9), ExceptionReply(0x104, 0x01, 0x03));
    // FC16 whose byte count does not match its quantity.
    std::vector<uint8_t> pdu = Pdu(0x10, fovr.address, 1);
    pdu.insert(pdu.end(), {4, 0, 1, 0, 2});
    ASSERT_TRUE(raw.Send(Frame(0x105, pdu)));
    EXPECT_EQ(raw.Receive(9), ExceptionReply(0x105, 0x10, 0x03));
    // FC15 whose byte count does not match its quantity.
    pdu = Pdu(0x0F, start.address, 9);
    pdu.insert(pdu.end(), {1, 0xFF});
    ASSERT_TRUE(raw.Send(Frame(0x106, pdu)));
    EXPECT_EQ(raw.Receive(9), ExceptionReply(0x106, 0x0F, 0x03));
    // Three requests in one segment: three replies, in order.
    std::vector<uint8_t> three;
    for (uint16_t tid : {0x201, 0x202, 0x203}) {
      const std::vector<uint8_t> f = Frame(tid, Pdu(0x03, fovr.address, 1));
      three.insert(three.end(), f.begin(), f.end());
    }
    ASSERT_TRUE(raw.Send(three));
    for (uint16_t tid : {0x201, 0x202, 0x203}) {
      const std::vector<uint8_t> r = raw.Receive(11);
      ASSERT_EQ(r.size(), 11u);
      EXPECT_EQ(r[0] << 8 | r[1], tid);
      EXPECT_EQ(r[7], 0x03);
      EXPECT_EQ(r[8], 2);
    }
    // Any unit id is served and echoed (0 and 255 are the usual ones over TCP).
    for (uint8_t unit : {0x00, 0xFF}) {
      std::vector<uint8_t> f = Frame(0x400 + unit, Pdu(0x03, fovr.address, 1));
      f[6] = unit;
      ASSERT_TRUE(raw.Send(f));
      const std::vector<uint8_t> r = raw.Receive(11);
      ASSERT_EQ(r.size(), 11u) << int(unit);
      EXPECT_EQ(r[6], unit);
      EXPECT_EQ(r[7], 0x03);
    }
    // A frame split across segments is put together.
    const std::vector<uint8_t> f = Frame(0x301, Pdu(0x03, fovr.address, 1));
    ASSERT_TRUE(raw.Send({f.begin(), f.begin() + 4}));
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_TRUE(raw.Send({f.begin() + 4, f.end()}));
    EXPECT_EQ(raw.Receive(11).size(), 11u);
  });
  EXPECT_EQ(image_.Bool(image_.Require("P00C.START")), false);
  EXPECT_EQ(server_.stats().exceptions_sent, 15u);
  EXPECT_EQ(server_.stats().requests_served, 6u);
  Drain(server_);
  EXPECT_EQ(server_.stats().clients_dropped, 1u);  // its own disconnect at the end
}

TEST_F(ModbusServerTest, MalformedFramesDropOnlyThatClient) {
  const ModbusAddress& fovr = At(image_, "P00C.FOVR");
  const std::vector<std::vector<uint8_t>> bad = {
      {'G', 'E', 'T', ' ', '/', ' ', 'H', 'T', 'T', 'P', '/', '1', '.', '1', '\r', '\n'},
      Frame(1, Pdu(0x03, 0, 1), /*protocol=*/1),
      Frame(2, Pdu(0x03, 0, 1), 0, /*length=*/0x0400),
      Frame(3, Pdu(0x03, 0, 1), 0, /*length=*/1),
      Frame(4, Pdu(0x03, 0, 1), 0, /*length=*/0),
  };
  WhilePolling(server_, [&] {
    // A client that stays connected through all of it.
    Client good(server_.port());
    uint16_t r = 0;
    ASSERT_EQ(modbus_read_registers(good.ctx, fovr.address, 1, &r), 1);
    for (size_t i = 0; i < bad.size(); ++i) {
      Raw raw(server_.port());
      ASSERT_TRUE(raw.Send(bad[i]));
      EXPECT_TRUE(raw.Closed()) << "frame " << i;
      EXPECT_EQ(modbus_read_registers(good.ctx, fovr.address, 1, &r), 1) << "after frame " << i;
    }
    // Truncated, then closed; and a header's worth of random bytes, then closed.
    {
      Raw raw(server_.port());
      const std::vector<uint8_t> f = Frame(5, Pdu(0x03, fovr.address, 1));
      ASSERT_TRUE(raw.Send({f.begin(), f.begin() + 9}));
    }
    {
      Raw raw(server_.port());
      ASSERT_TRUE(raw.Send({0x00, 0x01}));
    }
    // A new client after all that.
    Client late(server_.port());
    EXPECT_EQ(modbus_read_registers(late.ctx, fovr.address, 1, &r), 1);
    EXPECT_EQ(modbus_read_registers(good.ctx, fovr.address, 1, &r), 1);
  });
  Drain(server_);
  EXPECT_EQ(server_.clients(), 0);
  EXPECT_EQ(server_.stats().clients_accepted, 9u);
  EXPECT_EQ(server_.stats().clients_dropped, 9u);  // the two libmodbus clients closed too
  EXPECT_EQ(server_.stats().exceptions_sent, 0u);
}

// Frames with a correct MBAP header and random PDUs: each gets exactly one reply, normal or
// exception, with its transaction id, and the connection stays up.
TEST_F(ModbusServerTest, RandomPdusAlwaysGetAReply) {
  uint32_t state = 12345;
  const auto next = [&state] {
    state = state * 1664525u + 1013904223u;  // fixed LCG: the same frames every run
    return state >> 16;
  };
  const uint8_t codes[] = {1, 2, 3, 4, 5, 6, 15, 16, 23};
  const int holding = Extent(image_, ModbusAddress::kHoldingRegister);
  WhilePolling(server_, [&] {
    Raw raw(server_.port());
    for (int i = 0; i < 3000; ++i) {
      std::vector<uint8_t> pdu(1 + next() % 24);
      for (uint8_t& b : pdu) b = static_cast<uint8_t>(next());
      pdu[0] = next() % 4 == 0 ? static_cast<uint8_t>(next()) : codes[next() % 9];
      if (pdu.size() >= 5 && next() % 2 == 0) {  // plausible addresses and quantities
        const int address = static_cast<int>(next() % (holding + 4));
        pdu[1] = static_cast<uint8_t>(address >> 8);
        pdu[2] = static_cast<uint8_t>(address);
        pdu[3] = 0;
        pdu[4] = static_cast<uint8_t>(next() % 8);
        if (pdu.size() >= 6) pdu[5] = static_cast<uint8_t>(pdu.size() - 6);
      }
      const uint16_t tid = static_cast<uint16_t>(i);
      ASSERT_TRUE(raw.Send(Frame(tid, pdu)));
      const std::vector<uint8_t> head = raw.Receive(8);
      ASSERT_EQ(head.size(), 8u) << "frame " << i;
      EXPECT_EQ(head[0] << 8 | head[1], tid);
      EXPECT_TRUE(head[7] == pdu[0] || head[7] == (pdu[0] | 0x80)) << "frame " << i;
      const int rest = (head[4] << 8 | head[5]) - 2;
      ASSERT_GE(rest, 1);
      ASSERT_EQ(raw.Receive(rest).size(), static_cast<size_t>(rest));
    }
  });
  Drain(server_);
  EXPECT_EQ(server_.stats().requests_served + server_.stats().exceptions_sent, 3000u);
  EXPECT_EQ(server_.stats().clients_dropped, 1u);  // its own disconnect at the end
}

TEST(ModbusServerGarbageTest, RandomBytesThenAGoodClient) {
  SignalImage image = MakeImage();
  ModbusServer::Options o;
  o.max_clients = 64;  // the server may see the closes after the good client connects
  ModbusServer server(image, o);
  uint32_t state = 777;
  const auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return state >> 16;
  };
  WhilePolling(server, [&] {
    for (int i = 0; i < 50; ++i) {
      Raw raw(server.port());
      std::vector<uint8_t> bytes(1 + next() % 300);
      for (uint8_t& b : bytes) b = static_cast<uint8_t>(next());
      if (i % 2 == 0) bytes[2] = bytes[3] = 0;  // protocol id 0: the length decides
      raw.Send(bytes);                          // the server may already have closed: not checked
    }
    Client c(server.port());
    uint16_t r;
    EXPECT_EQ(modbus_read_registers(c.ctx, 0, 1, &r), 1);
  });
  Drain(server);
  EXPECT_EQ(server.clients(), 0);
  EXPECT_EQ(server.stats().clients_accepted, 51u);
}

}  // namespace
}  // namespace vmt::control::plc
