// TLD / OTD / MTD in programs the channel runs: wear registers move the tool tip under G48, OTD
// shifts a zero offset, MTD reads the machine data pages the channel was given.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"
#include "control/measure/measuring_pages.hpp"
#include "measuring_lathe.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing
using ::testing::HasSubstr;

// T2 D1 of WithOffsetsAndTools: lengths X 1.5, Z -4. Wear L1 lies along Z, L2 along X.
TEST(ChannelDataAccessTest, WearAddsToTheLengthUnderG48AndG49) {
  const std::string wear =
      "N1 TLD(1,2,,1,11,) = TLD(1,2,,1,11,) + 0.05\n"
      "N2 TLD(1,2,,1,12,) = TLD(1,2,,1,12,) + 0.05\n";
  Machine plus(wear + "N3 G48 T2 D1 G00 X10 Z0\nN4 RET\n", 0, 0, WithOffsetsAndTools);
  plus.channel->Start();
  plus.RunUntilEnd();
  ASSERT_EQ(plus.channel->state(), ChannelState::kEnded) << plus.channel->error();
  // G48: axis = program - length; the tip is 0.05 further from the reference point.
  EXPECT_NEAR(plus.X(), 10 - (1.5 + 0.05), 1e-9);
  EXPECT_NEAR(plus.Z(), 0 - (-4 + 0.05), 1e-9);
  Machine minus(wear + "N3 G49 T2 D1 G00 X10 Z0\nN4 RET\n", 0, 0, WithOffsetsAndTools);
  minus.channel->Start();
  minus.RunUntilEnd();
  ASSERT_EQ(minus.channel->state(), ChannelState::kEnded) << minus.channel->error();
  EXPECT_NEAR(minus.X(), 10 + (1.5 + 0.05), 1e-9);
  EXPECT_NEAR(minus.Z(), 0 + (-4 + 0.05), 1e-9);
}

TEST(ChannelDataAccessTest, WearOfTheActiveToolActsFromTheNextBlock) {
  // Omitted D: the active edge of the active tool (2.1's TLD(,...) "tool in the current
  // process"); the wear written between two moves of the same tool moves the second one.
  Machine m(
      "N1 G48 T2 D1 G00 X10 Z0\n"
      "N2 TLD(,2,,,12,) = -0.1\n"
      "N3 G00 X10 Z0\n"
      "N4 RET\n",
      0, 0, WithOffsetsAndTools);
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 10 - (1.5 - 0.1), 1e-9);
  EXPECT_NEAR(m.Z(), 4, 1e-9);
}

TEST(ChannelDataAccessTest, GeometryLengthsReadAlongTheirAxes) {
  // Elements 1 (L1, Z) and 2 (L2, X): read into variables and moved to under G47 G53.
  Machine m(
      "N1 @100 = TLD(1,2,,1,1,)\n"
      "N2 @101 = TLD(1,2,,1,2,)\n"
      "N3 G47 G00 X@101 Z@100\n"
      "N4 RET\n",
      0, 0, WithOffsetsAndTools);
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 1.5, 1e-9);
  EXPECT_NEAR(m.Z(), -4, 1e-9);
}

TEST(ChannelDataAccessTest, OtdWriteShiftsAG54Move) {
  // 2.1: OTD(,,4,1) is the X entry of G54 (X+5, Z+100 in WithOffsetsAndTools).
  Machine m(
      "N1 OTD(,,4,1) = OTD(,,4,1) + 0.5\n"
      "N2 OTD(1,0,4,2) = -7\n"
      "N3 G54 G00 X10 Z0\n"
      "N4 RET\n",
      0, 0, WithOffsetsAndTools);
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 15.5, 1e-9);
  EXPECT_NEAR(m.Z(), -7, 1e-9);
}

TEST(ChannelDataAccessTest, MtdReadsThePresetPagesAndCorrectsTheWear) {
  // 5.6: the correction value of ERGEBNISPAGE 105 into wear L2 of the tool.
  measure::MeasuringPages pages;
  pages.Result(0, 2)->correction_value = 0.02;
  pages.stylus[0].sphere_radius[0] = 3;
  Machine m(
      "N1 TLD(1,2,,1,12,) = TLD(1,2,,1,12,) + MTD(105,,2,13)\n"
      "N2 @100 = MTD(102,1,,4)\n"  // TASTWERKZEUGPAGE stylus 1: sphere radius 1
      "N3 G48 T2 D1 G00 X10 Z@100\n"
      "N4 MTD(105,,2,13) = 0\n"
      "N5 RET\n",
      0, 0, WithOffsetsAndTools);
  m.channel->SetMeasuringPages(&pages);
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 10 - (1.5 + 0.02), 1e-9);
  EXPECT_NEAR(m.Z(), 3 + 4, 1e-9);
  EXPECT_EQ(pages.Result(0, 2)->correction_value, 0);
}

// The program stops at the access with the channel's error and file:line:column.
std::string ErrorOf(const std::string& program, measure::MeasuringPages* pages = nullptr) {
  Machine m(program, 0, 0, WithOffsetsAndTools);
  if (pages) m.channel->SetMeasuringPages(pages);
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kError) << program;
  return m.channel->error();
}

