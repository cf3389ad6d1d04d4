// The probe program's reaction to the Q functions the NC outputs (mtc200-fast-measurement.md
// 6.1 fault categories, 7.2 typical application networks 5..12, 18, 19): Q9999 locks the
// process and writes message 205 until the reverse program starts, Q9998 writes message 204
// while the NC holds the program by itself.

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "control/gateway/signal_table.hpp"
#include "control/measure/measuring_messages.hpp"
#include "control/plc/plc_runtime.hpp"
#include "control/plc/programs/probe_block.hpp"
#include "probe_block_test_support.hpp"

namespace vmt::control::plc {
namespace {

using testing::kScan;

struct Plant {
  gateway::SignalImage image;
  std::shared_ptr<ProbeBlockProgram> program;
  PlcRuntime plc;

  Plant()
      : image(gateway::BuildSignalTable(Layout())),
        program(std::make_shared<ProbeBlockProgram>(image)),
        plc(
            image, [p = program](PlcScan& s) { (*p)(s); }, kScan) {
    Set("QMFB1A00.ENABLE", true);
    image.SetInt(image.Require("QMFB1A00.ACHS_NR_1"), 1);
    image.SetInt(image.Require("QMFB1A00.ACHS_NR_2"), 2);
    Scan();
  }
  Plant(const Plant&) = delete;  // the runtime holds the image by reference

