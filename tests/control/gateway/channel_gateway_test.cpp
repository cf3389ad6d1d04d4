// The channel through the gateway: control signals act on it each NC cycle, status signals show
// its state, on an ideal machine (actual = setpoint).

#include "control/gateway/channel_gateway.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string_view>
#include <vector>

#include "control/gateway/signal_catalog.hpp"
#include "control/nc/parser.hpp"
#include "tests/control/gateway/gateway_rig.hpp"
#include "tests/control/gateway/lathe_layout.hpp"

namespace vmt::control::gateway {
namespace {

using Rig = testing::GatewayRig;

// The binding table speaks the catalog's language: a misspelt pattern would leave a signal
// silently unserved (-1) on every machine.
TEST(ChannelGateway, EverySignalItBindsIsInTheCatalogAndOnTheLathe) {
  SignalImage image(BuildSignalTable(testing::LatheLayout()));
  // Process 0; channel axes X, Z, C (1, 2, 4); spindle S1 (3) on drive 2; C its rotary axis.
  const ChannelGateway gateway(image, 0, {1, 2, 4}, 3, 2, 4);
  std::set<std::string_view> families;
  for (const SignalFamily& f : SignalFamilies()) families.insert(f.pattern);
  ASSERT_GT(gateway.bindings().size(), 150u);
  std::set<std::string> names;
  for (const SignalBinding& b : gateway.bindings()) {
    const std::string name = InstanceName(b.pattern, b.number);
    EXPECT_TRUE(families.count(b.pattern)) << b.pattern << " is no catalog family";
    EXPECT_GE(b.id, 0) << name << " is not on the lathe";
    EXPECT_TRUE(names.insert(name).second) << name << " is bound twice";
  }
}

TEST(ChannelGateway, StartStopAndStatus) {
  Rig r("N1 G01 X100 F3000\nN2 RET\n");
  r.Cycle();
  EXPECT_TRUE(r.Get("P00S.AUTO"));
  EXPECT_FALSE(r.Get("P00S.RUN"));
  EXPECT_TRUE(r.Get("A01S.HOMED"));
  r.Press("P00C.START");
  r.Cycle(100);
  EXPECT_TRUE(r.Get("P00S.RUN"));
  EXPECT_TRUE(r.Get("A01S.MVPOS"));
  EXPECT_FALSE(r.Get("A01S.MVNEG"));
  EXPECT_FALSE(r.Get("A02S.MVPOS"));
  // Feed hold while STOP is held; START does nothing meanwhile.
  r.Set("P00C.STOP", true);
  r.Cycle(100);
  EXPECT_TRUE(r.Get("P00S.STOP"));
  EXPECT_FALSE(r.Get("P00S.RUN"));
  EXPECT_FALSE(r.Get("A01S.MVPOS"));
  const double held = r.at.feedback[0].position;
  r.Press("P00C.START");
  r.Cycle(50);
  EXPECT_EQ(r.at.feedback[0].position, held);
  r.Set("P00C.STOP", false);
  r.Press("P00C.START");
  r.Cycle(2000);
  EXPECT_EQ(r.ch->state(), channel::ChannelState::kEnded);
  EXPECT_DOUBLE_EQ(r.at.feedback[0].position, 100);
  EXPECT_FALSE(r.Get("P00S.RUN"));
}

TEST(ChannelGateway, OverrideModesAndJogKeys) {
  Rig r("N1 RET\n");
  r.image.SetInt(r.image.Require("P00C.FOVR"), 50);
  r.Press("P00C.MANU");
  EXPECT_TRUE(r.Get("P00S.MANU"));
  EXPECT_FALSE(r.Get("P00S.AUTO"));
  r.Set("P00C.JOGM0", true);  // code 1: jogging rapid
  r.Set("A02C.JGNEG", true);
  r.Cycle(50);
  EXPECT_EQ(r.ch->jog_mode(), channel::JogMode::kRapid);
  EXPECT_TRUE(r.Get("A02S.MVNEG"));
  r.Set("A02C.JGNEG", false);
  r.Cycle(200);
  EXPECT_FALSE(r.Get("A02S.MVNEG"));
  EXPECT_LT(r.at.feedback[1].position, 0);
  // Both keys at once: no motion.
  r.Set("A01C.JGPOS", true);
  r.Set("A01C.JGNEG", true);
  r.Cycle(50);
  EXPECT_EQ(r.at.feedback[0].position, 0);
}

TEST(ChannelGateway, AuxFunctionsWaitForAuxAckAndQFunctionsForTheirOwn) {
  Rig r("N1 M08 G01 X10 F3000\nN2 Q9992\nN3 G01 X20\nN4 RET\n", true);
  r.Press("P00C.START");
  r.Cycle(10);
  EXPECT_TRUE(r.Get("P00S.AUXSTB"));
  EXPECT_EQ(r.GetInt("P00S.MFUNC"), 8);
  EXPECT_EQ(r.at.feedback[0].position, 0);
  r.Press("P00C.AUXACK");
  r.Cycle(400);
  EXPECT_DOUBLE_EQ(r.at.feedback[0].position, 10);
  EXPECT_TRUE(r.Get("P00.Q9992"));  // N2's Q function waits for Q9992_Q
  EXPECT_FALSE(r.Get("P00S.AUXSTB"));
  r.Set("P00.Q9992_Q", true);
  r.Cycle(2);
  EXPECT_FALSE(r.Get("P00.Q9992"));
  r.Cycle(1000);
  EXPECT_EQ(r.ch->state(), channel::ChannelState::kEnded);
  EXPECT_DOUBLE_EQ(r.at.feedback[0].position, 20);
}

// M functions in consecutive blocks, against a PLC that scans every 4 NC cycles and acknowledges
// by a pulse (one scan) or by holding AUXACK until the strobe falls (four phases): the strobe
// stays low a whole scan and until AUXACK is low, so either PLC sees every function once.
TEST(ChannelGateway, AuxHandshakeHoldsEachPhaseAPlcScan) {
  for (const bool hold : {false, true}) {
    SCOPED_TRACE(hold ? "holding AUXACK" : "pulsing AUXACK");
    Rig r("N1 M08\nN2 M03 S100\nN3 M09\nN4 M05\nN5 RET\n", true);
    r.gateway->SetPlcScan(4);
    r.Press("P00C.START");
    std::vector<int64_t> seen;
    bool acked = false;
    for (int scan = 0; scan < 200 && r.ch->state() != channel::ChannelState::kEnded; ++scan) {
      const bool strobe = r.Get("P00S.AUXSTB");
      if (strobe && !acked) seen.push_back(r.GetInt("P00S.MFUNC"));
      acked = hold ? strobe : strobe && !acked;
      r.Set("P00C.AUXACK", acked);
      r.Cycle(4);
    }
    EXPECT_EQ(r.ch->state(), channel::ChannelState::kEnded);
    EXPECT_EQ(seen, (std::vector<int64_t>{8, 3, 9, 5}));
  }
}

TEST(ChannelGateway, OptionalStopSignalMakesM01HoldAndTheStopConditionsShowIt) {
  // M01 goes to the PLC as an M function either way; with P00C.OPSTP the program then holds
  // (P00S.STOP) until the next start, with HLI_SC_M00_OR_M01 | HLI_SC_M1_STOP.
  Rig r("N1 G01 X10 F3000 M01\nN2 G01 X20\nN3 G01 X30 M01\nN4 RET\n", true);
  r.Press("P00C.START");
  r.Cycle(10);
  EXPECT_EQ(r.GetInt("P00S.MFUNC"), 1);
  r.Press("P00C.AUXACK");
  r.Cycle(1000);
  EXPECT_DOUBLE_EQ(r.at.feedback[0].position, 20);  // through N1's M01 and on to N3's
  EXPECT_EQ(r.GetInt("P00S.MFUNC"), 1);
  r.Set("P00C.OPSTP", true);
  r.Press("P00C.AUXACK");
  r.Cycle(1000);
  EXPECT_DOUBLE_EQ(r.at.feedback[0].position, 30);
  EXPECT_EQ(r.ch->state(), channel::ChannelState::kHold);
  EXPECT_TRUE(r.Get("P00S.STOP"));
  EXPECT_EQ(r.GetInt("P00.bahn_state.stop_conditions_r") & 0x04000010, 0x04000010);
  r.Press("P00C.START");
  r.Cycle(10);
  EXPECT_EQ(r.ch->state(), channel::ChannelState::kEnded);
}

TEST(ChannelGateway, EventsBetweenProgramAndPlc) {
  // SE 30 shows on P00.EV30; BES 29 tests what the PLC set on P00.EV29; an event the table
  // does not list (E500) still works inside the NC.
  Rig r(
      "N1 SE 30\nN2 SE 500\nN3 BES .GO 29\nN4 G00 X1\nN5 RET\n.GO\nN6 BEC .END 500\n"
      "N7 G00 X2\n.END\nN8 RET\n");
  r.Set("P00.EV29", true);
  r.Press("P00C.START");
  r.Cycle(500);
  EXPECT_EQ(r.ch->state(), channel::ChannelState::kEnded) << r.ch->error();
  EXPECT_TRUE(r.Get("P00.EV30"));
  EXPECT_TRUE(r.gateway->Event(500));
  EXPECT_DOUBLE_EQ(r.at.feedback[0].position, 2);
}

TEST(ChannelGateway, ErrorNumberAndReset) {
  Rig r("N1 G01 X10\nN2 RET\n");  // no feed
  r.Press("P00C.START");
  r.Cycle(5);
  EXPECT_TRUE(r.Get("P00S.ERROR"));
  EXPECT_EQ(r.GetInt("P00S.ERRNR"), channel::kMsgNoFeed);
  r.Press("P00C.RESET");
  EXPECT_FALSE(r.Get("P00S.ERROR"));
  EXPECT_EQ(r.GetInt("P00S.ERRNR"), 0);
}

}  // namespace
}  // namespace vmt::control::gateway
