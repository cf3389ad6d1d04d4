#include "control/gateway/signal_image.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "tests/control/gateway/lathe_layout.hpp"

namespace vmt::control::gateway {
namespace {

using testing::LatheLayout;

class SignalImageTest : public ::testing::Test {
 protected:
  SignalImage image_{BuildSignalTable(LatheLayout())};
};

TEST_F(SignalImageTest, FindIsExactAndCaseSensitive) {
  const int id = image_.Find("P00C.REPOS");
  ASSERT_GE(id, 0);
  EXPECT_EQ(image_.table()[id].name, "P00C.REPOS");
  EXPECT_EQ(image_.Find("P00C.NOSUCH"), -1);
  EXPECT_EQ(image_.Find("p00c.repos"), -1);
  EXPECT_EQ(image_.Find("P00C.REPO"), -1);
  EXPECT_EQ(image_.Find(""), -1);
  EXPECT_EQ(image_.Find("PxxC.REPOS"), -1);  // patterns are not names
  EXPECT_EQ(image_.Find("P00SSTOP"), -1);    // aliases are not names
  EXPECT_GE(image_.Find("QMFB1A00.Q_MTstKol"), 0);
  EXPECT_EQ(image_.Find("QMFB1A00.Q_MTstKOl"), -1);
  // Every signal is found under its own name.
  for (int i = 0; i < image_.size(); ++i) EXPECT_EQ(image_.Find(image_.table()[i].name), i);
}

TEST_F(SignalImageTest, BoolGetSet) {
  const int id = image_.Require("P00S.CREST");
  EXPECT_FALSE(image_.Bool(id));
  image_.SetBool(id, true);
  EXPECT_TRUE(image_.Bool(id));
  image_.SetBool(id, false);
  EXPECT_FALSE(image_.Bool(id));
}

TEST_F(SignalImageTest, IntGetSetPerType) {
  const int i16 = image_.Require("QMFB1A00.FEHLER_NR");  // INT
  image_.SetInt(i16, -32768);
  EXPECT_EQ(image_.Int(i16), -32768);
  image_.SetInt(i16, 32767);
  EXPECT_EQ(image_.Int(i16), 32767);
  const int u16 = image_.Require("P00.mc_cmd_bs_type_w");  // UINT
  image_.SetInt(u16, 65535);
  EXPECT_EQ(image_.Int(u16), 65535);
  const int w16 = image_.Require("A03.AXD.65012");  // WORD
  image_.SetInt(w16, 0x0404);
  EXPECT_EQ(image_.Int(w16), 0x0404);
  const int i32 = image_.Require("A03.AXD.65013");  // DINT
  image_.SetInt(i32, -2147483648LL);
  EXPECT_EQ(image_.Int(i32), -2147483648LL);
  const int u32 = image_.Require("P00.bahn_state.block_count_r");  // UDINT
  image_.SetInt(u32, 4294967295LL);
  EXPECT_EQ(image_.Int(u32), 4294967295LL);
}

TEST_F(SignalImageTest, RealGetSet) {
  const int lreal = image_.Require("P00.mc_cmd_bs_covered_distance_w");
  image_.SetReal(lreal, 540.125);
  EXPECT_EQ(image_.Real(lreal), 540.125);
  image_.SetReal(lreal, 0.1);
  EXPECT_EQ(image_.Real(lreal), 0.1);  // binary64 keeps it
}

TEST_F(SignalImageTest, StringGetSet) {
  const int id = image_.Require("P00.mc_cmd_bs_block_nbr_prog_name_w");
  EXPECT_EQ(image_.String(id), "");
  image_.SetString(id, "%t_sv_number.nc");
  EXPECT_EQ(image_.String(id), "%t_sv_number.nc");
  const std::string longest(kStringBytes - 1, 'x');
  image_.SetString(id, longest);
  EXPECT_EQ(image_.String(id), longest);
}

TEST_F(SignalImageTest, NumberOfEveryType) {
  const int b = image_.Require("P00S.CREST");            // BOOL
  const int i16 = image_.Require("QMFB1A00.FEHLER_NR");  // INT
  const int i32 = image_.Require("A03.AXD.65013");       // DINT
  const int lreal = image_.Require("P00.mc_cmd_bs_covered_distance_w");
  const int s = image_.Require("P00.mc_cmd_bs_block_nbr_prog_name_w");  // STRING
  image_.SetNumber(b, 0.25);                                            // != 0: true
  EXPECT_TRUE(image_.Bool(b));
  EXPECT_EQ(image_.Number(b), 1);
  image_.SetNumber(b, 0);
  EXPECT_EQ(image_.Number(b), 0);
  image_.SetNumber(i16, -2.5);  // rounded half away from zero
  EXPECT_EQ(image_.Int(i16), -3);
  EXPECT_EQ(image_.Number(i16), -3);
  image_.SetNumber(i32, 123456.4);
  EXPECT_EQ(image_.Number(i32), 123456);
  image_.SetNumber(lreal, 540.125);
  EXPECT_EQ(image_.Real(lreal), 540.125);
  EXPECT_EQ(image_.Number(lreal), 540.125);
  image_.SetString(s, "%t.nc");
  image_.SetNumber(s, 7);  // a STRING is left as it is and reads 0
  EXPECT_EQ(image_.String(s), "%t.nc");
  EXPECT_EQ(image_.Number(s), 0);
}

TEST_F(SignalImageTest, SetNumberRoundsAsLlroundDoes) {
  const int i32 = image_.Require("A03.AXD.65013");  // DINT
  std::vector<double> values = {0.5,
                                -0.5,
                                1.5,
                                -1.5,
                                2.5,
                                -2.5,
                                0.49999999999999994,
                                -0.49999999999999994,
                                2147483647.4,
                                -2147483648.4,
                                1e-300,
                                -1e-300,
                                0.0,
                                -0.0};
  // Every quarter and its neighbours one ulp either side, over the DINT range's magnitudes.
  for (double m = 0.25; m < 2e9; m *= 3.7)
    for (double q : {0.0, 0.25, 0.5, 0.75})
      for (double v : {std::floor(m) + q, -(std::floor(m) + q)})
        for (double w : {std::nextafter(v, -1e10), v, std::nextafter(v, 1e10)}) values.push_back(w);
  for (double v : values) {
    const long long expected = std::llround(v);
    if (expected < -2147483648LL || expected > 2147483647LL) continue;
    image_.SetNumber(i32, v);
    EXPECT_EQ(image_.Int(i32), expected) << std::hexfloat << v;
  }
}

TEST_F(SignalImageTest, ChangesCountOnlyWritesThatChangeAValue) {
  const int b = image_.Require("P00S.CREST");
  const int i16 = image_.Require("QMFB1A00.FEHLER_NR");
  const int lreal = image_.Require("P00.mc_cmd_bs_covered_distance_w");
  const int s = image_.Require("P00.mc_cmd_bs_block_nbr_prog_name_w");
  uint64_t seen = image_.changes();
  const auto changed = [&] {
    const uint64_t before = std::exchange(seen, image_.changes());
    return before != seen;
  };
  image_.SetBool(b, false);  // as it was
  image_.SetInt(i16, image_.Int(i16));
  image_.SetString(s, "");
  EXPECT_FALSE(changed());
  image_.SetBool(b, true);
  EXPECT_TRUE(changed());
  image_.SetInt(i16, 7);
  EXPECT_TRUE(changed());
  image_.SetReal(lreal, 0.5);
  EXPECT_TRUE(changed());
  image_.SetReal(lreal, 0.5);
  EXPECT_FALSE(changed());
  image_.SetString(s, "%a.nc");  // a string changes no cell, but counts
  EXPECT_TRUE(changed());
  SignalImage other{image_.table()};
  image_.CopyValue(s, other);
  EXPECT_TRUE(changed());
  image_.CopyValuesFrom(other);
  EXPECT_TRUE(changed());
  image_.Reset();
  EXPECT_TRUE(changed());
}

TEST_F(SignalImageTest, PresetsAndReset) {
  const int q = image_.Require("QMFB1A00.Q_Nummer");
  const int fovr = image_.Require("P00C.FOVR");
  const int pass = image_.Require("P00.mc_cmd_bs_block_number_pass_w");
  EXPECT_EQ(image_.Int(q), 9992);
  EXPECT_EQ(image_.Int(fovr), 100);
  EXPECT_EQ(image_.Int(pass), 1);
  image_.SetInt(fovr, 50);
  const int repos = image_.Require("P00C.REPOS");
  image_.SetBool(repos, true);
  const int name = image_.Require("P00.mc_cmd_bs_pos_start_name_w");
  image_.SetString(name, "main.nc");
  image_.Reset();
  EXPECT_EQ(image_.Int(fovr), 100);
  EXPECT_FALSE(image_.Bool(repos));
  EXPECT_EQ(image_.String(name), "");
}

TEST_F(SignalImageTest, CopiesAreIndependent) {
  const int id = image_.Require("P00C.REPOS");
  SignalImage copy = image_;
  copy.SetBool(id, true);
  EXPECT_FALSE(image_.Bool(id));
  EXPECT_EQ(copy.Find("P00C.RESTA"), image_.Find("P00C.RESTA"));
}

TEST(SignalImage, RealIsStoredAsBinary32) {
  std::vector<Signal> table(1);
  table[0].name = "R";
  table[0].type = SignalType::kReal;
  table[0].direction = Direction::kNcToPlc;
  table[0].preset = 0;
  SignalImage image(table);
  image.SetReal(0, 0.1);
  EXPECT_EQ(image.Real(0), static_cast<double>(0.1f));
}

TEST(SignalImage, RejectsDuplicateNames) {
  std::vector<Signal> table(2);
  table[0].name = table[1].name = "P00C.REPOS";
  EXPECT_THROW(SignalImage{table}, std::invalid_argument);
}

using SignalImageDeathTest = SignalImageTest;

TEST_F(SignalImageDeathTest, WrongTypeAborts) {
  const int b = image_.Require("P00C.REPOS");
  const int i = image_.Require("P00C.FOVR");
  EXPECT_DEATH(image_.Int(b), "Int\\(P00C.REPOS\\): the signal is BOOL");
  EXPECT_DEATH(image_.SetBool(i, true), "SetBool\\(P00C.FOVR\\): the signal is INT");
  EXPECT_DEATH(image_.Real(i), "Real\\(P00C.FOVR\\)");
  EXPECT_DEATH(image_.String(b), "String\\(P00C.REPOS\\)");
}

TEST_F(SignalImageDeathTest, OutOfRangeAborts) {
  const int i16 = image_.Require("P00C.FOVR");
  EXPECT_DEATH(image_.SetInt(i16, 32768), "SetInt\\(P00C.FOVR, 32768\\): outside the range of INT");
  const int u16 = image_.Require("P00.mc_cmd_bs_type_w");
  EXPECT_DEATH(image_.SetInt(u16, -1), "outside the range of UINT");
  EXPECT_DEATH(image_.Bool(-1), "no such signal id");
  EXPECT_DEATH(image_.Bool(image_.size()), "no such signal id");
  EXPECT_DEATH((void)image_.Number(-1), "Number\\(-1\\): no such signal id");
  EXPECT_DEATH(image_.Require("P00C.NOSUCH"), "no signal called 'P00C.NOSUCH'");
  const int s = image_.Require("P00.mc_cmd_bs_pos_end_name_w");
  EXPECT_DEATH(image_.SetString(s, std::string(kStringBytes, 'x')), "at most 83");
}

TEST_F(SignalImageTest, RegistersHighWordFirst) {
  std::array<uint16_t, 2> two{};
  const int dint = image_.Require("A03.AXD.65013");
  image_.SetInt(dint, 1000000);  // 100 rpm in 0.0001 1/min: $F4240, c-axis 4.4
  ToRegisters(image_, dint, two);
  EXPECT_EQ(two[0], 0x000F);
  EXPECT_EQ(two[1], 0x4240);
  image_.SetInt(dint, -2);
  ToRegisters(image_, dint, two);
  EXPECT_EQ(two[0], 0xFFFF);
  EXPECT_EQ(two[1], 0xFFFE);

  std::array<uint16_t, 1> one{};
  const int i16 = image_.Require("QMFB1A00.FEHLER_NR");
  image_.SetInt(i16, -1);
  ToRegisters(image_, i16, one);
  EXPECT_EQ(one[0], 0xFFFF);

  std::array<uint16_t, 4> four{};
  const int lreal = image_.Require("P00.bahn_state.dist_prog_start");
  image_.SetReal(lreal, 1.0);  // 0x3FF0000000000000
  ToRegisters(image_, lreal, four);
  EXPECT_EQ(four, (std::array<uint16_t, 4>{0x3FF0, 0, 0, 0}));
}

TEST_F(SignalImageTest, RegistersRoundTrip) {
  const int i16 = image_.Require("QMFB1A00.FEHLER_NR");
  const std::array<uint16_t, 1> minus_one{0xFFFF};
  FromRegisters(image_, i16, minus_one);
  EXPECT_EQ(image_.Int(i16), -1);

  const int u16 = image_.Require("P00.mc_cmd_bs_type_w");
  FromRegisters(image_, u16, minus_one);
  EXPECT_EQ(image_.Int(u16), 65535);

  const int udint = image_.Require("P00.mc_cmd_bs_deviation_max_w");
  const std::array<uint16_t, 2> big{0xFFFF, 0xFFFF};
  FromRegisters(image_, udint, big);
  EXPECT_EQ(image_.Int(udint), 4294967295LL);

  const int lreal = image_.Require("P00.mc_cmd_bs_distance_prog_start_w");
  image_.SetReal(lreal, 2347.9);
  std::array<uint16_t, 4> four{};
  ToRegisters(image_, lreal, four);
  image_.SetReal(lreal, 0);
  FromRegisters(image_, lreal, four);
  EXPECT_EQ(image_.Real(lreal), 2347.9);

  const int str = image_.Require("P00.mc_cmd_bs_pos_start_name_w");
  image_.SetString(str, "ABC");
  std::array<uint16_t, kStringBytes / 2> regs{};
  ToRegisters(image_, str, regs);
  EXPECT_EQ(regs[0], 0x4142);
  EXPECT_EQ(regs[1], 0x4300);
  EXPECT_EQ(regs[2], 0);
  image_.SetString(str, "");
  FromRegisters(image_, str, regs);
  EXPECT_EQ(image_.String(str), "ABC");

  // A frame without NUL still decodes: the STRING keeps its first 83 bytes.
  regs.fill(0x4141);
  FromRegisters(image_, str, regs);
  EXPECT_EQ(image_.String(str), std::string(kStringBytes - 1, 'A'));
}

TEST_F(SignalImageDeathTest, RegisterMisuseAborts) {
  std::array<uint16_t, 1> one{};
  EXPECT_DEATH(ToRegisters(image_, image_.Require("P00C.REPOS"), one), "a BOOL is a bit");
  EXPECT_DEATH(ToRegisters(image_, image_.Require("A03.AXD.65013"), one),
               "1 registers for DINT, which takes 2");
}

}  // namespace
}  // namespace vmt::control::gateway
