// The machine_panel PLC program: panel keys to NC control signals, the door, quill and coolant
// with their interlocks, and the auxiliary-function acknowledgement.

#include "control/plc/programs/machine_panel.hpp"

#include <gtest/gtest.h>

#include <string>

#include "control/gateway/signal_table.hpp"
#include "control/plc/plc_programs.hpp"

namespace vmt::control::plc {
namespace {

class MachinePanelTest : public ::testing::Test {
 protected:
  static gateway::SignalImage Image() {
    gateway::GatewayLayout layout;
    layout.processes = {0};
    layout.axes = {{1, "X", false, false}, {2, "Z", false, false}, {3, "S1", true, false}};
    for (const char* out : {"QDOOR_OPEN", "QTAILSTOCK", "QCOOLANT"})
      layout.io.push_back({out, true, "valve"});
    for (const char* in : {"IDOOR_CLOSED", "ICOOLANT_PRESSURE", "ITAILSTOCK_FWD"})
      layout.io.push_back({in, false, "switch"});
    for (const char* key :
         {"mAUTO", "mMANU", "mSTART", "mSTOP", "mRESET", "mSBL", "mCOOLANT", "mDOOR", "mTAILSTOCK",
          "mJGPOS_X", "mJGNEG_X", "mJGPOS_Z", "mJGNEG_Z", "mREPOS", "mRESTA", "mRaR_OFF"})
      layout.io.push_back({key, false, "key"});
    return gateway::SignalImage(gateway::BuildSignalTable(layout));
  }

  MachinePanelTest()
      : image(Image()), plc(image, *MakePlcProgram("machine_panel", image), PlcTime(4000)) {
    Set("IDOOR_CLOSED", true);
    Set("A03S.N_NMIN", true);
  }

  void Set(const std::string& name, bool v) { image.SetBool(image.Require(name), v); }
  bool Get(const std::string& name) const { return image.Bool(image.Require(name)); }
  /// The operator presses a key for two scans and lets it go.
  void Press(const std::string& key) {
    Set(key, true);
    plc.Scan();
    plc.Scan();
    Set(key, false);
    plc.Scan();
  }

