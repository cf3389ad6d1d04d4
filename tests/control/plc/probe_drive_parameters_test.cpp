// What QMFB1Axx's AXD_WR writes into a measuring axis's drive for BASISMESSPAGE elements 6 (pin)
// and 7 (contact), and how AxxC.QDDS / AxxS.IDDS reach the drive's probe function through the
// real-time bits (fast-measurement manual 7.2, 7.3).

#include "control/plc/programs/probe_drive_parameters.hpp"

#include <gtest/gtest.h>

namespace vmt::control::plc {
namespace {

namespace pc = probe_control;

TEST(ProbeDriveParametersTest, ThePageChoosesTheProbeAndItsEdge) {
  struct Case {
    bool pin5, normally_closed;
    uint16_t s303, s307, s169;
  };
  for (const Case& c : {Case{false, false, 405, 409, pc::kProbe1Positive},
                        Case{false, true, 405, 410, pc::kProbe1Negative},
                        Case{true, false, 406, 411, pc::kProbe2Positive},
                        Case{true, true, 406, 412, pc::kProbe2Negative}}) {
    BasisMessPage page;
    page.PIN_DDS = c.pin5;
    page.Pushbutton_contact = c.normally_closed;
    const ProbeDriveParameters p = AxdWrProbeParameters(page);
    EXPECT_EQ(p.S_0_0170, 3) << c.pin5 << c.normally_closed;
    EXPECT_EQ(p.S_0_0303, c.s303) << c.pin5 << c.normally_closed;
    EXPECT_EQ(p.S_0_0307, c.s307) << c.pin5 << c.normally_closed;
    EXPECT_EQ(p.S_0_0169, c.s169) << c.pin5 << c.normally_closed;
  }
}

TEST(ProbeDriveParametersTest, QddsIsTheEnableS0303Names) {
  BasisMessPage pin4;
  const ProbeDriveParameters p4 = AxdWrProbeParameters(pin4);
  ProbeControl c = ProbeControlOf(p4, true);
  EXPECT_EQ(c.probe_cycle_command, 3);
  EXPECT_EQ(c.probe_control_parameter, pc::kProbe1Positive);
  EXPECT_TRUE(c.probe1_enable);
  EXPECT_FALSE(c.probe2_enable);
  c = ProbeControlOf(p4, false);
  EXPECT_FALSE(c.probe1_enable);
  EXPECT_EQ(c.probe_cycle_command, 3);  // the function stays on between measurements

  BasisMessPage pin5;
  pin5.PIN_DDS = true;
  c = ProbeControlOf(AxdWrProbeParameters(pin5), true);
  EXPECT_FALSE(c.probe1_enable);
  EXPECT_TRUE(c.probe2_enable);
  // Not initialised (all 0): the drive's function stays off whatever QDDS says.
  c = ProbeControlOf(ProbeDriveParameters{}, true);
  EXPECT_EQ(c.probe_cycle_command, 0);
  EXPECT_FALSE(c.probe1_enable || c.probe2_enable);
}

TEST(ProbeDriveParametersTest, IddsIsTheFlagS0307Names) {
  ProbeStatus s;
  ProbeDriveParameters p;
  for (uint16_t idn : {409, 410, 411, 412}) {
    p.S_0_0307 = idn;
    s = {};
    EXPECT_FALSE(RealTimeStatusBit2(p, s)) << idn;
    s.probe1.positive.latched = idn == 409;
    s.probe1.negative.latched = idn == 410;
    s.probe2.positive.latched = idn == 411;
    s.probe2.negative.latched = idn == 412;
    EXPECT_TRUE(RealTimeStatusBit2(p, s)) << idn;
    // Every other flag set, this one clear: the bit is clear.
    s.probe1.positive.latched = !s.probe1.positive.latched;
    s.probe1.negative.latched = !s.probe1.negative.latched;
    s.probe2.positive.latched = !s.probe2.positive.latched;
    s.probe2.negative.latched = !s.probe2.negative.latched;
    EXPECT_FALSE(RealTimeStatusBit2(p, s)) << idn;
  }
  p.S_0_0307 = 0;
  s.probe1.positive.latched = s.probe1.negative.latched = true;
  EXPECT_FALSE(RealTimeStatusBit2(p, s));
}

}  // namespace
}  // namespace vmt::control::plc
