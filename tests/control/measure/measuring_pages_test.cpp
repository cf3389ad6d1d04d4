#include "control/measure/measuring_pages.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace vmt::control::measure {
namespace {

using ::testing::HasSubstr;

// The manual's tables (3.1): element count and data type of every element.
TEST(MeasuringPages, ElementsAndTypesAreTheManuals) {
  using enum DataType;
  struct Expected {
    Page page;
    const char* name;
    std::vector<DataType> types;
  };
  const std::vector<Expected> pages = {
      {Page::kBasisMessPage,
       "BASISMESSPAGE",
       {kInt, kInt, kInt, kInt, kInt, kBool, kBool, kBool, kBool, kBool}},
      {Page::kZwischenspeicherPage, "ZWISCHENSPEICHERPAGE",
       [] {
         std::vector<DataType> t = {kBool, kBool, kInt, kInt, kInt, kInt, kInt, kInt, kInt};
         t.insert(t.end(), 17, kReal);  // @100..@112, axes 1..3, F value
         return t;
       }()},
      {Page::kTastwerkzeugPage,
       "TASTWERKZEUGPAGE",
       {kDint, kBool, kBool, kReal, kReal, kReal, kReal, kReal}},
      {Page::kEichwertePage, "EICHWERTEPAGE", std::vector<DataType>(12, kReal)},
      {Page::kPointPage, "POINTPAGE", {kReal, kReal, kReal}},
      {Page::kErgebnisPage,
       "ERGEBNISPAGE",
       {kReal, kReal, kReal, kReal, kReal, kReal, kSint, kReal, kReal, kReal, kSint, kReal, kReal,
        kBool}},
  };
  for (const Expected& e : pages) {
    EXPECT_STREQ(PageName(e.page), e.name);
    ASSERT_EQ(ElementCount(e.page), static_cast<int>(e.types.size())) << e.name;
    for (size_t i = 0; i < e.types.size(); ++i) {
      const int element = static_cast<int>(i + 1);
      ASSERT_TRUE(ElementType(e.page, element)) << e.name << " " << element;
      EXPECT_EQ(*ElementType(e.page, element), e.types[i]) << e.name << " " << element;
      EXPECT_STRNE(ElementDesignation(e.page, element), "") << e.name << " " << element;
    }
    EXPECT_FALSE(ElementType(e.page, 0));
    EXPECT_FALSE(ElementType(e.page, ElementCount(e.page) + 1));
    EXPECT_STREQ(ElementDesignation(e.page, ElementCount(e.page) + 1), "");
  }
  EXPECT_STREQ(ElementDesignation(Page::kZwischenspeicherPage, 9), "G(13)");
  EXPECT_STREQ(ElementDesignation(Page::kZwischenspeicherPage, 22), "@112");
  EXPECT_STREQ(ElementDesignation(Page::kErgebnisPage, 13), "Correction value");
  EXPECT_STREQ(ElementDesignation(Page::kBasisMessPage, 7), "Pushbutton_contact");
}

// 7.1: page 90 and the user pages 101..105 by default; LV2 20 for points and results.
TEST(MeasuringPages, DefaultInstallation) {
  const MeasuringPages pages;
  EXPECT_EQ(pages.NumberOf(Page::kBasisMessPage), 90);
  EXPECT_EQ(pages.PageOf(90), Page::kBasisMessPage);
  EXPECT_EQ(pages.PageOf(101), Page::kZwischenspeicherPage);
  EXPECT_EQ(pages.PageOf(102), Page::kTastwerkzeugPage);
  EXPECT_EQ(pages.PageOf(103), Page::kEichwertePage);
  EXPECT_EQ(pages.PageOf(104), Page::kPointPage);
  EXPECT_EQ(pages.PageOf(105), Page::kErgebnisPage);
  EXPECT_FALSE(pages.PageOf(106));
  // BASISMESSPAGE elements 1..5 point to the other pages.
  for (int e = 1; e <= 5; ++e)
    EXPECT_EQ(ReadMtd(pages, {90, 0, {}, double(e)}, 0).value, 100 + e) << e;
  EXPECT_NE(pages.Point(0, 20), nullptr);
  EXPECT_EQ(pages.Point(0, 21), nullptr);  // LV2 = 20 at installation
  EXPECT_NE(pages.Result(0, 20), nullptr);
  EXPECT_EQ(pages.Result(0, 21), nullptr);
  EXPECT_EQ(pages.Point(0, 0), nullptr);
  EXPECT_EQ(pages.Point(1, 1), nullptr);  // one process
}

// 3.1 POINTPAGE: LV2 may be raised to 50, not beyond: the 51st point is refused.
TEST(MeasuringPages, FiftyPointsAtMost) {
  MeasuringPagesConfig c;
  c.points = 50;
  c.results = 50;
  MeasuringPages pages(c);
  EXPECT_NE(pages.Point(0, 50), nullptr);
  EXPECT_EQ(pages.Point(0, 51), nullptr);
  EXPECT_NE(pages.Result(0, 50), nullptr);
  EXPECT_EQ(pages.Result(0, 51), nullptr);
  EXPECT_EQ(WriteMtd(pages, {104, {}, 50, 2}, 0, 1.5), "");
  EXPECT_EQ(ReadMtd(pages, {104, {}, 50, 2}, 0).value, 1.5);
  EXPECT_THAT(ReadMtd(pages, {104, {}, 51, 2}, 0).error,
              HasSubstr("LV2 51 outside POINTPAGE's 1..50"));

  c.points = 51;
  EXPECT_THAT(Validate(c), HasSubstr("POINTPAGE LV2 51 outside 1..50"));
  EXPECT_THROW(MeasuringPages{c}, std::invalid_argument);
  c.points = 20;
  c.results = 51;
  EXPECT_THAT(Validate(c), HasSubstr("ERGEBNISPAGE LV2 51 outside 1..50"));
  c.results = 0;
  EXPECT_THAT(Validate(c), HasSubstr("ERGEBNISPAGE LV2 0 outside 1..50"));
}

// PROBE's record: the 21st point of the default installation and the 51st of the largest are
// refused; nothing is written then.
TEST(MeasuringPages, RecordTestPoint) {
  MeasuringPages pages;
  // PROBE(2,1,125,-10,,X,-2,...) under G16: the diameter 125 is the radius 62.5.
  ASSERT_EQ(RecordTestPoint(pages, 0, 2, 'X', 62.5, 62.52), "");
  const PointPage& p = *pages.Point(0, 2);
  EXPECT_EQ(p.value.command, 62.5);
  EXPECT_EQ(p.value.actual, 62.52);
  EXPECT_NEAR(p.value.deviation, 0.02, 1e-12);  // 62.52 - 62.5
  EXPECT_EQ(p.measuring_axis, 'X');
  EXPECT_THAT(RecordTestPoint(pages, 0, 21, 'X', 1, 1),
              HasSubstr("point number 21 outside POINTPAGE's 1..20 of process 0"));
  EXPECT_THAT(RecordTestPoint(pages, 0, 0, 'X', 1, 1), HasSubstr("point number 0 outside"));
  EXPECT_THAT(RecordTestPoint(pages, 1, 1, 'X', 1, 1), HasSubstr("of process 1"));
  EXPECT_THAT(RecordTestPoint(pages, 0, 1, 'U', 1, 1),
              HasSubstr("measuring axis U is not X, Y or Z"));
  EXPECT_THAT(RecordTestPoint(pages, 0, 1, 'Z', 1, std::numeric_limits<double>::quiet_NaN()),
              HasSubstr("not a number"));
  EXPECT_EQ(pages.Point(0, 1)->measuring_axis, 0);

  MeasuringPagesConfig c;
  c.points = 50;
  MeasuringPages fifty(c);
  EXPECT_EQ(RecordTestPoint(fifty, 0, 50, 'Z', -10, -10.001), "");
  EXPECT_THAT(RecordTestPoint(fifty, 0, 51, 'Z', -10, -10.001),
              HasSubstr("point number 51 outside POINTPAGE's 1..50"));
}

TEST(MeasuringPages, ConfigurationErrors) {
  MeasuringPagesConfig c;
  EXPECT_EQ(Validate(c), "");
  c.result_page = 101;
  EXPECT_THAT(Validate(c), HasSubstr("page number 101 used twice"));
  c.result_page = 90;  // Indramat's range, BASISMESSPAGE's own number
  EXPECT_THAT(Validate(c), HasSubstr("page number 90 is not a user page"));
  c.result_page = 40000;
  EXPECT_THAT(Validate(c), HasSubstr("not a user page"));
  c = {};
  c.processes = 0;
  EXPECT_THAT(Validate(c), HasSubstr("processes 0"));
  // Other numbers are followed by MTD.
  c = {};
  c.result_page = 205;
  MeasuringPages pages(c);
  EXPECT_EQ(pages.PageOf(205), Page::kErgebnisPage);
  EXPECT_FALSE(pages.PageOf(105));
  EXPECT_EQ(ReadMtd(pages, {90, {}, {}, 5}, 0).value, 205);
}

// 5.6: MTD(105,,1,13), the correction value of compare 1 in the current process.
TEST(MeasuringPages, MtdReadsAndWritesEveryPage) {
  MeasuringPagesConfig c;
  c.processes = 2;
  MeasuringPages pages(c);
  pages.Result(1, 1)->correction_value = 0.0123;
  EXPECT_EQ(ReadMtd(pages, {105, {}, 1, 13}, 1).value, 0.0123);  // LV1 omitted: process 1
  EXPECT_EQ(ReadMtd(pages, {105, 1, 1, 13}, 0).value, 0.0123);
  EXPECT_EQ(ReadMtd(pages, {105, 0, 1, 13}, 1).value, 0);  // process 0 is the master, not omitted

  // Each page, one element of each data type, written and read back into the struct.
  EXPECT_EQ(WriteMtd(pages, {90, {}, {}, 6}, 0, 1), "");
  EXPECT_TRUE(pages.basis[0].PIN_DDS);
  EXPECT_EQ(WriteMtd(pages, {101, {}, {}, 4}, 0, 90), "");  // G(2) = 90
  EXPECT_EQ(pages.buffer[0].g_group[1], 90);
  EXPECT_EQ(WriteMtd(pages, {101, {}, {}, 22}, 0, -7.25), "");  // @112
  EXPECT_EQ(pages.buffer[0].variable[12], -7.25);
  EXPECT_EQ(WriteMtd(pages, {101, {}, {}, 26}, 0, 100), "");  // F value
  EXPECT_EQ(pages.buffer[0].F_value, 100);
  EXPECT_EQ(WriteMtd(pages, {102, 3, {}, 1}, 0, 25), "");  // stylus 3 is T25
  EXPECT_EQ(pages.stylus[2].tool_number, 25);
  EXPECT_EQ(WriteMtd(pages, {102, 3, {}, 8}, 0, 3), "");  // sphere 5 radius
  EXPECT_EQ(pages.stylus[2].sphere_radius[4], 3);
  EXPECT_EQ(WriteMtd(pages, {103, 4, 5, 12}, 0, 250), "");  // feed - axis 3, stylus 4 sphere 5
  EXPECT_EQ(pages.calibration[3][4].measuring_feed[5], 250);
  EXPECT_EQ(WriteMtd(pages, {103, 1, 1, 2}, 0, 0.004), "");  // direction - axis 1
  EXPECT_EQ(pages.calibration[0][0].measuring_direction[1], 0.004);
  EXPECT_EQ(WriteMtd(pages, {104, {}, 7, 3}, 0, -0.02), "");  // deviation of point 7
  EXPECT_EQ(pages.Point(0, 7)->value.deviation, -0.02);
  EXPECT_EQ(WriteMtd(pages, {105, {}, 3, 7}, 0, 4), "");  // comparison strategy
  EXPECT_EQ(pages.Result(0, 3)->comparison_strategy, 4);
  EXPECT_EQ(WriteMtd(pages, {105, {}, 3, 14}, 0, 1), "");
  EXPECT_TRUE(pages.Result(0, 3)->correction_strategy);

  // What was written reads back the same through MTD.
  EXPECT_EQ(ReadMtd(pages, {90, {}, {}, 6}, 0).value, 1);
  EXPECT_EQ(ReadMtd(pages, {101, {}, {}, 22}, 0).value, -7.25);
  EXPECT_EQ(ReadMtd(pages, {102, 3, {}, 1}, 0).value, 25);
  EXPECT_EQ(ReadMtd(pages, {103, 4, 5, 12}, 0).value, 250);
  EXPECT_EQ(ReadMtd(pages, {104, {}, 7, 3}, 0).value, -0.02);
  EXPECT_EQ(ReadMtd(pages, {105, {}, 3, 7}, 0).value, 4);
  // Another process's pages are untouched.
  EXPECT_FALSE(pages.basis[1].PIN_DDS);
  EXPECT_EQ(pages.Point(1, 7)->value.deviation, 0);
}

TEST(MeasuringPages, MtdAddressErrors) {
  MeasuringPages pages;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    MtdAddress address;
    const char* error;
  };
  const std::vector<Case> cases = {
      {{106, {}, 1, 13}, "MTD(106,,1,13): page 106 is not a measuring page (90, 101, 102"},
      {{105.5, {}, 1, 13}, "page 105.5 is not a measuring page"},
      {{nan, {}, 1, 13}, "page nan is not a measuring page"},
      {{105, {}, 1, 15}, "MTD(105,,1,15): element 15 outside ERGEBNISPAGE's 1..14"},
      {{105, {}, 1, 0}, "element 0 outside ERGEBNISPAGE's 1..14"},
      {{105, {}, 1, 1.5}, "element 1.5 outside"},
      {{105, {}, 21, 13}, "LV2 21 outside ERGEBNISPAGE's 1..20"},
      {{105, {}, 0, 13}, "LV2 0 outside ERGEBNISPAGE's 1..20"},
      {{105, {}, inf, 13}, "LV2 inf outside"},
      {{105, {}, {}, 13}, "ERGEBNISPAGE needs LV2 (1..20)"},
      {{105, 1, 1, 13}, "LV1 1 is not a process of ERGEBNISPAGE (0..0)"},
      {{105, -1, 1, 13}, "LV1 -1 is not a process"},
      {{90, {}, 1, 6}, "BASISMESSPAGE has no LV2"},
      {{101, {}, {}, 27}, "element 27 outside ZWISCHENSPEICHERPAGE's 1..26"},
      {{102, {}, {}, 1}, "TASTWERKZEUGPAGE needs LV1, the stylus 1..4"},
      {{102, 5, {}, 1}, "LV1 5 is not a stylus of TASTWERKZEUGPAGE (1..4)"},
      {{102, 0, {}, 1}, "LV1 0 is not a stylus"},
      {{102, 1, 1, 1}, "TASTWERKZEUGPAGE has no LV2"},
      {{103, 1, 6, 1}, "LV2 6 outside EICHWERTEPAGE's 1..5"},
      {{103, 1, {}, 1}, "EICHWERTEPAGE needs LV2 (1..5)"},
      {{103, 1, 1, 13}, "element 13 outside EICHWERTEPAGE's 1..12"},
      {{104, {}, 1, 4}, "element 4 outside POINTPAGE's 1..3"},
  };
  for (const Case& c : cases) {
    const MtdRead read = ReadMtd(pages, c.address, 0);
    EXPECT_THAT(read.error, HasSubstr(c.error));
    EXPECT_EQ(read.value, 0);
    EXPECT_THAT(WriteMtd(pages, c.address, 0, 1), HasSubstr(c.error));
  }
  // The current process itself must exist where LV1 is omitted.
  EXPECT_THAT(ReadMtd(pages, {105, {}, 1, 13}, 3).error,
              HasSubstr("LV1 (current process 3) is not a process"));
}

