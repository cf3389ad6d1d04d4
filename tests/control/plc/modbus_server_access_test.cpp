// Who may connect to the Modbus TCP server and who may write: idle connections cannot lock the
// PLC out (the limit makes room, idle ones time out), only the PLC role writes and vmt's own
// signals are read only, unit ids, loopback unless allowed otherwise (IPv6 too), and a flood of
// pipelined requests that ServeUntil cuts off at its deadline without starving the PLC.

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <ifaddrs.h>
#include <modbus.h>
#include <net/if.h>

#include <chrono>
#include <optional>

#include "control/plc/modbus_server.hpp"
#include "modbus_server_test_support.hpp"

namespace vmt::control::plc {
namespace {

using namespace testing;  // vmt::control::plc::testing
using Clock = std::chrono::steady_clock;

std::vector<uint8_t> WithUnit(std::vector<uint8_t> frame, uint8_t unit) {
  frame[6] = unit;
  return frame;
}

TEST_F(ModbusServerTest, IdleConnectionsDoNotLockThePlcOut) {
  ModbusServer::Options o;
  o.client_timeout_ms = 300;
  ModbusServer server(image_, o);
  std::vector<std::unique_ptr<Raw>> idle;
  for (int i = 0; i < 10; ++i) {
    idle.push_back(std::make_unique<Raw>(server.port()));
    for (int k = 0; k < 200 && server.stats().clients_accepted < idle.size(); ++k) server.Poll(5);
  }
  ASSERT_EQ(server.clients(), 8);
  EXPECT_EQ(server.stats().clients_evicted, 2u);  // the two oldest made room
  const ModbusAddress& fovr = At(image_, "P00C.FOVR");
  WhilePolling(server, [&] {
    Client plc(server.port());
    ASSERT_EQ(modbus_write_register(plc.ctx, fovr.address, 42), 1);
    // The PLC keeps scanning; the idle ones are closed after the timeout, the PLC stays.
    for (int i = 0; i < 40; ++i) {
      uint16_t r = 0;
      ASSERT_EQ(modbus_read_registers(plc.ctx, fovr.address, 1, &r), 1);
      EXPECT_EQ(r, 42);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  EXPECT_EQ(image_.Int(image_.Require("P00C.FOVR")), 42);
  EXPECT_EQ(server.stats().clients_evicted, 3u);    // one more for the PLC
  EXPECT_EQ(server.stats().clients_timed_out, 7u);  // the rest, after 300 ms
  for (const auto& r : idle) EXPECT_TRUE(r->Closed());
}

// Monitors read; every write function from them is refused with 01 and changes nothing.
TEST_F(ModbusServerTest, OnlyThePlcWrites) {
  const ModbusAddress& fovr = At(image_, "P00C.FOVR");
  const ModbusAddress& coil = At(image_, "P00C.START");
  ModbusServer::Options o;
  o.cycle_register = Extent(image_, ModbusAddress::kHoldingRegister);
  ModbusServer server(image_, o);
  WhilePolling(server, [&] {
    Client plc(server.port());
    Client monitor(server.port());
    ASSERT_EQ(modbus_write_register(plc.ctx, fovr.address, 50), 1);
    uint16_t r[2] = {};
    uint8_t bits[1] = {1};
    EXPECT_EQ(modbus_read_registers(monitor.ctx, fovr.address, 1, r), 1);
    EXPECT_EQ(r[0], 50);
    const int refused[] = {
        modbus_write_bit(monitor.ctx, coil.address, 1),
        modbus_write_register(monitor.ctx, fovr.address, 7),
        modbus_write_bits(monitor.ctx, coil.address, 1, bits),
        modbus_write_registers(monitor.ctx, fovr.address, 1, r),
        modbus_write_and_read_registers(monitor.ctx, fovr.address, 1, r, fovr.address, 1, r),
        modbus_write_register(monitor.ctx, *o.cycle_register, 1),
    };
    for (int rc : refused) EXPECT_EQ(rc, -1);
    EXPECT_EQ(modbus_write_register(monitor.ctx, fovr.address, 7), -1);
    EXPECT_EQ(errno, EMBXILFUN);
    EXPECT_EQ(modbus_write_register(plc.ctx, fovr.address, 51), 1);
  });
  EXPECT_EQ(image_.Int(image_.Require("P00C.FOVR")), 51);
  EXPECT_FALSE(image_.Bool(image_.Require("P00C.START")));
  EXPECT_EQ(server.cycle(), 0u);
  EXPECT_EQ(server.stats().writes_refused, 7u);
  EXPECT_EQ(server.stats().writes, 2u);
}

// The role passes on when the PLC's connection closes, or after plc_role_timeout_ms without a
// write from it (a PLC that reconnects while its old connection still looks open).
TEST_F(ModbusServerTest, ThePlcRolePassesOn) {
  const int fovr = At(image_, "P00C.FOVR").address;
  ModbusServer::Options o;
  o.plc_role_timeout_ms = 150;
  ModbusServer server(image_, o);
  WhilePolling(server, [&] {
    {
      Client first(server.port());
      ASSERT_EQ(modbus_write_register(first.ctx, fovr, 1), 1);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(30));  // its close is seen
    Client old_plc(server.port());
    ASSERT_EQ(modbus_write_register(old_plc.ctx, fovr, 2), 1);
    Client new_plc(server.port());
    EXPECT_EQ(modbus_write_register(new_plc.ctx, fovr, 3), -1);  // the role is taken
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    EXPECT_EQ(modbus_write_register(new_plc.ctx, fovr, 4), 1);  // the old PLC has gone quiet
    EXPECT_EQ(modbus_write_register(old_plc.ctx, fovr, 5), -1);
  });
  EXPECT_EQ(image_.Int(image_.Require("P00C.FOVR")), 4);
  EXPECT_EQ(server.stats().writes_refused, 2u);
}

// What vmt drives (the NC, the machine) lies in the read-only areas: a write to such an address
// meets no coil or holding register, and a table that put one there is refused.
TEST_F(ModbusServerTest, VmtsSignalsAreReadOnly) {
  for (const Signal& s : image_.table()) {
    if (gateway::PlcWrites(s.direction)) continue;
    EXPECT_TRUE(s.modbus.area == ModbusAddress::kDiscreteInput ||
                s.modbus.area == ModbusAddress::kInputRegister)
        << s.name;
  }
  const int past_coils = Extent(image_, ModbusAddress::kCoil);
  const int past_holding = Extent(image_, ModbusAddress::kHoldingRegister);
  WhilePolling(server_, [&] {
    Client plc(server_.port());
    EXPECT_EQ(modbus_write_bit(plc.ctx, past_coils, 1), -1);
    EXPECT_EQ(errno, EMBXILADD);
    EXPECT_EQ(modbus_write_register(plc.ctx, past_holding + 1, 1), -1);
    EXPECT_EQ(errno, EMBXILADD);
  });
  std::vector<Signal> table = image_.table();
  for (Signal& s : table) {
    if (s.direction == gateway::Direction::kNcToPlc && s.type == SignalType::kBool) {
      s.modbus = {ModbusAddress::kCoil, past_coils, 1};
      break;
    }
  }
  SignalImage wrong(std::move(table));
  try {
    ModbusServer bad(wrong, {});
    ADD_FAILURE() << "an NC signal in the coils was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("written by vmt"), std::string::npos) << e.what();
  }
}

// The configured unit id, 0 and 255 are this server; another is a device it does not have:
// exception 0B, the unit id echoed, nothing done.
TEST(ModbusServerUnitTest, OtherUnitIdsGetGatewayTargetFailed) {
  SignalImage image = MakeImage();
  ModbusServer::Options o;
  o.unit_id = 17;
  ModbusServer server(image, o);
  const int fovr = At(image, "P00C.FOVR").address;
  WhilePolling(server, [&] {
    Raw raw(server.port());
    for (const uint8_t unit : {17, 0, 255}) {
      ASSERT_TRUE(raw.Send(WithUnit(Frame(unit, Pdu(0x03, fovr, 1)), unit)));
      const std::vector<uint8_t> reply = raw.Receive(11);
      ASSERT_EQ(reply.size(), 11u) << int(unit);
      EXPECT_EQ(reply[6], unit);
      EXPECT_EQ(reply[7], 0x03);
    }
    for (const uint8_t unit : {1, 2, 247}) {
      ASSERT_TRUE(raw.Send(WithUnit(Frame(unit, Pdu(0x06, fovr, 9)), unit)));
      std::vector<uint8_t> expected = ExceptionReply(unit, 0x06, 0x0B);
      expected[6] = unit;
      EXPECT_EQ(raw.Receive(9), expected) << int(unit);
    }
  });
  EXPECT_EQ(server.stats().wrong_unit, 3u);
  EXPECT_NE(image.Int(image.Require("P00C.FOVR")), 9);
  o.unit_id = 0;
  EXPECT_THROW(ModbusServer(image, o), std::invalid_argument);
  o.unit_id = 248;
  EXPECT_THROW(ModbusServer(image, o), std::invalid_argument);
}

// Every address, not loopback: only with allow_remote.
TEST(ModbusServerRemoteTest, OffLoopbackNeedsAllowRemote) {
  SignalImage image = MakeImage();
  ModbusServer::Options o;
  o.host = "0.0.0.0";
  try {
    ModbusServer server(image, o);
    ADD_FAILURE() << "listening on 0.0.0.0 without allow_remote";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--allow-remote"), std::string::npos) << e.what();
  }
  o.allow_remote = true;
  ModbusServer open(image, o);
  EXPECT_TRUE(open.remote());
  EXPECT_FALSE(ModbusServer(image, {}).remote());
  o.allowed_clients = {"plc.example"};
  EXPECT_THROW(ModbusServer(image, o), std::invalid_argument);
}

// A numeric, non-loopback IPv4 address of this machine, if it has one that is up.
std::optional<std::string> LocalAddress() {
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return std::nullopt;
  std::optional<std::string> found;
  for (ifaddrs* i = list; i != nullptr && !found; i = i->ifa_next) {
    if (i->ifa_addr == nullptr || i->ifa_addr->sa_family != AF_INET ||
        (i->ifa_flags & IFF_UP) == 0 || (i->ifa_flags & IFF_LOOPBACK) != 0) {
      continue;
    }
    char text[INET_ADDRSTRLEN];
    inet_ntop(AF_INET, &reinterpret_cast<sockaddr_in*>(i->ifa_addr)->sin_addr, text, sizeof text);
    found = text;
  }
  freeifaddrs(list);
  return found;
}

// With allowed clients, a connection from another address is closed at accept.
TEST(ModbusServerRemoteTest, AllowedClientsOnly) {
  const std::optional<std::string> local = LocalAddress();
  if (!local) GTEST_SKIP() << "no network address besides loopback";
  SignalImage image = MakeImage();
  ModbusServer::Options o;
  o.host = *local;
  o.allow_remote = true;
  o.allowed_clients = {"192.0.2.7"};
  ModbusServer server(image, o);
  WhilePolling(server, [&] {
    modbus_t* ctx = modbus_new_tcp(local->c_str(), server.port());
    ASSERT_NE(ctx, nullptr);
    uint16_t r;
    EXPECT_TRUE(modbus_connect(ctx) != 0 || modbus_read_registers(ctx, 0, 1, &r) == -1);
    modbus_free(ctx);
  });
  EXPECT_EQ(server.stats().clients_not_allowed, 1u);
  o.allowed_clients = {"192.0.2.7", *local};
  ModbusServer allowing(image, o);
  WhilePolling(allowing, [&] {
    modbus_t* ctx = modbus_new_tcp(local->c_str(), allowing.port());
    ASSERT_EQ(modbus_connect(ctx), 0);
    uint16_t r;
    EXPECT_EQ(modbus_read_registers(ctx, 0, 1, &r), 1);
    modbus_close(ctx);
    modbus_free(ctx);
  });
  EXPECT_EQ(allowing.stats().clients_not_allowed, 0u);
}

TEST(ModbusServerRemoteTest, Ipv6Loopback) {
  SignalImage image = MakeImage();
  ModbusServer::Options o;
  o.host = "::1";
  std::optional<ModbusServer> server;
  try {
    server.emplace(image, o);
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "no IPv6 loopback here: " << e.what();
  }
  EXPECT_FALSE(server->remote());
  WhilePolling(*server, [&] {
    modbus_t* ctx = modbus_new_tcp_pi("::1", std::to_string(server->port()).c_str());
    ASSERT_NE(ctx, nullptr);
    ASSERT_EQ(modbus_connect(ctx), 0) << modbus_strerror(errno);
    uint16_t r;
    EXPECT_EQ(modbus_read_registers(ctx, 0, 1, &r), 1);
    EXPECT_EQ(modbus_write_register(ctx, At(image, "P00C.FOVR").address, 33), 1);
    modbus_close(ctx);
    modbus_free(ctx);
  });
  EXPECT_EQ(image.Int(image.Require("P00C.FOVR")), 33);
}

// A client with thousands of reads in flight: ServeUntil returns at its deadline with requests
// left over, and the PLC's one request, sent after the flood, is answered in that first call.
TEST_F(ModbusServerTest, ServeUntilKeepsItsDeadlineUnderAFlood) {
  constexpr int kFlood = 20000;
  Raw flood(server_.port());
  Raw plc(server_.port());
  for (int i = 0; i < 200 && server_.clients() < 2; ++i) server_.Poll(5);
  ASSERT_EQ(server_.clients(), 2);
  std::vector<uint8_t> requests;
  for (int i = 0; i < kFlood; ++i) {
    const std::vector<uint8_t> f = Frame(static_cast<uint16_t>(i), Pdu(0x04, 0, 1));
    requests.insert(requests.end(), f.begin(), f.end());
  }
  std::thread sender([&] { flood.Send(requests); });  // blocks while the server holds back
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(plc.Send(Frame(1, Pdu(0x03, At(image_, "P00C.FOVR").address, 1))));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const auto start = Clock::now();
  server_.ServeUntil(start + std::chrono::milliseconds(2));
  const auto took = Clock::now() - start;
  EXPECT_LT(took, std::chrono::milliseconds(50));  // 2 ms and one request, with slack
  EXPECT_LT(server_.stats().requests(), static_cast<uint64_t>(kFlood));
  EXPECT_EQ(plc.Receive(11).size(), 11u);
  // The rest is served by later calls, none of them past its deadline by much.
  std::thread reader([&] { flood.Receive(static_cast<size_t>(kFlood) * 11); });
  for (int i = 0; i < 5000 && server_.stats().requests() < kFlood + 1u; ++i) {
    const auto t0 = Clock::now();
    server_.ServeUntil(t0 + std::chrono::milliseconds(1));
    EXPECT_LT(Clock::now() - t0, std::chrono::milliseconds(50));
  }
  sender.join();
  reader.join();
  EXPECT_EQ(server_.stats().requests(), kFlood + 1u);
}

// A caller already late (catching up on cycles) still has each client's next request answered,
// one per client and no more.
TEST_F(ModbusServerTest, ALateCallAnswersOneRequestPerClient) {
  Raw plc(server_.port());
  Raw monitor(server_.port());
  for (int i = 0; i < 200 && server_.clients() < 2; ++i) server_.Poll(5);
  ASSERT_EQ(server_.clients(), 2);
  const std::vector<uint8_t> f = Frame(1, Pdu(0x03, At(image_, "P00C.FOVR").address, 1));
  ASSERT_TRUE(plc.Send(f));
  ASSERT_TRUE(monitor.Send(f) && monitor.Send(f) && monitor.Send(f));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  server_.ServeUntil(Clock::now() - std::chrono::milliseconds(10));
  EXPECT_EQ(server_.stats().requests(), 2u);
  EXPECT_EQ(plc.Receive(11).size(), 11u);
  server_.ServeUntil(Clock::now() - std::chrono::milliseconds(10));
  EXPECT_EQ(server_.stats().requests(), 3u);
}

}  // namespace
}  // namespace vmt::control::plc
