// The C-axis manual's changeover program (4.4) in the PLC runtime, with the test playing the NC
// (ROTMOD / SPMOD, PxxSSTOP) and the machine (clutch K: valves in, switches out).

#include "control/plc/programs/c_axis_changeover.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "control/gateway/signal_table.hpp"

namespace vmt::control::plc {
namespace {

using namespace std::chrono_literals;

constexpr PlcTime kPeriod = 4ms;

// A lathe with a C servo as NC axis 3 and the spindle as axis 4, then the machine's I/O
// (lathe-c1 numbers them the other way round, S1 = A03 and C = A04; the first test checks that
// the program finds either).
gateway::GatewayLayout LatheLayout(bool with_c = true) {
  gateway::GatewayLayout layout;
  layout.processes = {0};
  layout.axes = {{1, "X", false, false}, {2, "Z", false, false}};
  if (with_c) layout.axes.push_back({3, "C", false, true});
  layout.axes.push_back({with_c ? 4 : 3, "S1", true, false});
  layout.io = {{"QROTMODE", true, "valve (machine output)"},
               {"QSPMODE", true, "valve (machine output)"},
               {"IROTMODE", false, "sensor (machine input)"},
               {"ISPMODE", false, "sensor (machine input)"},
               {"mREPOS", false, "machine key (operator input)"},
               {"mRESTA", false, "machine key (operator input)"},
               {"mRaR_OFF", false, "machine key (operator input)"}};
  return layout;
}

// Clutch K as the switches see it: a valve moves the dogs; leaving an end position drops its
// switch at once, the other comes at the end of the stroke. A blocked clutch leaves both off
// (dogs on dogs, or ratcheting), as sim/backend/dog_clutch does.
struct Clutch {
  gateway::SignalImage& image;
  int QROTMODE = image.Require("QROTMODE"), QSPMODE = image.Require("QSPMODE");
  int IROTMODE = image.Require("IROTMODE"), ISPMODE = image.Require("ISPMODE");
  int stroke_scans = 20;  // 80 ms, the lathe's engage_time
  bool blocked = false;
  int direction = 0;  // +1 engaging, -1 releasing
  int moving = 0;     // scans in this direction

  void Released() { image.SetBool(ISPMODE, true), image.SetBool(IROTMODE, false); }
  void Step() {
    const bool in = image.Bool(QROTMODE) && !image.Bool(QSPMODE);
    const bool out = image.Bool(QSPMODE) && !image.Bool(QROTMODE);
    const int d = in ? 1 : out ? -1 : 0;
    if (d != direction) direction = d, moving = 0;
    if (d == 0) return;
    const int leave = d > 0 ? ISPMODE : IROTMODE, reach = d > 0 ? IROTMODE : ISPMODE;
    if (image.Bool(reach)) return;
    image.SetBool(leave, false);
    if (++moving >= stroke_scans && !blocked) image.SetBool(reach, true);
  }
};

// Every signal's value as text, to see what a scan changed.
std::vector<std::string> Values(const gateway::SignalImage& image) {
  std::vector<std::string> v;
  for (int id = 0; id < image.size(); ++id) {
    const gateway::SignalType t = image.table()[id].type;
    if (t == gateway::SignalType::kBool)
      v.push_back(std::to_string(image.Bool(id)));
    else if (gateway::IsInteger(t))
      v.push_back(std::to_string(image.Int(id)));
    else if (t == gateway::SignalType::kString)
      v.push_back(image.String(id));
    else
      v.push_back(std::to_string(image.Real(id)));
  }
  return v;
}

class CAxisChangeoverTest : public ::testing::Test {
 protected:
  CAxisChangeoverTest()
      : image(gateway::BuildSignalTable(LatheLayout())),
        program(std::make_shared<CAxisChangeover>(image)),
        plc(
            image, [p = program](PlcScan& s) { (*p)(s); }, kPeriod),
        clutch{image} {
    clutch.Released();
  }

  int Id(const std::string& name) const { return image.Require(name); }
  bool B(const std::string& name) const { return image.Bool(Id(name)); }
  int64_t I(const std::string& name) const { return image.Int(Id(name)); }
  void Set(const std::string& name, bool v) { image.SetBool(Id(name), v); }