  static gateway::GatewayLayout Layout() {
    gateway::GatewayLayout layout;
    layout.processes = {0};
    layout.axes = {{1, "X", false, false}, {2, "Z", false, false}};
    return layout;
  }
  bool Bool(const char* name) const { return image.Bool(image.Require(name)); }
  int64_t Int(const char* name) const { return image.Int(image.Require(name)); }
  void Set(const char* name, bool v) { image.SetBool(image.Require(name), v); }
  void Scan(int scans = 1) {
    for (int i = 0; i < scans; ++i) plc.Scan();
  }
};

// The definitions the program acts on: fault category 1 leaves only the reverse program and
// has message 205, fault category 2 continues with the advance program and has 204.
TEST(ProbeBlockMessagesTest, TheQFunctionsDefineTheMessageNumbers) {
  EXPECT_EQ(measure::QFunction(measure::kQ9999)->plc_message, 205);
  EXPECT_EQ(measure::QFunction(measure::kQ9998)->plc_message, 204);
}

// Network 5, 8, 9, 10, 18: Q9999 sets M_Q9999, which removes the process enable and writes
// message 205; the acknowledgement waits for the reverse program, whose start clears both.
TEST(ProbeBlockMessagesTest, Q9999LocksTheProcessWithMessage205UntilTheReverseProgram) {
  Plant p;
  EXPECT_TRUE(p.Bool("P00C.ENABL"));
  EXPECT_EQ(p.Int("P00.MSG_WR"), 0);
  p.Set("P00.Q9999", true);
  p.Scan();
  EXPECT_TRUE(p.program->M_Q9999);
  EXPECT_FALSE(p.Bool("P00C.ENABL"));
  EXPECT_EQ(p.Int("P00.MSG_WR"), 205);
  EXPECT_FALSE(p.Bool("P00.Q9999_Q"));
  p.Scan(5);  // a fault category 1 stays: no acknowledgement, no enable
  EXPECT_FALSE(p.Bool("P00C.ENABL"));
  EXPECT_EQ(p.Int("P00.MSG_WR"), 205);
  EXPECT_FALSE(p.Bool("P00.Q9999_Q"));

  p.Set("P00S.REV", true);  // the reverse program becomes active
  p.Scan();
  EXPECT_TRUE(p.Bool("P00.Q9999_Q"));
  EXPECT_FALSE(p.program->M_Q9999);
  EXPECT_TRUE(p.Bool("P00C.ENABL"));
  EXPECT_EQ(p.Int("P00.MSG_WR"), 0);
  p.Set("P00.Q9999", false);  // the NC has taken the acknowledgement
  p.Set("P00S.REV", false);
  p.Scan();
  EXPECT_FALSE(p.Bool("P00.Q9999_Q"));
  EXPECT_TRUE(p.Bool("P00C.ENABL"));
}

// The reverse program start key (network 10) and Control-Reset (its key, or the NC dropping
// the unacknowledged output) clear M_Q9999 too.
TEST(ProbeBlockMessagesTest, TheReverseKeyOrControlResetClearsQ9999sLock) {
  for (const char* key : {"P00C.REV", "P00C.RESET", "P00.Q9999"}) {
    Plant p;
    p.Set("P00.Q9999", true);
    p.Scan();
    ASSERT_FALSE(p.Bool("P00C.ENABL")) << key;
    p.Set(key, std::string(key) != "P00.Q9999");
    p.Scan();
    EXPECT_FALSE(p.program->M_Q9999) << key;
    EXPECT_TRUE(p.Bool("P00C.ENABL")) << key;
    EXPECT_EQ(p.Int("P00.MSG_WR"), 0) << key;
  }
}

// Network 6, 11, 19: Q9998 is acknowledged at once and writes message 204; the process enable
// stays (the NC holds the program itself). The message lasts while the program stays stopped
// and clears when the new start takes it on.
TEST(ProbeBlockMessagesTest, Q9998WritesMessage204UntilTheProgramGoesOn) {
  Plant p;
  p.Set("P00S.RUN", true);
  p.Set("P00.Q9998", true);
  p.Scan();
  EXPECT_TRUE(p.Bool("P00.Q9998_Q"));
  EXPECT_TRUE(p.program->M_Q9998);
  EXPECT_EQ(p.Int("P00.MSG_WR"), 204);
  EXPECT_TRUE(p.Bool("P00C.ENABL"));
  // The NC takes the acknowledgement and holds with OVERSIZE / UNDERSIZE.
  p.Set("P00.Q9998", false);
  p.Set("P00S.RUN", false);
  p.Set("P00S.STOP", true);
  p.Scan(5);
  EXPECT_EQ(p.Int("P00.MSG_WR"), 204);
  EXPECT_TRUE(p.Bool("P00C.ENABL"));
  // The new advance start continues the program.
  p.Set("P00S.STOP", false);
  p.Set("P00S.RUN", true);
  p.Scan();
  EXPECT_FALSE(p.program->M_Q9998);
  EXPECT_EQ(p.Int("P00.MSG_WR"), 0);
}

// A probe collision of the block and the NC's Q9999 together: the probe's own message (203)
// shows; when the collision is cleared (RESET) and Q9999 still stands, 205 shows.
TEST(ProbeBlockMessagesTest, TheCollisionMessageComesBeforeQ9999s) {
  Plant p;
  p.Set("P00.Q9992", true);
  for (int i = 0; i < 10 && !p.Bool("P00.Q9992_Q"); ++i) p.Scan();
  ASSERT_TRUE(p.Bool("P00.Q9992_Q"));
  p.Set("P00.Q9992", false);
  p.Set("P00.EV29", true);
  p.Set("QMFB1A00.I_MT_OK1", true);
  p.Set("QMFB1A00.I_MTast1", true);  // displaced on the way in
  p.Set("P00.Q9999", true);
  p.Scan(2);
  EXPECT_TRUE(p.program->Measuring.Q_MTstKol);
  EXPECT_FALSE(p.Bool("P00C.ENABL"));
  EXPECT_EQ(p.Int("P00.MSG_WR"), 203);
  p.Set("QMFB1A00.RESET", true);
  p.Scan();
  EXPECT_FALSE(p.program->Measuring.Q_MTstKol);
  EXPECT_FALSE(p.Bool("P00C.ENABL"));
  EXPECT_EQ(p.Int("P00.MSG_WR"), 205);
}

}  // namespace
}  // namespace vmt::control::plc