TEST(ChannelDataAccessTest, BadAddressesStopTheProgram) {
  EXPECT_THAT(ErrorOf("N1 @1 = TLD(1,9,,1,11,)\nN2 RET\n"),
              HasSubstr("p.mtc:1:9: error: TLD(1,9,,1,11,): T9 D1 is not in the tool list"));
  // 2.1's form with T at position 3 is not taken for T12 (its position 2 reads as T1).
  EXPECT_THAT(ErrorOf("N1 TLD(,1,12,,11,) = 0\nN2 RET\n"),
              HasSubstr("p.mtc:1:4: error: TLD(,1,12,,11,): argument 3 is not used: the T "
                        "number is argument 2"));
  EXPECT_THAT(ErrorOf("N1 @1 = TLD(1,2,,1,7,)\nN2 RET\n"),
              HasSubstr("argument 5 (element) must be 1, 2, 3"));
  EXPECT_THAT(ErrorOf("N1 TLD(1,2,,1,1,) = 3\nN2 RET\n"),
              HasSubstr("the length L1 is the set-up's and cannot be written"));
  EXPECT_THAT(ErrorOf("N1 @1 = TLD(2,2,,1,11,)\nN2 RET\n"),
              HasSubstr("argument 1 (NC memory) must be a whole number in 1..1"));
  EXPECT_THAT(ErrorOf("N1 @1 = TLD(1,2,,1,11)\nN2 RET\n"), HasSubstr("TLD has 6 arguments"));
  EXPECT_THAT(ErrorOf("N1 @1 = TLD(1,2,,1,3,)\nN2 RET\n"),
              HasSubstr("the length L3 lies along Y, which this channel does not have"));
  EXPECT_THAT(ErrorOf("N1 OTD(,,10,1) = 1\nN2 RET\n"),
              HasSubstr("OTD(,,10,1): argument 3 (table, 4..9 for G54..G59) must be a whole "
                        "number in 4..9"));
  EXPECT_THAT(ErrorOf("N1 @1 = OTD(,,4,3)\nN2 RET\n"),
              HasSubstr("argument 4 (channel axis) must be a whole number in 1..2"));
  EXPECT_THAT(ErrorOf("N1 @1 = OTD(,1,4,1)\nN2 RET\n"),
              HasSubstr("argument 2 (process) must be a whole number in 0..0"));
  EXPECT_THAT(ErrorOf("N1 @1 = OTD(,,4.5,1)\nN2 RET\n"), HasSubstr("OTD(,,4.5,1): argument 3"));
  EXPECT_THAT(ErrorOf("N1 @1 = MTD(105,,1,13)\nN2 RET\n"),
              HasSubstr("p.mtc:1:9: error: MTD(105,,1,13): no machine data pages"));
  measure::MeasuringPages pages;
  EXPECT_THAT(ErrorOf("N1 @1 = MTD(105,,99,13)\nN2 RET\n", &pages), HasSubstr("MTD(105,,99,13)"));
  EXPECT_THAT(ErrorOf("N1 MTD(90,,,1) = 7\nN2 RET\n", &pages),
              HasSubstr("is set at installation, not by the NC program"));
  EXPECT_THAT(ErrorOf("N1 @1 = MTD(,,1,13)\nN2 RET\n", &pages),
              HasSubstr("the page (argument 1) and the element (argument 4) must be given"));
}

TEST(ChannelDataAccessTest, WearWrittenByTheReposSubroutineMovesTheContourAsAnOperatorEdit) {
  // REPOS manual 2.5: the wear written while the program is interrupted shifts the return to
  // the contour and the rest of the program, as SetToolLength does (channel_repositioning_test).
  Machine m(
      "N0 T2 D1 G48 G00 X1.5 Z-4\nN1 G01 X100 F600\nN2 RET\n"
      ".REPOS\nN10 TLD(1,2,,1,12,) = 0.05\nN11 G77 Z0 F3000\nN12 G77 X0 F3000 RTS\n",
      0, 0, WithOffsetsAndTools);
  auto run_for = [&](double s) {
    for (int i = 0; i < s / 250e-6; ++i) m.Tick();
  };
  m.channel->Start();
  run_for(3.0);
  m.channel->Stop();
  run_for(0.2);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->Jog(1, +1);
  run_for(0.2);
  m.channel->Jog(1, 0);
  run_for(0.1);
  m.channel->SetReposition(true, false);
  run_for(0.01);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 100 - 1.55, 1e-9);
  EXPECT_NEAR(m.Z(), 0, 1e-9);
}

TEST(ChannelDataAccessTest, CorrectionValueOfAMeasurementGoesIntoTheWear) {
  // 5.6 in small: PROBE a diameter 0.05 oversize, COMPARE, CORRECTION, then the correction value
  // into wear L2 (X) of the turning tool T1, which the next G48 move applies. The TLD statement
  // after CORRECTION reads ERGEBNISPAGE only once CORRECTION has written it.
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 PROBE(1,1,30,5,,X,-2,100,1,1,0)\n"
      "N3 COMPARE(1,0,1,)\n"
      "N4 CORRECTION(1,0.1,-0.1,0.24,0.18,0,0,1,0,0)\n"
      "N5 TLD(1,1,,1,12,) = TLD(1,1,,1,12,) + MTD(105,,1,13)\n"
      "N6 G48 T1 D1 G00 X40 Z5\n"
      "N7 RET\n",
      30.05);
  Machine& m = l.m;
  m.channel->Start();
  l.RunUntilStopped();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  const double correction = l.pages.Result(0, 1)->correction_value;
  EXPECT_GT(std::abs(correction), 0.01);
  EXPECT_NEAR(m.X(), 40 - correction, 1e-9);
  EXPECT_NEAR(m.Z(), 5, 1e-9);
}

TEST(ChannelDataAccessTest, MdiBlocksReachTheData) {
  Machine m("N1 RET\n", 0, 0, WithOffsetsAndTools);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kMdi));
  ASSERT_TRUE(m.channel->Mdi("OTD(,,4,1) = 1\nG54 G00 X0 Z0\n"));
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 1, 1e-9);
  EXPECT_NEAR(m.Z(), 100, 1e-9);
}

}  // namespace
}  // namespace vmt::control::channel