  // One PLC cycle: the machine moves on what the last scan wrote, then the PLC scans. Every
  // signal that changes in the scan must be one the PLC drives; the names are kept for the test
  // of which ones.
  void Cycle() {
    clutch.Step();
    const std::vector<std::string> before = Values(image);
    plc.Scan();
    const std::vector<std::string> after = Values(image);
    for (int id = 0; id < image.size(); ++id) {
      if (before[id] == after[id]) continue;
      const gateway::Signal& sig = image.table()[id];
      EXPECT_TRUE(PlcDrives(sig.direction)) << sig.name;
      written.push_back(sig.name);
    }
  }
  // Cycles until `done` holds (at most `limit`); returns the cycles it took.
  template <typename Done>
  int CycleUntil(Done done, int limit = 2000) {
    for (int n = 1; n <= limit; ++n) {
      Cycle();
      if (done()) return n;
    }
    ADD_FAILURE() << "not reached within " << limit << " cycles";
    return limit;
  }
  // The NC pre-selects a mode (a level, for as long as the mode is selected: 4.1).
  void Preselect(bool rotary) { Set("A04.ROTMOD", rotary), Set("A04.SPMOD", !rotary); }
  // The NC in spindle mode, acknowledged, as after power-on with the clutch out.
  void StartInSpindleMode() {
    Preselect(false);
    CycleUntil([&] { return B("A04.SPMOD_Q"); });
  }

