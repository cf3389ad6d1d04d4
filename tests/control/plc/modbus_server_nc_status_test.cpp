// The NC status block over Modbus: a program moves X on an ideal machine, the block is filled
// from the channel and its drives, and a Modbus client reads the positions, velocities, mode,
// state, line and messages back with function 04, as a PLC or an HMI would.

#include <gtest/gtest.h>
#include <modbus.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "control/gateway/nc_status_block.hpp"
#include "tests/control/gateway/gateway_rig.hpp"
#include "tests/control/gateway/lathe_layout.hpp"
#include "tests/control/plc/modbus_server_test_support.hpp"

namespace vmt::control::plc::testing {
namespace {

using gateway::NcStatus;
using gateway::NcStatusLayout;
using gateway::NcStatusLayoutOf;

int32_t Dint(const std::vector<uint16_t>& w, int at) {
  return static_cast<int32_t>(static_cast<uint32_t>(w[at]) << 16 | w[at + 1]);
}

// The block as a client reads it (two requests: FC04 reads at most 125 registers).
std::vector<uint16_t> ReadBlock(ModbusServer& server, const NcStatusLayout& layout) {
  std::vector<uint16_t> words(static_cast<size_t>(layout.count()));
  WhilePolling(server, [&] {
    Client c(server.port());
    for (int at = 0; at < layout.count(); at += 100) {
      const int n = std::min(100, layout.count() - at);
      ASSERT_EQ(modbus_read_input_registers(c.ctx, layout.address + at, n, words.data() + at), n)
          << modbus_strerror(errno);
    }
  });
  return words;
}

// The rig's channel (X drive 0, Z drive 1, spindle S1 drive 2) behind a server with its block.
struct StatusRig {
  explicit StatusRig(const std::string& program)
      : rig(program),
        layout(NcStatusLayoutOf(rig.image.table())),
        server(rig.image, Options(layout)),
        words(static_cast<size_t>(layout.count())) {
    rig.drives[0] = test_support::IdealDrive::Servo();
  }
  static ModbusServer::Options Options(const NcStatusLayout& layout) {
    ModbusServer::Options o;
    o.status_register = layout.address;
    o.status_count = layout.count();
    return o;
  }
  std::vector<uint16_t> Refresh() {
    gateway::EncodeNcStatus(layout, gateway::NcStatusOf(layout, *rig.ch, rig.at, 0.5), words);
    server.SetStatus(words);
    return ReadBlock(server, layout);
  }
  gateway::testing::GatewayRig rig;
  NcStatusLayout layout;
  ModbusServer server;
  std::vector<uint16_t> words;
};

TEST(NcStatusBlock, LayoutFollowsTheTablesAxesBehindItsInputRegisters) {
  const std::vector<Signal> table = gateway::BuildSignalTable(gateway::testing::LatheLayout());
  const NcStatusLayout layout = NcStatusLayoutOf(table);
  int end = 0;
  for (const Signal& s : table)
    if (s.modbus.area == ModbusAddress::kInputRegister)
      end = std::max(end, s.modbus.address + s.modbus.count);
  ASSERT_LT(end, 1000);
  EXPECT_EQ(layout.address, 1000);
  ASSERT_EQ(layout.axes.size(), 4u);
  const char* names[] = {"X", "Z", "S1", "C"};
  const bool rotary[] = {false, false, true, true};
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(layout.axes[i].number, static_cast<int>(i) + 1);
    EXPECT_EQ(layout.axes[i].name, names[i]);
    EXPECT_EQ(layout.axes[i].rotary, rotary[i]) << names[i];
    EXPECT_EQ(layout.axes[i].spindle, i == 2) << names[i];
  }
  EXPECT_EQ(layout.count(), 32 + 4 * 8);
  // Every register listed once, inside the block, with the unit of its axis' kind.
  std::vector<int> covered(static_cast<size_t>(layout.count()), 0);
  for (const gateway::NcStatusField& f : layout.Fields()) {
    for (int a = f.address; a < f.address + f.count; ++a) {
      ASSERT_GE(a, layout.address);
      ASSERT_LT(a, layout.address + layout.count());
      EXPECT_EQ(++covered[static_cast<size_t>(a - layout.address)], 1) << f.name;
    }
    if (f.name == "A02.NC_POS") {
      EXPECT_EQ(f.unit, "0.0001 mm");
    }
    if (f.name == "A03.NC_VEL") {
      EXPECT_EQ(f.unit, "0.001 deg/s");
    }
    if (f.name == "NC.LINE") {
      EXPECT_EQ(f.address, 1008);
    }
    if (f.name == "A04.NC_FE") {
      EXPECT_EQ(f.address, 1000 + 32 + 3 * 8 + 4);
    }
  }
}

TEST(NcStatusBlock, AProgramsMotionReadsBackOverModbus) {
  StatusRig s("N1 G01 X100 F3000\nN2 RET\n");
  s.rig.Cycle();
  std::vector<uint16_t> w = s.Refresh();
  EXPECT_EQ(w[0], 1);          // layout version
  EXPECT_EQ(w[1], 4);          // axes
  EXPECT_EQ(w[2], 0);          // process
  EXPECT_EQ(w[3], 8);          // message slots
  EXPECT_EQ(Dint(w, 4), 500);  // ms
  EXPECT_EQ(w[6], 0);          // automatic
  EXPECT_EQ(w[7], 0);          // idle
  EXPECT_EQ(Dint(w, 8), 0);

  s.rig.Press("P00C.START");
  s.rig.Cycle(200);  // 50 mm/s: X is on its way
  w = s.Refresh();
  ASSERT_EQ(s.rig.ch->state(), channel::ChannelState::kRunning);
  EXPECT_EQ(w[7], 1);        // running
  EXPECT_EQ(Dint(w, 8), 1);  // source line of N1
  const double x = s.rig.at.feedback[0].position;
  ASSERT_GT(x, 1);
  ASSERT_LT(x, 99);
  EXPECT_EQ(Dint(w, 32), std::lround(x * 1e4));
  EXPECT_NEAR(Dint(w, 34) * 1e-3, 50, 0.5);  // mm/s
  EXPECT_EQ(w[32 + 6], 1);
  EXPECT_EQ(w[32 + 7] & (gateway::kNcStatusRotary | gateway::kNcStatusFed), gateway::kNcStatusFed);
  // Z stands; C is no drive of this channel: no values, but its axis number and kind.
  EXPECT_EQ(Dint(w, 40 + 2), 0);
  EXPECT_EQ(w[56 + 6], 4);
  EXPECT_EQ(w[56 + 7], gateway::kNcStatusRotary);

  // Feed hold: state 2.
  s.rig.Set("P00C.STOP", true);
  s.rig.Cycle(100);
  EXPECT_EQ(s.Refresh()[7], 2);
  s.rig.Set("P00C.STOP", false);
  s.rig.Press("P00C.START");
  s.rig.Cycle(3000);
  w = s.Refresh();
  ASSERT_EQ(s.rig.ch->state(), channel::ChannelState::kEnded);
  EXPECT_EQ(w[7], 3);
  EXPECT_EQ(Dint(w, 32), 1000000);  // X100.0000
  EXPECT_EQ(Dint(w, 34), 0);
  EXPECT_TRUE(w[32 + 7] & gateway::kNcStatusInPosition);

  // Manual mode: 1.
  s.rig.Press("P00C.MANU");
  EXPECT_EQ(s.Refresh()[6], 1);
}

TEST(NcStatusBlock, MessagesRotaryPositionsAndLimits) {
  const NcStatusLayout layout =
      NcStatusLayoutOf(gateway::BuildSignalTable(gateway::testing::LatheLayout()));
  NcStatus st;
  st.state = channel::ChannelState::kError;
  st.mode = channel::ChannelMode::kMdi;
  st.line = 70000;  // beyond one register
  for (int k = 0; k < 9; ++k) {
    channel::OperatorMessage m;
    m.number = 500 + k;
    m.source =
        k == 1 ? channel::OperatorMessage::Source::kPlc : channel::OperatorMessage::Source::kNc;
    st.messages.push_back(m);
  }
  st.axes.resize(4);
  st.axes[0] = {true, -12.34567, -3.2, 1e9, 0};  // X: following error beyond the DINT range
  st.axes[2] = {true, 725.5, 18000, -0.25, 0};   // S1: two turns and 5.5 deg, 3000 rpm
  st.axes[3] = {true, -30, 0, 0, 0};             // C at -30 deg
  std::vector<uint16_t> w(static_cast<size_t>(layout.count()));
  gateway::EncodeNcStatus(layout, st, w);
  EXPECT_EQ(w[6], 2);
  EXPECT_EQ(w[7], 4);
  EXPECT_EQ(Dint(w, 8), 70000);
  EXPECT_EQ(w[10], 9);  // all of them, 8 in slots
  for (int k = 0; k < 8; ++k) {
    EXPECT_EQ(w[12 + 2 * k], 500 + k);
    EXPECT_EQ(w[13 + 2 * k], k == 1 ? 2 : 1);
  }
  EXPECT_EQ(Dint(w, 32), -123457);
  EXPECT_EQ(Dint(w, 34), -3200);
  EXPECT_EQ(Dint(w, 36), INT32_MAX);
  EXPECT_EQ(Dint(w, 48), 55000);  // within the turn
  EXPECT_EQ(Dint(w, 50), 18000000);
  EXPECT_EQ(Dint(w, 52), -2500);
  EXPECT_EQ(Dint(w, 56), 3300000);  // 330 deg
  EXPECT_EQ(w[40 + 7], 0);          // Z: linear, no drive answered
}

TEST(NcStatusBlock, ServerReadsTheBlockAloneAndRefusesWhatIsOutside) {
  SignalImage image = MakeImage();
  const int end = Extent(image, ModbusAddress::kInputRegister);
  ModbusServer::Options o;
  o.status_register = end + 10;
  o.status_count = 4;
  ModbusServer server(image, o);
  const std::vector<uint16_t> words = {1, 2, 3, 0xffff};
  server.SetStatus(words);
  WhilePolling(server, [&] {
    Client c(server.port());
    uint16_t got[8] = {};
    ASSERT_EQ(modbus_read_input_registers(c.ctx, end + 10, 4, got), 4);
    EXPECT_EQ(std::vector<uint16_t>(got, got + 4), words);
    ASSERT_EQ(modbus_read_input_registers(c.ctx, end + 12, 2, got), 2);
    EXPECT_EQ(got[0], 3);
    // The gap between the signals and the block, and past the block's end: 02.
    EXPECT_EQ(modbus_read_input_registers(c.ctx, end + 9, 2, got), -1);
    EXPECT_EQ(errno, EMBXILADD);
    EXPECT_EQ(modbus_read_input_registers(c.ctx, end + 12, 3, got), -1);
    EXPECT_EQ(errno, EMBXILADD);
    // Not a holding register.
    EXPECT_EQ(modbus_read_registers(c.ctx, end + 10, 1, got), -1);
    EXPECT_EQ(errno, EMBXILADD);
  });
  // A block over a signal's input register is refused.
  o.status_register = end - 1;
  EXPECT_THROW(ModbusServer(image, o), std::invalid_argument);
  o.status_register = 65535;
  o.status_count = 2;
  EXPECT_THROW(ModbusServer(image, o), std::invalid_argument);
}

}  // namespace
}  // namespace vmt::control::plc::testing
