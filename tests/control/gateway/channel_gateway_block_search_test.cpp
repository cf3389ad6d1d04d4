// Block search through the gateway (twincat-cnc-block-search-de.md 5, 7): the PLC writes the
// CNC objects mc_cmd_bs_*_w into the image before the start, reads them back as _r, follows
// the HLI status (block_search_state_r, block_count_r, block_search_path_deviation_r,
// dist_prog_start, stop_conditions_r) and answers the on/off handshake; a reset clears both
// signals of the handshake. X A01 (drive 0), Z A02 (drive 1), spindle A03 on an ideal machine.

#include <gtest/gtest.h>

#include <cmath>

#include "control/channel/channel_messages.hpp"
#include "control/channel/jog_of_path.hpp"
#include "control/gateway/channel_gateway.hpp"
#include "tests/control/gateway/gateway_rig.hpp"

namespace vmt::control::gateway {
namespace {

const char* kProgram =
    "N1 G01 X10 Z0 F600\n"
    "N2 X20\n"
    "N3 Z-10\n"
    "N4 X30\n"
    "N5 RET\n";

struct SearchRig : testing::GatewayRig {
  SearchRig() : GatewayRig(kProgram, /*handshake=*/false, /*spindle_at_speed=*/true) {}
  void SetNumber(const char* name, int64_t v) { image.SetInt(image.Require(name), v); }
  void SetReal(const char* name, double v) { image.SetReal(image.Require(name), v); }
  double Real(const char* name) const { return image.Real(image.Require(name)); }
  int64_t State() const { return GetInt("P00.bahn_state.block_search_state_r"); }
  void Type4(int64_t block, double permille) {
    SetNumber("P00.mc_cmd_bs_type_w", 4);
    SetNumber("P00.mc_cmd_bs_block_number_w", block);
    SetReal("P00.mc_cmd_bs_covered_distance_w", permille);
    Set("P00.mc_cmd_bs_auto_return_w", true);
  }
};

TEST(ChannelGatewayBlockSearch, ObjectsStatusAndReadBacks) {
  SearchRig r;
  r.Type4(3, 500);
  r.Press("P00C.START");
  r.Cycle(5);
  EXPECT_EQ(r.State(), 4);  // HLI_BS_WAIT_RETURN_TO_CONTOUR
  EXPECT_FALSE(r.Get("P00.bahn_state.block_search_active_r"));
  EXPECT_EQ(r.GetInt("P00.mc_cmd_bs_type_r"), 4);
  EXPECT_EQ(r.GetInt("P00.mc_cmd_bs_block_number_r"), 3);
  EXPECT_EQ(r.Real("P00.mc_cmd_bs_covered_distance_r"), 500);
  EXPECT_EQ(r.GetInt("P00.bahn_state.block_count_r"), 3);
  // From X0 Z0 to the continue position X20 Z-5, in 0.1 um.
  EXPECT_EQ(r.GetInt("P00.bahn_state.block_search_path_deviation_r"),
            std::lround(std::hypot(20.0, 5.0) * 1e4));
  EXPECT_NEAR(r.Real("P00.bahn_state.dist_prog_start"), 25e4, 1e-3);
  EXPECT_EQ(r.at.feedback[0].position, 0);  // nothing moved
  // Objects written now do not touch the running program (5).
  r.SetNumber("P00.mc_cmd_bs_block_number_w", 4);
  r.Press("P00C.START");
  ASSERT_TRUE([&] {
    for (int k = 0; k < 5000 && r.State() != 6; ++k) r.Cycle();
    return r.State() == 6;  // HLI_BS_WAIT_FOR_CONTINUE_CONTOUR at the contour
  }());
  EXPECT_EQ(r.GetInt("P00.mc_cmd_bs_block_number_r"), 3);
  EXPECT_NEAR(r.at.feedback[0].position, 20, 1e-9);
  EXPECT_NEAR(r.at.feedback[1].position, -5, 1e-9);
  EXPECT_TRUE(r.Get("P00S.STOP"));
  r.Press("P00C.START");
  for (int k = 0; k < 5000 && r.ch->state() != channel::ChannelState::kEnded; ++k) r.Cycle();
  ASSERT_EQ(r.ch->state(), channel::ChannelState::kEnded);
  EXPECT_EQ(r.State(), 0);
  // 10 + 10 + 10 + 10 mm since program start, in 0.1 um, on both of its names.
  EXPECT_NEAR(r.Real("P00.bahn_state.dist_prog_start"), 40e4, 1e-3);
  EXPECT_NEAR(r.Real("P00.distance_from_program_start"), 40e4, 1e-3);
}

TEST(ChannelGatewayBlockSearch, HandshakeAndResetClearIt) {
  SearchRig r;
  r.Type4(3, 0);
  r.Set("P00.bahn_lc_control.block_search.enable_w", true);
  r.Press("P00C.START");
  r.Cycle(3);
  EXPECT_EQ(r.State(), 1);  // HLI_BS_WAIT_FOR_PLC_ON
  EXPECT_TRUE(r.Get("P00.bahn_lc_control.block_search.command_r"));
  r.Set("P00.bahn_lc_control.block_search.state_r", true);
  r.Cycle(3);
  EXPECT_EQ(r.State(), 3);  // found; HLI_BS_WAIT_FOR_PLC_OFF
  EXPECT_FALSE(r.Get("P00.bahn_lc_control.block_search.command_r"));
  EXPECT_TRUE(r.Get("P00.bahn_state.block_search_active_r"));
  // Control-Reset: off without the handshake; the NC clears the PLC's signal too (7).
  r.Press("P00C.RESET");
  EXPECT_EQ(r.State(), 0);
  EXPECT_FALSE(r.Get("P00.bahn_lc_control.block_search.state_r"));
  EXPECT_FALSE(r.Get("P00.bahn_lc_control.block_search.command_r"));
}

TEST(ChannelGatewayBlockSearch, ProgramNameSelectsWhereTheNumberCounts) {
  // 5.4: mc_cmd_bs_block_nbr_prog_name_w; the rig's program is "p".
  SearchRig r;
  r.Type4(2, 0);
  r.image.SetString(r.image.Require("P00.mc_cmd_bs_block_nbr_prog_name_w"), "%p");
  r.Press("P00C.START");
  r.Cycle(5);
  EXPECT_EQ(r.State(), 4);
  EXPECT_EQ(r.image.String(r.image.Require("P00.mc_cmd_bs_block_nbr_prog_name_r")), "%p");
  SearchRig other;
  other.Type4(2, 0);
  other.image.SetString(other.image.Require("P00.mc_cmd_bs_block_nbr_prog_name_w"), "other");
  other.Press("P00C.START");
  other.Cycle(5);
  EXPECT_EQ(other.ch->state(), channel::ChannelState::kEnded);  // not found: 10, a warning
  EXPECT_EQ(other.ch->block_search().warnings.size(), 1u);
}

TEST(ChannelGatewayBlockSearch, AWrongTypeStopsTheStartWithItsMessage) {
  SearchRig r;
  r.SetNumber("P00.mc_cmd_bs_type_w", 2);  // type 2 no longer exists (1)
  r.Press("P00C.START");
  r.Cycle(2);
  EXPECT_TRUE(r.Get("P00S.ERROR"));
  EXPECT_EQ(r.GetInt("P00S.ERRNR"), channel::kMsgBlockSearch);
}

}  // namespace
}  // namespace vmt::control::gateway

