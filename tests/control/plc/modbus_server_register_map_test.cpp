// The Modbus TCP server's register map: every area reads as the signal image holds it, writes
// of every type (BOOL to STRING) reach the image, FC23, and addresses outside the map or across
// a signal's words change nothing.

#include <gtest/gtest.h>
#include <modbus.h>

#include <bit>

#include "control/plc/modbus_server.hpp"
#include "modbus_server_test_support.hpp"

namespace vmt::control::plc {
namespace {

using namespace testing;  // vmt::control::plc::testing

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

// The PLC is the client that writes: vmt serve's link watchdog counts writes, so a monitor that
// only reads keeps no dead PLC alive.
TEST_F(ModbusServerTest, CountsWritesApartFromReads) {
  WhilePolling(server_, [&] {
    Client c(server_.port());
    uint8_t bits[8];
    uint16_t regs[2];
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(modbus_read_input_bits(c.ctx, 0, 8, bits), 8);
      ASSERT_EQ(modbus_read_registers(c.ctx, 0, 2, regs), 2);
    }
    EXPECT_EQ(server_.stats().writes, 0u);
    ASSERT_EQ(
        modbus_write_bit(c.ctx, image_.table()[image_.Require("P00C.START")].modbus.address, 1), 1);
    ASSERT_EQ(modbus_write_register(c.ctx,
                                    image_.table()[image_.Require("P00C.FOVR")].modbus.address, 50),
              1);
  });
  EXPECT_EQ(server_.stats().writes, 2u);
  EXPECT_EQ(server_.stats().requests_served, 8u);
}

}  // namespace
}  // namespace vmt::control::plc
