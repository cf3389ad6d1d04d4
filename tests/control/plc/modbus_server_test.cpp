#include "control/plc/modbus_server.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <modbus.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cerrno>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace vmt::control::plc {
namespace {

using gateway::ModbusAddress;
using gateway::Signal;
using gateway::SignalImage;
using gateway::SignalType;

// A small machine: one process, a linear axis and a spindle, two I/O points; plus one REAL
// holding register, a type the catalog has no PLC-written family of.
SignalImage MakeImage() {
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

int Extent(const SignalImage& image, ModbusAddress::Area area) {
  int end = 0;
  for (const Signal& s : image.table()) {
    if (s.modbus.area == area) end = std::max(end, s.modbus.address + s.modbus.count);
  }
  return end;
}

const ModbusAddress& At(const SignalImage& image, const char* name) {
  return image.table()[image.Require(name)].modbus;
}

// Runs `client` on its own thread while this thread polls the server, the way a simulation loop
// would; returns when the client is done.
void WhilePolling(ModbusServer& server, const std::function<void()>& client) {
  std::atomic<bool> done{false};
  std::thread t([&] {
    client();
    done = true;
  });
  while (!done) server.Poll(2);
  t.join();
}

// Polls until every client's disconnect has been seen (the client threads have closed theirs).
void Drain(ModbusServer& server) {
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

std::vector<uint8_t> Frame(uint16_t tid, const std::vector<uint8_t>& pdu, uint16_t protocol = 0,
                           int length = -1) {
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

std::vector<uint8_t> Pdu(uint8_t function, int a, int b) {
  return {function, static_cast<uint8_t>(a >> 8), static_cast<uint8_t>(a),
          static_cast<uint8_t>(b >> 8), static_cast<uint8_t>(b)};
}

// The exception reply to Frame(tid, {function, ...}).
std::vector<uint8_t> ExceptionReply(uint16_t tid, uint8_t function, uint8_t code) {
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

std::vector<uint16_t> Registers(const SignalImage& image, int id) {
  std::vector<uint16_t> w(image.table()[id].modbus.count);
  ToRegisters(image, id, w);
  return w;
}

class ModbusServerTest : public ::testing::Test {
 protected:
  SignalImage image_ = MakeImage();
  ModbusServer server_{image_, {}};
};

TEST_F(ModbusServerTest, ReadsEveryAreaAsTheImageHoldsIt) {
  image_.SetBool(image_.Require("P00C.START"), true);
  image_.SetBool(image_.Require("P00S.CREST"), true);
  image_.SetBool(image_.Require("ISWITCH"), true);
  image_.SetInt(image_.Require("P00C.FOVR"), -7);
  image_.SetInt(image_.Require("P00.mc_cmd_bs_pos_start_offset_r"), -123456);
  image_.SetReal(image_.Require("P00.mc_cmd_bs_breakpoint_position_r"), 12.625);
  image_.SetString(image_.Require("P00.mc_cmd_bs_pos_start_name_r"), "MAIN.NC");

  // What the PLC must see: every bit and register of every area, from the image.
  std::vector<std::vector<uint16_t>> want(4);
  for (int a = 0; a < 4; ++a) {
    want[a].assign(Extent(image_, static_cast<ModbusAddress::Area>(a)), 0);
  }
  for (int id = 0; id < image_.size(); ++id) {
    const ModbusAddress& m = image_.table()[id].modbus;
    if (m.area == ModbusAddress::kCoil || m.area == ModbusAddress::kDiscreteInput) {
      want[m.area][m.address] = image_.Bool(id);
    } else {
      const std::vector<uint16_t> w = Registers(image_, id);
      std::copy(w.begin(), w.end(), want[m.area].begin() + m.address);
    }
  }
  for (int a = 0; a < 4; ++a) ASSERT_GT(want[a].size(), 0u) << a;

  std::vector<std::vector<uint16_t>> got(4);
  WhilePolling(server_, [&] {
    Client c(server_.port());
    for (int a = 0; a < 4; ++a) {
      const int n = static_cast<int>(want[a].size());
      got[a].assign(n, 0xDEAD);
      const bool bits = a == ModbusAddress::kCoil || a == ModbusAddress::kDiscreteInput;
      const int chunk = bits ? 2000 : 125;
      std::vector<uint8_t> b(chunk);
      for (int at = 0; at < n; at += chunk) {
        const int k = std::min(chunk, n - at);
        int rc = -1;
        switch (a) {
          case ModbusAddress::kCoil:
            rc = modbus_read_bits(c.ctx, at, k, b.data());
            break;
          case ModbusAddress::kDiscreteInput:
            rc = modbus_read_input_bits(c.ctx, at, k, b.data());
            break;
          case ModbusAddress::kHoldingRegister:
            rc = modbus_read_registers(c.ctx, at, k, got[a].data() + at);
            break;
          default:
            rc = modbus_read_input_registers(c.ctx, at, k, got[a].data() + at);
        }
        ASSERT_EQ(rc, k) << "area " << a << " at " << at << ": " << modbus_strerror(errno);
        if (bits) std::copy(b.begin(), b.begin() + k, got[a].begin() + at);
      }
    }
    // A read may start inside a multi-register signal: the second word of the LREAL alone.
    const ModbusAddress& lreal = At(image_, "P00.mc_cmd_bs_breakpoint_position_r");
    uint16_t one = 0;
    ASSERT_EQ(modbus_read_input_registers(c.ctx, lreal.address + 1, 1, &one), 1);
    EXPECT_EQ(one, want[ModbusAddress::kInputRegister][lreal.address + 1]);
  });
  for (int a = 0; a < 4; ++a) EXPECT_EQ(got[a], want[a]) << "area " << a;
  EXPECT_EQ(server_.stats().exceptions_sent, 0u);
  EXPECT_EQ(server_.stats().clients_accepted, 1u);
}

TEST_F(ModbusServerTest, WritesReachTheImage) {
  const int start = image_.Require("P00C.START");
  const int stop = image_.Require("P00C.STOP");
  const int valve = image_.Require("QVALVE");
  const int fovr = image_.Require("P00C.FOVR");
  const int dint = image_.Require("P00.MSG_WR_N");
  const int real = image_.Require("TEST.REAL_W");
  const int lreal = image_.Require("P00.mc_cmd_bs_breakpoint_position_w");
  const int name = image_.Require("P00.mc_cmd_bs_pos_start_name_w");

  WhilePolling(server_, [&] {
    Client c(server_.port());
    EXPECT_EQ(modbus_write_bit(c.ctx, At(image_, "P00C.START").address, 1), 1);
    // STOP and the valve are far apart: two single writes; FC15 over STOP and its neighbour.
    EXPECT_EQ(modbus_write_bit(c.ctx, At(image_, "QVALVE").address, 1), 1);
    const uint8_t bits[2] = {1, 0};
    EXPECT_EQ(modbus_write_bits(c.ctx, At(image_, "P00C.STOP").address, 2, bits), 2);
    EXPECT_EQ(modbus_write_register(c.ctx, At(image_, "P00C.FOVR").address, 0xFFF9), 1);  // -7

    const int32_t d = -123456;
    const uint16_t dw[2] = {static_cast<uint16_t>(static_cast<uint32_t>(d) >> 16),
                            static_cast<uint16_t>(d)};
    EXPECT_EQ(modbus_write_registers(c.ctx, At(image_, "P00.MSG_WR_N").address, 2, dw), 2);

    const uint32_t f = std::bit_cast<uint32_t>(3.14159f);
    const uint16_t fw[2] = {static_cast<uint16_t>(f >> 16), static_cast<uint16_t>(f)};
    EXPECT_EQ(modbus_write_registers(c.ctx, At(image_, "TEST.REAL_W").address, 2, fw), 2);

    const uint64_t l = std::bit_cast<uint64_t>(-2.5e-3);
    const uint16_t lw[4] = {static_cast<uint16_t>(l >> 48), static_cast<uint16_t>(l >> 32),
                            static_cast<uint16_t>(l >> 16), static_cast<uint16_t>(l)};
    EXPECT_EQ(modbus_write_registers(
                  c.ctx, At(image_, "P00.mc_cmd_bs_breakpoint_position_w").address, 4, lw),
              4);

    std::vector<uint16_t> sw(gateway::kStringBytes / 2, 0);
    sw[0] = 'P' << 8 | '1';
    sw[1] = '2' << 8 | '3';
    EXPECT_EQ(modbus_write_registers(c.ctx, At(image_, "P00.mc_cmd_bs_pos_start_name_w").address,
                                     static_cast<int>(sw.size()), sw.data()),
              static_cast<int>(sw.size()));

    // Round trip: what was written reads back.
    uint16_t back[2] = {};
    EXPECT_EQ(modbus_read_registers(c.ctx, At(image_, "TEST.REAL_W").address, 2, back), 2);
    EXPECT_EQ(back[0], fw[0]);
    EXPECT_EQ(back[1], fw[1]);
    EXPECT_EQ(modbus_read_registers(c.ctx, At(image_, "P00.MSG_WR_N").address, 2, back), 2);
    EXPECT_EQ(back[0], dw[0]);
    EXPECT_EQ(back[1], dw[1]);
  });
  EXPECT_TRUE(image_.Bool(start));
  EXPECT_TRUE(image_.Bool(stop));
  EXPECT_TRUE(image_.Bool(valve));
  EXPECT_EQ(image_.Int(fovr), -7);
  EXPECT_EQ(image_.Int(dint), -123456);
  EXPECT_EQ(image_.Real(real), static_cast<double>(3.14159f));
  EXPECT_EQ(image_.Real(lreal), -2.5e-3);
  EXPECT_EQ(image_.String(name), "P123");
  EXPECT_EQ(server_.stats().exceptions_sent, 0u);
}

TEST_F(ModbusServerTest, WriteAndReadRegisters) {
  const ModbusAddress& fovr = At(image_, "P00C.FOVR");
  const ModbusAddress& dint = At(image_, "P00.MSG_WR_N");
  image_.SetInt(image_.Require("P00.MSG_WR_N"), 0x12345678);
  WhilePolling(server_, [&] {
    Client c(server_.port());
    const uint16_t w = 55;
    uint16_t r[2] = {};
    EXPECT_EQ(modbus_write_and_read_registers(c.ctx, fovr.address, 1, &w, dint.address, 2, r), 2);
    EXPECT_EQ(r[0], 0x1234);
    EXPECT_EQ(r[1], 0x5678);
    // Half a DINT written by FC23: refused like FC16.
    EXPECT_EQ(modbus_write_and_read_registers(c.ctx, dint.address, 1, &w, fovr.address, 1, r), -1);
    EXPECT_EQ(errno, EMBXILADD);
  });
  EXPECT_EQ(image_.Int(image_.Require("P00C.FOVR")), 55);
  EXPECT_EQ(image_.Int(image_.Require("P00.MSG_WR_N")), 0x12345678);
}

TEST_F(ModbusServerTest, IllegalAddressesChangeNothing) {
  const int coils = Extent(image_, ModbusAddress::kCoil);
  const int holding = Extent(image_, ModbusAddress::kHoldingRegister);
  const int inputs = Extent(image_, ModbusAddress::kInputRegister);
  const ModbusAddress& fovr = At(image_, "P00C.FOVR");
  const ModbusAddress& dint = At(image_, "P00.MSG_WR_N");
  const ModbusAddress& real = At(image_, "TEST.REAL_W");
  const int last_coil = image_.Find("P00C.START");  // any coil; checked unchanged below
  ASSERT_GE(last_coil, 0);
  const int64_t fovr_preset = image_.Int(image_.Require("P00C.FOVR"));
  image_.SetInt(image_.Require("P00.MSG_WR_N"), 42);
  image_.SetReal(image_.Require("TEST.REAL_W"), 1.5);

  WhilePolling(server_, [&] {
    Client c(server_.port());
    const auto expect_address = [&](int rc, const char* what) {
      EXPECT_EQ(rc, -1) << what;
      EXPECT_EQ(errno, EMBXILADD) << what << ": " << modbus_strerror(errno);
    };
    expect_address(modbus_write_bit(c.ctx, coils, 1), "coil past the area");
    const uint8_t ones[3] = {1, 1, 1};
    // Two coils inside, one past the end: none is written.
    expect_address(modbus_write_bits(c.ctx, coils - 2, 3, ones), "coils across the end");
    uint16_t w[4] = {1, 2, 3, 4};
    expect_address(modbus_write_register(c.ctx, holding, 1), "register past the area");
    expect_address(modbus_write_register(c.ctx, dint.address, 7), "high word of a DINT");
    expect_address(modbus_write_register(c.ctx, dint.address + 1, 7), "low word of a DINT");
    expect_address(modbus_write_registers(c.ctx, real.address + 1, 1, w), "half a REAL");
    expect_address(modbus_write_registers(c.ctx, real.address, 3, w), "a REAL and beyond");
    if (fovr.address + 1 == dint.address) {
      expect_address(modbus_write_registers(c.ctx, fovr.address, 2, w), "INT + half a DINT");
    }
    uint16_t r[2];
    uint8_t b[2];
    expect_address(modbus_read_registers(c.ctx, holding, 1, r), "holding read past the area");
    expect_address(modbus_read_input_registers(c.ctx, inputs - 1, 2, r), "input read across end");
    expect_address(modbus_read_bits(c.ctx, coils, 1, b), "coil read past the area");
    expect_address(modbus_read_input_bits(c.ctx, 65535, 1, b), "discrete input at 65535");
    // The connection survives every exception.
    EXPECT_EQ(modbus_read_registers(c.ctx, fovr.address, 1, r), 1);
  });
  EXPECT_EQ(image_.Int(image_.Require("P00.MSG_WR_N")), 42);
  EXPECT_EQ(image_.Real(image_.Require("TEST.REAL_W")), 1.5);
  EXPECT_EQ(image_.Int(image_.Require("P00C.FOVR")), fovr_preset);
  for (int id = 0; id < image_.size(); ++id) {
    const Signal& s = image_.table()[id];
    if (s.modbus.area == ModbusAddress::kCoil) {
      EXPECT_EQ(image_.Bool(id), s.preset != 0) << s.name;
    }
  }
  EXPECT_GE(server_.stats().exceptions_sent, 11u);
  Drain(server_);
  EXPECT_EQ(server_.stats().clients_dropped, 1u);  // its own disconnect at the end
}

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

TEST_F(ModbusServerTest, TwoClientsAtOnce) {
  const int fovr = image_.Require("P00C.FOVR");
  const int dint = image_.Require("P00.MSG_WR_N");
  std::atomic<int> failures{0};
  WhilePolling(server_, [&] {
    const auto run = [&](const char* name, int words) {
      Client c(server_.port());
      const int address = At(image_, name).address;
      for (int i = 1; i <= 200; ++i) {
        uint16_t w[2] = {0, static_cast<uint16_t>(i)};
        uint16_t r[2] = {};
        if (modbus_write_registers(c.ctx, address, words, words == 2 ? w : w + 1) != words ||
            modbus_read_registers(c.ctx, address, words, r) != words || r[words - 1] != i) {
          ++failures;
        }
      }
    };
    std::thread a(run, "P00C.FOVR", 1);
    std::thread b(run, "P00.MSG_WR_N", 2);
    a.join();
    b.join();
  });
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(image_.Int(fovr), 200);
  EXPECT_EQ(image_.Int(dint), 200);
  EXPECT_EQ(server_.stats().requests_served, 800u);
}

TEST_F(ModbusServerTest, MaxClientsRefusesTheRest) {
  ModbusServer::Options o;
  o.max_clients = 1;
  ModbusServer one(image_, o);
  WhilePolling(one, [&] {
    Client first(one.port());
    uint16_t r;
    ASSERT_EQ(modbus_read_registers(first.ctx, 0, 1, &r), 1);
    Raw second(one.port());
    EXPECT_TRUE(second.Closed());
    EXPECT_EQ(modbus_read_registers(first.ctx, 0, 1, &r), 1);
  });
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

TEST(ModbusServerSetupTest, ErrorsNameTheProblem) {
  SignalImage image = MakeImage();
  ModbusServer first(image, {});
  ModbusServer::Options o;
  o.port = first.port();
  try {
    ModbusServer second(image, o);
    ADD_FAILURE() << "a second server on the same port";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("127.0.0.1:" + std::to_string(first.port())), std::string::npos) << what;
    EXPECT_NE(what.find(std::strerror(EADDRINUSE)), std::string::npos) << what;
  }
  o = {};
  o.host = "192.0.2.1";  // TEST-NET-1: not an address of this machine
  EXPECT_THROW(ModbusServer(image, o).Poll(0), std::runtime_error);
  o = {};
  o.cycle_register = At(image, "P00C.FOVR").address;
  EXPECT_THROW(ModbusServer(image, o).Poll(0), std::invalid_argument);
  o.cycle_register = 65536;
  EXPECT_THROW(ModbusServer(image, o).Poll(0), std::invalid_argument);
  o = {};
  o.port = 70000;
  EXPECT_THROW(ModbusServer(image, o).Poll(0), std::invalid_argument);
  o = {};
  o.max_clients = 0;
  EXPECT_THROW(ModbusServer(image, o).Poll(0), std::invalid_argument);
  // Poll with nothing to do returns after its timeout; a moved server keeps serving.
  first.Poll(0);
  ModbusServer moved = std::move(first);
  WhilePolling(moved, [&] {
    Client c(moved.port());
    uint16_t r;
    EXPECT_EQ(modbus_read_registers(c.ctx, 0, 1, &r), 1);
  });
}

}  // namespace
}  // namespace vmt::control::plc