TEST(MeasuringPages, MtdWriteValueErrors) {
  MeasuringPages pages;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // BOOL: 0 or 1.
  EXPECT_THAT(WriteMtd(pages, {90, {}, {}, 7}, 0, 2),
              HasSubstr("element 7 (Pushbutton_contact) of BASISMESSPAGE: BOOL takes 0 or 1, "
                        "not 2"));
  EXPECT_THAT(WriteMtd(pages, {105, {}, 1, 14}, 0, 0.5), HasSubstr("BOOL takes 0 or 1"));
  // SINT -128..127, INT -32768..32767, DINT, whole numbers.
  EXPECT_THAT(WriteMtd(pages, {105, {}, 1, 11}, 0, 200),
              HasSubstr("SINT takes a whole number -128..127, not 200"));
  EXPECT_EQ(WriteMtd(pages, {105, {}, 1, 11}, 0, -128), "");
  EXPECT_THAT(WriteMtd(pages, {101, {}, {}, 3}, 0, 1.5),
              HasSubstr("INT takes a whole number -32768..32767, not 1.5"));
  EXPECT_THAT(WriteMtd(pages, {101, {}, {}, 3}, 0, 40000), HasSubstr("INT takes"));
  EXPECT_THAT(WriteMtd(pages, {102, 1, {}, 1}, 0, 3e9), HasSubstr("DINT takes"));
  EXPECT_EQ(WriteMtd(pages, {102, 1, {}, 1}, 0, 2e9), "");
  // REAL: any finite number.
  EXPECT_THAT(WriteMtd(pages, {104, {}, 1, 1}, 0, nan), HasSubstr("the value nan is not a number"));
  EXPECT_EQ(pages.Point(0, 1)->value.command, 0);  // nothing written on an error
  // 3.1: page numbers are entered before the download, not by the program.
  EXPECT_THAT(WriteMtd(pages, {90, {}, {}, 5}, 0, 106),
              HasSubstr("element 5 (Result page) of BASISMESSPAGE is set at installation"));
  EXPECT_EQ(pages.PageOf(105), Page::kErgebnisPage);
  EXPECT_EQ(pages.basis[0].Pushbutton_contact, false);
  EXPECT_EQ(pages.Result(0, 1)->correction_strategy, false);
}

