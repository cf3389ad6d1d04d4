#pragma once
// The six machine data pages of fast measurement (mtc200-fast-measurement.md 3.1) as plain
// structs with the manual's element numbers and data types, and the element access MTD() needs:
// MTD(page, LV1, LV2, element) read and written with an error text for any address or value the
// page cannot take (never a crash, whatever the NC program computes).
//
// Control variables: LV1 of BASISMESSPAGE, ZWISCHENSPEICHERPAGE, POINTPAGE and ERGEBNISPAGE is
// the process (0 = master process; omitted = the current process); LV1 of TASTWERKZEUGPAGE and
// EICHWERTEPAGE is the stylus 1..4, LV2 of EICHWERTEPAGE the measuring sphere 1..5; LV2 of
// POINTPAGE / ERGEBNISPAGE the point / compare number 1..20 by default, at most 50.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vmt::control::measure {

/// 3.1: the base measurement page is Indramat page 90, fixed by the system software.
inline constexpr int kBasisMessPageNumber = 90;
inline constexpr int kStyluses = 4;        ///< TASTWERKZEUGPAGE / EICHWERTEPAGE LV1: NO_CLASS [1-4]
inline constexpr int kSpheres = 5;         ///< EICHWERTEPAGE LV2: NO_CLASS [1-5]
inline constexpr int kDefaultPoints = 20;  ///< POINTPAGE / ERGEBNISPAGE LV2 at installation
inline constexpr int kMaxPoints = 50;      ///< ... and the most it may be raised to

enum class Page : uint8_t {
  kBasisMessPage,
  kZwischenspeicherPage,
  kTastwerkzeugPage,
  kEichwertePage,
  kPointPage,
  kErgebnisPage,
};
inline constexpr std::array kPages = {Page::kBasisMessPage,    Page::kZwischenspeicherPage,
                                      Page::kTastwerkzeugPage, Page::kEichwertePage,
                                      Page::kPointPage,        Page::kErgebnisPage};

/// The manual's data types of page elements.
enum class DataType : uint8_t { kBool, kSint, kInt, kDint, kReal };

/// "BASISMESSPAGE", ... as the manual spells the page.
const char* PageName(Page page);
/// "BOOL", "SINT", "INT", "DINT", "REAL".
const char* DataTypeName(DataType type);
/// Number of data elements of a page (BASISMESSPAGE 10, ..., ERGEBNISPAGE 14).
int ElementCount(Page page);
/// Type and the manual's designation of element `element` (1..ElementCount); nullopt / "" if
/// there is no such element.
std::optional<DataType> ElementType(Page page, int element);
const char* ElementDesignation(Page page, int element);

/// BASISMESSPAGE (3.1). Elements 1..5 are the numbers of the other pages, entered before the
/// program download; 6..10 are set by the NC program (SETTING and the stylus page) for the PLC.
struct BasisMessPage {
  int16_t buffer_page = 101;             ///< 1 INT: ZWISCHENSPEICHERPAGE
  int16_t stylus_page = 102;             ///< 2 INT: TASTWERKZEUGPAGE
  int16_t calibration_value_page = 103;  ///< 3 INT: EICHWERTEPAGE
  int16_t point_page = 104;              ///< 4 INT: POINTPAGE
  int16_t result_page = 105;             ///< 5 INT: ERGEBNISPAGE
  bool PIN_DDS = false;                  ///< 6 BOOL: probe at drive pin 4 (0) or pin 5 (1)
  bool Pushbutton_contact = false;       ///< 7 BOOL: normally open (0) / closed (1) contact
  bool measuring_axis_1 = false;         ///< 8 BOOL: measuring axis 1 available
  bool measuring_axis_2 = false;         ///< 9 BOOL
  bool measuring_axis_3 = false;         ///< 10 BOOL
};

/// ZWISCHENSPEICHERPAGE (3.1): what SAVE( ) keeps and RESTORE( ) writes back.
struct ZwischenspeicherPage {
  bool calibration_off = false;  ///< 1 BOOL: calibration points hidden (1) / shown (0)
  bool free = false;             ///< 2 BOOL
  /// 3..9 INT: the modal groups PROBE and MOVE save, G(1) G(2) G(3) G(5) G(6) G(7) G(13).
  std::array<int16_t, 7> g_group{};
  std::array<double, 13> variable{};      ///< 10..22 REAL: @100..@112
  std::array<double, 3> axis_position{};  ///< 23..25 REAL: axes 1..3 of SETTING, mm
  double F_value = 0;                     ///< 26 REAL
};
/// The modal groups of ZWISCHENSPEICHERPAGE elements 3..9, in that order.
inline constexpr std::array<int, 7> kSavedGGroups = {1, 2, 3, 5, 6, 7, 13};

/// TASTWERKZEUGPAGE (3.1): one stylus, entered by the user.
struct TastwerkzeugPage {
  int32_t tool_number = 0;                ///< 1 DINT: T number of the stylus in the tool list
  bool normally_closed = false;           ///< 2 BOOL: NO (0) / NC (1)
  bool pin5 = false;                      ///< 3 BOOL: PIN4 (0) / PIN5 (1)
  std::array<double, 5> sphere_radius{};  ///< 4..8 REAL: measuring sphere radius 1..5, mm
};

/// EICHWERTEPAGE (3.1): calibration values and measuring feeds of one sphere of one stylus, per
/// measuring direction in the order axis 1 +, axis 1 -, axis 2 +, axis 2 -, axis 3 +, axis 3 -.
struct EichwertePage {
  std::array<double, 6> measuring_direction{};  ///< 1..6 REAL: calibration value, mm
  std::array<double, 6> measuring_feed{};       ///< 7..12 REAL: mm/min
};