namespace vmt::control::gateway {
namespace {

TEST(ChannelGatewayBlockSearch, BackwardTravelAfterTheSearchThroughItsSignals) {
  // 4.3: at the contour after the search, backward_motion_w and a start take the axes back
  // along N2 and N1, which the search decoded; cleared, a start brings them forward and the
  // program goes on. backward_motion_r says they stand behind the interruption point.
  SearchRig r;
  r.Type4(3, 500);
  r.Press("P00C.START");
  r.Cycle(5);
  r.Press("P00C.START");
  for (int k = 0; k < 5000 && r.State() != 6; ++k) r.Cycle();
  ASSERT_EQ(r.State(), 6);
  r.Set("P00.backward_motion_w", true);
  r.Press("P00C.START");
  for (int k = 0; k < 20000 && r.at.feedback[0].position > 1e-9; ++k) r.Cycle();
  EXPECT_NEAR(r.at.feedback[0].position, 0, 1e-9);  // N1's start, the program's start
  EXPECT_NEAR(r.at.feedback[1].position, 0, 1e-9);
  EXPECT_TRUE(r.Get("P00.bahn_state.backward_motion_r"));
  r.Set("P00.backward_motion_w", false);
  r.Press("P00C.START");
  for (int k = 0; k < 20000 && r.ch->state() != channel::ChannelState::kEnded; ++k) r.Cycle();
  ASSERT_EQ(r.ch->state(), channel::ChannelState::kEnded);
  EXPECT_FALSE(r.Get("P00.bahn_state.backward_motion_r"));
  EXPECT_NEAR(r.at.feedback[0].position, 30, 1e-9);
}

// 4.2.1 through the signals: P00.suspend_axis_output_w lends the axes to the JogOfPath channel
// (P00.bahn_state.axis_output_suspended_r, P00.jog_of_path.axis_output_r), a rising edge of
// P00.jog_of_path.start_w starts its program and P00.jog_of_path.state_r follows it.
TEST(ChannelGatewayBlockSearch, JogOfPathThroughItsSignals) {
  SearchRig r;
  auto manual = nc::ParseProgram("N10 G00 Z-5\nN20 X15\nN30 RET\n", "r.mtc", nc::Dialect::kMtc200);
  ASSERT_TRUE(manual.ok());
  channel::Channel jop(channel::JogOfPathConfig(r.ch->config()), {&manual.program});
  // One NC cycle of both channels, as vmt's runner runs it.
  const auto cycle = [&](int n) {
    for (int k = 0; k < n; ++k) {
      r.gateway->ReadControls(*r.ch);
      r.gateway->ReadJogOfPath(jop);
      channel::HandOverAxes(*r.ch, jop);
      for (int i = 0; i < 4; ++i) {
        const bool holds = !jop.output_suspended();
        if (!holds) jop.Tick(r.at, r.mdt);
        r.ch->Tick(r.at, r.mdt);
        if (holds) jop.Tick(r.at, r.mdt);
        for (int d = 0; d < 2; ++d) r.Answer(d, r.drives[d]);  // X and Z; the spindle stands
      }
      r.gateway->WriteStatus(*r.ch, r.at);
      r.gateway->WriteJogOfPath(jop);
    }
  };
  r.Set("P00.suspend_axis_output_w", true);
  cycle(2);
  EXPECT_TRUE(r.Get("P00.bahn_state.axis_output_suspended_r"));
  EXPECT_TRUE(r.Get("P00.jog_of_path.axis_output_r"));
  EXPECT_EQ(r.GetInt("P00.jog_of_path.state_r"), 0);  // idle
  r.Set("P00.jog_of_path.start_w", true);
  cycle(1);
  EXPECT_EQ(r.GetInt("P00.jog_of_path.state_r"), 1);  // running
  for (int k = 0; k < 5000 && r.GetInt("P00.jog_of_path.state_r") == 1; ++k) cycle(1);
  EXPECT_EQ(r.GetInt("P00.jog_of_path.state_r"), 3);  // ended
  EXPECT_NEAR(r.at.feedback[0].position, 15, 1e-9);
  EXPECT_NEAR(r.at.feedback[1].position, -5, 1e-9);
  r.Set("P00.suspend_axis_output_w", false);
  cycle(3);
  EXPECT_FALSE(r.Get("P00.bahn_state.axis_output_suspended_r"));
  EXPECT_FALSE(r.Get("P00.jog_of_path.axis_output_r"));
}

}  // namespace
}  // namespace vmt::control::gateway