// Whatever the NC program computes, MTD answers with a value or an error.
TEST(MeasuringPages, MtdNeverCrashesOnAnyAddress) {
  MeasuringPages pages;
  const double values[] = {-1e300, -32769,
                           -1,     0,
                           0.5,    1,
                           2,      3,
                           4,      5,
                           6,      13,
                           14,     20,
                           21,     50,
                           51,     90,
                           101,    103,
                           105,    106,
                           1e9,    2e9,
                           1e300,  std::numeric_limits<double>::quiet_NaN()};
  int ok = 0, refused = 0;
  for (double page : values)
    for (double lv1 : {-1.0, 0.0, 1.0, 4.0, 5.0, 0.5})
      for (double lv2 : {0.0, 1.0, 5.0, 20.0, 21.0})
        for (double element : values) {
          for (std::optional<double> l1 : {std::optional<double>(), std::optional<double>(lv1)})
            for (std::optional<double> l2 : {std::optional<double>(), std::optional<double>(lv2)}) {
              const MtdAddress a{page, l1, l2, element};
              const MtdRead read = ReadMtd(pages, a, 0);
              (read.error.empty() ? ok : refused)++;
              const std::string write = WriteMtd(pages, a, 0, 0);
              if (read.error.empty()) {
                // Page numbers refuse writing; every other readable element takes a 0.
                const bool page_number = page == 90 && element >= 1 && element <= 5;
                EXPECT_EQ(write.empty(), !page_number) << write;
              } else {
                EXPECT_EQ(write, read.error);
              }
            }
        }
  EXPECT_GT(ok, 100);
  EXPECT_GT(refused, ok);
}

}  // namespace
}  // namespace vmt::control::measure