/// A command value, the measured actual value and actual - command (POINTPAGE 1..3; each
/// measured value of ERGEBNISPAGE). Positions along the measuring axis in mm, radius values
/// even under G16 (4.6 Actual values).
struct MeasuredValue {
  double command = 0;
  double actual = 0;
  double deviation = 0;
};

/// POINTPAGE (3.1): one test point.
struct PointPage {
  MeasuredValue value;  ///< 1..3 REAL: test point (command value), (actual value), deviation
  /// Not a page element: the measuring axis ('X', 'Y', 'Z') PROBE measured the point along, 0
  /// while the point has not been measured. COMPARE needs it (2.1: only points of the same
  /// measuring axis compare); the real control keeps it in its generated code.
  char measuring_axis = 0;
};

/// ERGEBNISPAGE (3.1): one COMPARE (elements 1..10) and its CORRECTION (11..14).
struct ErgebnisPage {
  MeasuredValue measured_value_1;    ///< 1..3 REAL
  MeasuredValue measured_value_2;    ///< 4..6 REAL
  int8_t comparison_strategy = 0;    ///< 7 SINT: 0..4 (compare.hpp)
  MeasuredValue comparison_value;    ///< 8..10 REAL: nominal, actual dimension, deviation
  int8_t dimensional_accuracy = 0;   ///< 11 SINT: 0..3 (correction.hpp)
  double average_value = 0;          ///< 12 REAL: the averaging's old average value
  double correction_value = 0;       ///< 13 REAL
  bool correction_strategy = false;  ///< 14 BOOL: averaging (0) / percentage correction (1)
  /// Not a page element: the measuring axis of the compared points, for the correction target.
  char measuring_axis = 0;
};

/// How the pages are installed (7.1): the number of processes (LV1 of the PROCESS pages), LV2
/// of POINTPAGE and ERGEBNISPAGE, and the user page numbers (101..105 by default).
struct MeasuringPagesConfig {
  int processes = 1;
  int points = kDefaultPoints;
  int results = kDefaultPoints;
  int buffer_page = 101;
  int stylus_page = 102;
  int calibration_value_page = 103;
  int point_page = 104;
  int result_page = 105;
};

/// "" if the configuration can be installed, else what is wrong with it (points above 50, a page
/// number used twice or outside the user pages 100..32767, ...).
std::string Validate(const MeasuringPagesConfig& config);

/// An MTD( ) address as the NC program gives it: reals, since they are expressions; an omitted
/// control variable is nullopt (not 0: process 0 is the master process).
struct MtdAddress {
  double page = 0;
  std::optional<double> lv1;
  std::optional<double> lv2;
  double element = 0;
};

/// A value read by MTD( ), or why it could not be read.
struct MtdRead {
  double value = 0;
  std::string error;  ///< "" when read
};

/// The machine data pages of fast measurement of one control. Constant shape (installation),
/// changing contents.
struct MeasuringPages {
  /// Throws std::invalid_argument with Validate's text for a configuration that cannot be.
  explicit MeasuringPages(const MeasuringPagesConfig& config = {});

  MeasuringPagesConfig config;
  std::vector<BasisMessPage> basis;                                        ///< [process]
  std::vector<ZwischenspeicherPage> buffer;                                ///< [process]
  std::array<TastwerkzeugPage, kStyluses> stylus;                          ///< [LV1 - 1]
  std::array<std::array<EichwertePage, kSpheres>, kStyluses> calibration;  ///< [LV1-1][LV2-1]
  std::vector<std::vector<PointPage>> points;                              ///< [process][LV2 - 1]
  std::vector<std::vector<ErgebnisPage>> results;                          ///< [process][LV2 - 1]

  /// Test point `n` (1..config.points) of `process`; nullptr outside the page.
  PointPage* Point(int process, int n);
  const PointPage* Point(int process, int n) const;
  /// Compare `n` (1..config.results) of `process`; nullptr outside the page.
  ErgebnisPage* Result(int process, int n);
  const ErgebnisPage* Result(int process, int n) const;
  /// The page that has number `number` (90 or one of the configured user pages).
  std::optional<Page> PageOf(int number) const;
  /// The configured number of a page.
  int NumberOf(Page page) const;
};

/// What PROBE( ) leaves in POINTPAGE for test point A (2.1: 1..20, at most 50) of `process`:
/// command and actual value along `measuring_axis` ('X', 'Y', 'Z'; 4.1), radius values in mm
/// (4.6 Actual values), deviation = actual - command. "" when recorded, else why not; nothing
/// is written then.
std::string RecordTestPoint(MeasuringPages& pages, int process, double point_number,
                            char measuring_axis, double command_mm, double actual_mm);

/// MTD(page, LV1, LV2, element) read in `current_process` (used where LV1 of a PROCESS page is
/// omitted).
MtdRead ReadMtd(const MeasuringPages& pages, const MtdAddress& address, int current_process);
/// MTD(...) = value. "" when written, else why not: the address, a value the element's data type
/// cannot hold (BOOL 0/1, SINT/INT/DINT whole numbers in range, REAL finite), or BASISMESSPAGE
/// elements 1..5, which are set at installation, not by the program (3.1).
std::string WriteMtd(MeasuringPages& pages, const MtdAddress& address, int current_process,
                     double value);

}  // namespace vmt::control::measure