  gateway::SignalImage image;
  PlcRuntime plc;
};

TEST_F(MachinePanelTest, KeysBecomeControlSignals) {
  Set("mAUTO", true);
  plc.Scan();
  EXPECT_TRUE(Get("P00C.AUTO"));
  Set("mAUTO", false);
  plc.Scan();
  EXPECT_FALSE(Get("P00C.AUTO"));
  Set("mJGNEG_Z", true);
  plc.Scan();
  EXPECT_TRUE(Get("A02C.JGNEG"));
  EXPECT_FALSE(Get("A01C.JGNEG"));
  Set("mJGNEG_Z", false);
  Press("mSBL");
  EXPECT_TRUE(Get("P00C.SBL"));  // toggled on, stays
  Press("mSBL");
  EXPECT_FALSE(Get("P00C.SBL"));
}

TEST_F(MachinePanelTest, FeedHoldHoldsUntilStart) {
  Press("mSTOP");
  EXPECT_TRUE(Get("P00C.STOP"));  // held after the key is let go
  Set("mSTART", true);
  plc.Scan();
  EXPECT_FALSE(Get("P00C.STOP"));
  EXPECT_TRUE(Get("P00C.START"));
  Set("mSTART", false);
  plc.Scan();
  EXPECT_FALSE(Get("P00C.START"));
}

TEST_F(MachinePanelTest, DoorOpensOnlyAtRestAndAnOpenDoorHoldsTheFeed) {
  Set("P00S.RUN", true);
  Press("mDOOR");
  EXPECT_FALSE(Get("QDOOR_OPEN"));  // the program runs
  Set("P00S.RUN", false);
  Set("A03S.N_NMIN", false);
  Press("mDOOR");
  EXPECT_FALSE(Get("QDOOR_OPEN"));  // the spindle turns
  Set("A03S.N_NMIN", true);
  Press("mDOOR");
  EXPECT_TRUE(Get("QDOOR_OPEN"));
  Set("IDOOR_CLOSED", false);
  plc.Scan();
  EXPECT_TRUE(Get("P00C.STOP"));
  Set("mSTART", true);
  Set("mJGPOS_X", true);
  plc.Scan();
  EXPECT_FALSE(Get("P00C.START"));  // no cycle start with the door open
  EXPECT_FALSE(Get("A01C.JGPOS"));  // nor jogging
  Set("mSTART", false);
  Set("mJGPOS_X", false);
  Press("mDOOR");
  EXPECT_FALSE(Get("QDOOR_OPEN"));  // closes at any time
}

TEST_F(MachinePanelTest, QuillMovesOnlyWhileTheProgramDoesNotRun) {
  Set("P00S.RUN", true);
  Press("mTAILSTOCK");
  EXPECT_FALSE(Get("QTAILSTOCK"));
  Set("P00S.RUN", false);
  Press("mTAILSTOCK");
  EXPECT_TRUE(Get("QTAILSTOCK"));
  Press("mTAILSTOCK");
  EXPECT_FALSE(Get("QTAILSTOCK"));
}

// M08 waits for the pressure switch; M09 and other functions are acknowledged at once; each
// acknowledgement is a pulse, so a function that follows at once gets its own edge.
TEST_F(MachinePanelTest, AuxiliaryFunctionsAreAcknowledgedAsPulses) {
  image.SetInt(image.Require("P00S.MFUNC"), 8);
  Set("P00S.AUXSTB", true);
  plc.Scan();
  EXPECT_TRUE(Get("QCOOLANT"));
  EXPECT_FALSE(Get("P00C.AUXACK"));
  plc.Scan();
  EXPECT_FALSE(Get("P00C.AUXACK"));  // no pressure yet
  Set("ICOOLANT_PRESSURE", true);
  plc.Scan();
  EXPECT_TRUE(Get("P00C.AUXACK"));
  // The NC has moved on to the next block's M03 before the PLC saw AUXSTB drop.
  image.SetInt(image.Require("P00S.MFUNC"), 3);
  plc.Scan();
  EXPECT_FALSE(Get("P00C.AUXACK"));  // the pulse ends
  plc.Scan();
  EXPECT_TRUE(Get("P00C.AUXACK"));  // M03 gets an edge of its own
  EXPECT_TRUE(Get("QCOOLANT"));
  image.SetInt(image.Require("P00S.MFUNC"), 9);
  plc.Scan();
  plc.Scan();
  EXPECT_FALSE(Get("QCOOLANT"));
  Set("P00S.AUXSTB", false);
  Press("mCOOLANT");
  EXPECT_TRUE(Get("QCOOLANT"));  // the key toggles it too
}

TEST_F(MachinePanelTest, RepositioningKeysAreANetworkOfIt) {
  Set("P00S.REPOS", true);
  Press("mREPOS");
  EXPECT_TRUE(Get("P00C.REPOS"));
}

TEST(MachinePanelChangeoverTest, RunsTheChangeoverWhenTheSpindleHasARotaryAxisMode) {
  // lathe-c1: S1 (A03) with its rotary axis mode C (A04) through clutch K.
  gateway::GatewayLayout layout;
  layout.processes = {0};
  layout.axes = {{1, "X", false, false},
                 {2, "Z", false, false},
                 {3, "S1", true, false},
                 {4, "C", false, true}};
  for (const char* out : {"QDOOR_OPEN", "QTAILSTOCK", "QCOOLANT", "QROTMODE", "QSPMODE"})
    layout.io.push_back({out, true, "valve"});
  for (const char* in : {"IDOOR_CLOSED", "ICOOLANT_PRESSURE", "IROTMODE", "ISPMODE"})
    layout.io.push_back({in, false, "switch"});
  for (const char* key :
       {"mAUTO", "mMANU", "mSTART", "mSTOP", "mRESET", "mSBL", "mCOOLANT", "mDOOR", "mTAILSTOCK"})
    layout.io.push_back({key, false, "key"});
  gateway::SignalImage image(gateway::BuildSignalTable(layout));
  PlcRuntime plc(image, *MakePlcProgram("machine_panel", image), PlcTime(4000));
  image.SetBool(image.Require("ISPMODE"), true);
  plc.Scan();
  EXPECT_TRUE(image.Bool(image.Require("A03.SPMOD_Q")));  // power-on: clutch out, spindle mode
  EXPECT_EQ(image.Int(image.Require("A04.AXD.65013")), 10000);
  image.SetBool(image.Require("A03.ROTMOD"), true);
  plc.Scan();
  EXPECT_TRUE(image.Bool(image.Require("QROTMODE")));
  EXPECT_EQ(image.Int(image.Require("A04.AXD.65012")), 0b100);  // C hunts
}

// The panel's machine I/O and keys without the optional ones (jog mode keys, selectors).
gateway::GatewayLayout PanelLayout() {
  gateway::GatewayLayout layout;
  layout.processes = {0};
  layout.axes = {{1, "X", false, false}, {2, "Z", false, false}, {3, "S1", true, false}};
  for (const char* out : {"QDOOR_OPEN", "QTAILSTOCK", "QCOOLANT"})
    layout.io.push_back({out, true, "valve"});
  for (const char* in : {"IDOOR_CLOSED", "ICOOLANT_PRESSURE"})
    layout.io.push_back({in, false, "switch"});
  for (const char* key :
       {"mAUTO", "mMANU", "mSTART", "mSTOP", "mRESET", "mSBL", "mCOOLANT", "mDOOR", "mTAILSTOCK"})
    layout.io.push_back({key, false, "key"});
  return layout;
}

// The jog mode selector: each key toggles its bit of PxxC.JOGM0..2.
TEST(MachinePanelJogMode, EachKeyTogglesItsBitOfTheJogModeCode) {
  gateway::GatewayLayout layout = PanelLayout();
  for (const char* key : {"mJOGM0", "mJOGM1", "mJOGM2"}) layout.io.push_back({key, false, "key"});
  gateway::SignalImage image(gateway::BuildSignalTable(layout));
  PlcRuntime plc(image, *MakePlcProgram("machine_panel", image), PlcTime(4000));
  auto press = [&](const char* key) {
    image.SetBool(image.Require(key), true);
    plc.Scan();
    image.SetBool(image.Require(key), false);
    plc.Scan();
  };
  auto code = [&] {
    int c = 0;
    for (int bit = 0; bit < 3; ++bit)
      c |= image.Bool(image.Require("P00C.JOGM" + std::to_string(bit))) << bit;
    return c;
  };
  plc.Scan();
  EXPECT_EQ(code(), 0);  // continuous
  press("mJOGM1");
  EXPECT_EQ(code(), 2);  // parametric
  press("mJOGM0");
  press("mJOGM1");
  press("mJOGM2");
  EXPECT_EQ(code(), 5);
  press("mJOGM0");
  press("mJOGM2");
  EXPECT_EQ(code(), 0);
}

// The override switches are selectors (INT inputs): their positions are the feed override and the
// spindle's override, every scan; a machine without them leaves both at their presets.
TEST(MachinePanelOverrides, SelectorPositionsAreTheFeedAndSpindleOverrides) {
  gateway::GatewayLayout layout = PanelLayout();
  gateway::SignalImage bare(gateway::BuildSignalTable(layout));
  layout.io.push_back({"mFOVR", false, "selector", true, 100});
  layout.io.push_back({"mSOVR_S1", false, "selector", true, 90});
  gateway::SignalImage image(gateway::BuildSignalTable(layout));
  EXPECT_EQ(image.table()[image.Require("mFOVR")].type, gateway::SignalType::kInt);

  PlcRuntime plc(image, *MakePlcProgram("machine_panel", image), PlcTime(4000));
  plc.Scan();
  EXPECT_EQ(image.Int(image.Require("P00C.FOVR")), 100);
  EXPECT_EQ(image.Int(image.Require("A03C.SOVR")), 90);
  image.SetInt(image.Require("mFOVR"), 40);
  image.SetInt(image.Require("mSOVR_S1"), 115);
  plc.Scan();
  EXPECT_EQ(image.Int(image.Require("P00C.FOVR")), 40);
  EXPECT_EQ(image.Int(image.Require("A03C.SOVR")), 115);

  PlcRuntime without(bare, *MakePlcProgram("machine_panel", bare), PlcTime(4000));
  without.Scan();
  EXPECT_EQ(bare.Int(bare.Require("P00C.FOVR")), 100);  // the signal's preset
  EXPECT_EQ(bare.Int(bare.Require("A03C.SOVR")), 100);
}

// machine_panel_nc_turret: the turret is the NC's (REPOS manual 3.4) - the clamp released for
// the NC's drive, mMGPOS / mMGNEG to PxxC.MGPOS / MGNEG while the door is closed.
TEST(MachinePanelNcTurret, ReleasesTheClampAndPassesTheTurretJogKeys) {
  gateway::GatewayLayout layout;
  layout.processes = {0};
  layout.axes = {{1, "X", false, false}, {2, "Z", false, false}, {3, "S1", true, false}};
  for (const char* out : {"QDOOR_OPEN", "QTAILSTOCK", "QCOOLANT", "QTURRET_UNCLAMP"})
    layout.io.push_back({out, true, "valve"});
  for (const char* in : {"IDOOR_CLOSED", "ICOOLANT_PRESSURE"})
    layout.io.push_back({in, false, "switch"});
  for (const char* key : {"mAUTO", "mMANU", "mSTART", "mSTOP", "mRESET", "mSBL", "mCOOLANT",
                          "mDOOR", "mTAILSTOCK", "mMGPOS", "mMGNEG"})
    layout.io.push_back({key, false, "key"});
  gateway::SignalImage image(gateway::BuildSignalTable(layout));
  auto set = [&](const char* name, bool v) { image.SetBool(image.Require(name), v); };
  auto get = [&](const char* name) { return image.Bool(image.Require(name)); };
  {
    // machine_panel keeps its hands off the turret.
    PlcRuntime plc(image, *MakePlcProgram("machine_panel", image), PlcTime(4000));
    set("IDOOR_CLOSED", true);
    set("mMGPOS", true);
    plc.Scan();
    EXPECT_FALSE(get("QTURRET_UNCLAMP"));
    EXPECT_FALSE(get("P00C.MGPOS"));
    set("mMGPOS", false);
  }
  PlcRuntime plc(image, *MakePlcProgram("machine_panel_nc_turret", image), PlcTime(4000));
  plc.Scan();
  EXPECT_TRUE(get("QTURRET_UNCLAMP"));
  set("mMGPOS", true);
  plc.Scan();
  EXPECT_TRUE(get("P00C.MGPOS"));
  EXPECT_FALSE(get("P00C.MGNEG"));
  set("mMGPOS", false);
  set("mMGNEG", true);
  plc.Scan();
  EXPECT_FALSE(get("P00C.MGPOS"));
  EXPECT_TRUE(get("P00C.MGNEG"));
  set("IDOOR_CLOSED", false);  // an open door: no jog
  plc.Scan();
  EXPECT_FALSE(get("P00C.MGNEG"));
}

}  // namespace
}  // namespace vmt::control::plc