  gateway::SignalImage image;
  std::shared_ptr<CAxisChangeover> program;
  PlcRuntime plc;
  Clutch clutch;
  std::vector<std::string> written;
};

TEST_F(CAxisChangeoverTest, FindsTheSpindleAndTheCServoByTheirSignals) {
  EXPECT_EQ(program->ISP_NR, 4);
  EXPECT_EQ(program->IROT_NR, 3);
  EXPECT_EQ(image.table()[program->ROTMOD_Q].name, "A04.ROTMOD_Q");
  EXPECT_EQ(image.table()[program->ROT_65012].name, "A03.AXD.65012");
  EXPECT_EQ(image.table()[program->ROT_C_READY].name, "A03C.READY");
  EXPECT_EQ(image.table()[program->PxxS_STOP].name, "P00S.STOP");

  // Another numbering: the spindle before the C servo.
  gateway::GatewayLayout swapped = LatheLayout();
  swapped.axes[2].number = 5;
  const gateway::SignalImage other(gateway::BuildSignalTable(swapped));
  const CAxisChangeover p(other);
  EXPECT_EQ(p.ISP_NR, 4);
  EXPECT_EQ(p.IROT_NR, 5);
}

TEST(CAxisChangeoverSetupTest, AMachineWithoutTheCServoAsAnAxisCannotRunIt) {
  // A lathe whose C servo is no NC axis: S1 is A03.
  const gateway::SignalImage image(gateway::BuildSignalTable(LatheLayout(false)));
  try {
    CAxisChangeover program(image);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rotary axis"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("A03"), std::string::npos) << e.what();
  }
  gateway::GatewayLayout no_valves = LatheLayout();
  no_valves.io.erase(no_valves.io.begin() + 1);  // QSPMODE
  const gateway::SignalImage without(gateway::BuildSignalTable(no_valves));
  EXPECT_THROW(
      {
        try {
          CAxisChangeover program(without);
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("QSPMODE"), std::string::npos) << e.what();
          throw;
        }
      },
      std::invalid_argument);
}

TEST_F(CAxisChangeoverTest, InitialisesTheIdentsOnTheFirstScan) {
  Cycle();
  // Spindle: the manual's 100 1/min ($F4240 in 0.0001 1/min), 500 rad/s^2 ($1F4), 0 degrees.
  EXPECT_EQ(I("A04.AXD.65013"), 1000000);
  EXPECT_EQ(I("A04.AXD.65014"), 500);
  EXPECT_EQ(I("A04.AXD.65015"), 0);
  // C servo: its hunting speed, 1 1/min.
  EXPECT_EQ(I("A03.AXD.65013"), 10000);
  EXPECT_EQ(I("A03.AXD.65014"), 10);
  EXPECT_EQ(I("A03.AXD.65015"), 0);
  EXPECT_TRUE(program->READY);
  // No mode selected yet: nothing hunts, no valve moves; the released clutch is reported as
  // spindle mode (power-on state).
  EXPECT_EQ(I("A03.AXD.65012"), 0);
  EXPECT_EQ(I("A04.AXD.65012"), 0);
  EXPECT_FALSE(B("QROTMODE"));
  EXPECT_FALSE(B("QSPMODE"));
  EXPECT_TRUE(B("A04.SPMOD_Q"));
  EXPECT_FALSE(B("A04.ROTMOD_Q"));
  // The NC may change the idents afterwards (AXD from the NC program): the PLC leaves them.
  image.SetInt(Id("A04.AXD.65013"), 42);
  Cycle();
  EXPECT_EQ(I("A04.AXD.65013"), 42);
}

TEST_F(CAxisChangeoverTest, SpindleToCAndBack) {
  StartInSpindleMode();
  EXPECT_TRUE(B("QSPMODE"));
  EXPECT_FALSE(B("QROTMODE"));
  EXPECT_TRUE(B("A04C.READY"));
  EXPECT_FALSE(B("A03C.READY"));

  // Spindle -> C: C hunts, the valves switch in the same scan.
  Preselect(true);
  Cycle();
  EXPECT_EQ(I("A03.AXD.65012"), 0b100);  // speed specification: hunting
  EXPECT_TRUE(B("QROTMODE"));
  EXPECT_FALSE(B("QSPMODE"));
  EXPECT_TRUE(B("A03C.READY"));
  EXPECT_TRUE(B("A04C.READY"));  // the spindle holds until the clutch has switched
  EXPECT_FALSE(B("A04.ROTMOD_Q"));
  const int scans = CycleUntil([&] { return B("A04.ROTMOD_Q"); });
  EXPECT_EQ(scans, clutch.stroke_scans);  // acknowledged in the scan that sees IROTMODE
  EXPECT_EQ(I("A03.AXD.65012"), 0);       // hunting off
  EXPECT_FALSE(B("A04C.READY"));          // the spindle idles
  EXPECT_TRUE(B("A03C.READY"));
  EXPECT_FALSE(B("A04.SPMOD_Q"));
  // The acknowledgement stays for as long as rotary axis mode is selected.
  for (int n = 0; n < 100; ++n) Cycle();
  EXPECT_TRUE(B("A04.ROTMOD_Q"));
  EXPECT_EQ(I("A03.AXD.65012"), 0);

  // C -> spindle: the spindle hunts and the valves switch back at once; ROTMOD_Q drops in the
  // next scan, as network 12 resets MPENDOR after network 11 has used it.
  Preselect(false);
  Cycle();
  EXPECT_EQ(I("A04.AXD.65012"), 0b1);  // spindle hunting
  EXPECT_TRUE(B("QSPMODE"));
  EXPECT_FALSE(B("QROTMODE"));
  EXPECT_FALSE(program->MPENDOR);
  Cycle();
  EXPECT_FALSE(B("A04.ROTMOD_Q"));
  EXPECT_TRUE(B("A04C.READY"));
  EXPECT_FALSE(B("A03C.READY"));
  CycleUntil([&] { return B("A04.SPMOD_Q"); });
  EXPECT_EQ(I("A04.AXD.65012"), 0);
  EXPECT_FALSE(B("A04.ROTMOD_Q"));
  EXPECT_EQ(I("P00.MSG_WR"), 0);

  // And to C again: the markers of the last changeover were reset, so C hunts again.
  Preselect(true);
  Cycle();
  EXPECT_EQ(I("A03.AXD.65012"), 0b100);
  CycleUntil([&] { return B("A04.ROTMOD_Q"); });
  EXPECT_EQ(I("A03.AXD.65012"), 0);
}

TEST_F(CAxisChangeoverTest, OnlyTheProgramsOutputsChange) {
  StartInSpindleMode();
  Preselect(true);
  CycleUntil([&] { return B("A04.ROTMOD_Q"); });
  Preselect(false);
  CycleUntil([&] { return B("A04.SPMOD_Q"); });
  std::sort(written.begin(), written.end());
  written.erase(std::unique(written.begin(), written.end()), written.end());
  EXPECT_EQ(written, (std::vector<std::string>{"A03.AXD.65012", "A03.AXD.65013", "A03.AXD.65014",
                                               "A03C.READY", "A04.AXD.65012", "A04.AXD.65013",
                                               "A04.AXD.65014", "A04.ROTMOD_Q", "A04.SPMOD_Q",
                                               "A04C.READY", "QROTMODE", "QSPMODE"}));
}

TEST_F(CAxisChangeoverTest, AClutchThatDoesNotEngageTimesOut) {
  StartInSpindleMode();
  clutch.blocked = true;
  Preselect(true);
  Cycle();
  EXPECT_EQ(I("A03.AXD.65012"), 0b100);
  // Hunting goes on for T_CLUTCH, then stops; the NC gets message 220 and no acknowledgement.
  const PlcTime start = plc.now();
  const int scans = CycleUntil([&] { return program->M_ROTERR; });
  EXPECT_EQ(PlcTime(scans * kPeriod), 5s);
  EXPECT_GE(plc.now() - start, 5s);
  EXPECT_EQ(I("A03.AXD.65012"), 0);
  EXPECT_EQ(I("P00.MSG_WR"), 220);
  EXPECT_FALSE(B("A04.ROTMOD_Q"));
  EXPECT_FALSE(B("A04.SPMOD_Q"));
  EXPECT_TRUE(B("QROTMODE"));    // the valves stay
  EXPECT_TRUE(B("A04C.READY"));  // the spindle was never given up
  for (int n = 0; n < 100; ++n) Cycle();
  EXPECT_EQ(I("A03.AXD.65012"), 0);  // no hunting while the error stands
  EXPECT_EQ(I("P00.MSG_WR"), 220);

  // Control-Reset: the NC drops its request; the error and the message go.
  Set("A04.ROTMOD", false);
  Cycle();
  EXPECT_FALSE(program->M_ROTERR);
  EXPECT_EQ(I("P00.MSG_WR"), 0);
  // The NC asks again and the dogs mesh this time: C hunts again and the changeover ends.
  Set("A04.ROTMOD", true);
  Cycle();
  EXPECT_EQ(I("A03.AXD.65012"), 0b100);
  clutch.blocked = false;
  CycleUntil([&] { return B("A04.ROTMOD_Q"); });
  EXPECT_EQ(I("A03.AXD.65012"), 0);
  EXPECT_EQ(I("P00.MSG_WR"), 0);
}

TEST_F(CAxisChangeoverTest, AClutchThatDoesNotReleaseTimesOut) {
  StartInSpindleMode();
  Preselect(true);
  CycleUntil([&] { return B("A04.ROTMOD_Q"); });
  clutch.blocked = true;
  Preselect(false);
  CycleUntil([&] { return program->M_SPERR; });
  EXPECT_EQ(I("A04.AXD.65012"), 0);  // spindle hunting off again
  EXPECT_EQ(I("P00.MSG_WR"), 221);
  EXPECT_FALSE(B("A04.SPMOD_Q"));
  EXPECT_FALSE(B("A04.ROTMOD_Q"));
}

TEST_F(CAxisChangeoverTest, TheMessageOfAnotherProgramIsNotCleared) {
  StartInSpindleMode();
  clutch.blocked = true;
  Preselect(true);
  CycleUntil([&] { return program->M_ROTERR; });
  image.SetInt(Id("P00.MSG_WR"), 205);  // somebody else's message since
  Set("A04.ROTMOD", false);
  Cycle();
  EXPECT_EQ(I("P00.MSG_WR"), 205);
}

TEST_F(CAxisChangeoverTest, ARequestWhileTheOtherIsPending) {
  StartInSpindleMode();
  clutch.blocked = true;
  Preselect(true);
  for (int n = 0; n < 50; ++n) Cycle();  // C hunting, dogs on dogs
  ASSERT_EQ(I("A03.AXD.65012"), 0b100);
  ASSERT_FALSE(B("A04.ROTMOD_Q"));

  // The NC gives rotary axis mode up for spindle mode (reverse, 2.3): C stops hunting, the
  // spindle hunts, the valves go back, and the released clutch is acknowledged.
  Preselect(false);
  Cycle();
  clutch.blocked = false;
  EXPECT_EQ(I("A03.AXD.65012"), 0);
  EXPECT_EQ(I("A04.AXD.65012"), 0b1);
  EXPECT_TRUE(B("QSPMODE"));
  EXPECT_FALSE(B("QROTMODE"));
  CycleUntil([&] { return B("A04.SPMOD_Q"); });
  EXPECT_EQ(I("A04.AXD.65012"), 0);
  EXPECT_FALSE(B("A04.ROTMOD_Q"));

  // Both requests at once is no state the NC gives: spindle mode (clutch out) wins.
  Set("A04.ROTMOD", true);
  Set("A04.SPMOD", true);
  for (int n = 0; n < 50; ++n) Cycle();
  EXPECT_TRUE(B("QSPMODE"));
  EXPECT_FALSE(B("QROTMODE"));
  EXPECT_TRUE(B("A04.SPMOD_Q"));
  EXPECT_FALSE(B("A04.ROTMOD_Q"));
  EXPECT_EQ(I("A03.AXD.65012"), 0);
}

TEST_F(CAxisChangeoverTest, ProgramStoppedHoldsTheHunting) {
  StartInSpindleMode();
  clutch.blocked = true;
  Preselect(true);
  Cycle();
  ASSERT_EQ(I("A03.AXD.65012"), 0b100);
  // PxxSSTOP: the SPS's movement stops at once (2.3 Immediate Stop) and the time does not count.
  Set("P00S.STOP", true);
  Cycle();
  EXPECT_EQ(I("A03.AXD.65012"), 0);
  for (int n = 0; n < 2000; ++n) Cycle();  // 8 s, longer than T_CLUTCH
  EXPECT_FALSE(program->M_ROTERR);
  EXPECT_EQ(I("A03.AXD.65012"), 0);
  // Continued: hunting again, and the dogs mesh.
  Set("P00S.STOP", false);
  Cycle();
  EXPECT_EQ(I("A03.AXD.65012"), 0b100);
  clutch.blocked = false;
  CycleUntil([&] { return B("A04.ROTMOD_Q"); });
  EXPECT_EQ(I("A03.AXD.65012"), 0);
}

TEST_F(CAxisChangeoverTest, PowerOnInRotaryAxisModeAcknowledgesAtOnce) {
  // The clutch engaged at power-on and the NC still selecting rotary axis mode (4.1: the
  // acknowledgement is due after power-on as well): no hunting, acknowledged in the first scan.
  image.SetBool(Id("IROTMODE"), true);
  image.SetBool(Id("ISPMODE"), false);
  image.SetBool(Id("QROTMODE"), false);
  Preselect(true);
  plc.Scan();
  EXPECT_TRUE(B("A04.ROTMOD_Q"));
  EXPECT_EQ(I("A03.AXD.65012"), 0);
  EXPECT_TRUE(B("QROTMODE"));
  EXPECT_TRUE(B("A03C.READY"));
  EXPECT_FALSE(B("A04C.READY"));
}

TEST(CAxisChangeoverWrongTest, AcknowledgesBeforeTheClutchHasMeshed) {
  // The deliberately wrong variant: ROTMOD_Q comes with the valve, while the dogs are still on
  // their way (or blocked), so the NC would position C with the spindle not coupled.
  gateway::SignalImage image(gateway::BuildSignalTable(LatheLayout()));
  CAxisChangeoverConfig config;
  config.acknowledge_before_clutch = true;
  auto program = std::make_shared<CAxisChangeover>(image, config);
  PlcRuntime plc(
      image, [p = program](PlcScan& s) { (*p)(s); }, kPeriod);
  Clutch clutch{image};
  clutch.Released();
  clutch.blocked = true;  // dogs on dogs: IROTMODE never comes
  image.SetBool(image.Require("A04.SPMOD"), true);
  plc.Scan();
  image.SetBool(image.Require("A04.SPMOD"), false);
  image.SetBool(image.Require("A04.ROTMOD"), true);
  clutch.Step();
  plc.Scan();
  EXPECT_TRUE(image.Bool(image.Require("QROTMODE")));
  EXPECT_TRUE(image.Bool(image.Require("A04.ROTMOD_Q")));
  EXPECT_FALSE(image.Bool(image.Require("IROTMODE")));
  // The right program waits for the switch.
  gateway::SignalImage right_image(gateway::BuildSignalTable(LatheLayout()));
  auto right = std::make_shared<CAxisChangeover>(right_image);
  PlcRuntime right_plc(
      right_image, [p = right](PlcScan& s) { (*p)(s); }, kPeriod);
  Clutch right_clutch{right_image};
  right_clutch.Released();
  right_clutch.blocked = true;
  right_image.SetBool(right_image.Require("A04.ROTMOD"), true);
  for (int n = 0; n < 50; ++n) right_clutch.Step(), right_plc.Scan();
  EXPECT_TRUE(right_image.Bool(right_image.Require("QROTMODE")));
  EXPECT_FALSE(right_image.Bool(right_image.Require("A04.ROTMOD_Q")));
}

}  // namespace
}  // namespace vmt::control::plc
