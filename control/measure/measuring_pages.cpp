#include "control/measure/measuring_pages.hpp"

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "control/measure/nc_number.hpp"

namespace vmt::control::measure {
namespace {

// The manual's designations (3.1), element n at index n - 1.
constexpr std::array<const char*, 10> kBasisDesignations = {"Buffer page",
                                                            "Stylus page",
                                                            "Calibration value page",
                                                            "Point page",
                                                            "Result page",
                                                            "PIN DDS",
                                                            "Pushbutton_contact",
                                                            "Measuring axis 1 available",
                                                            "Measuring axis 2 available",
                                                            "Measuring axis 3 available"};
constexpr std::array<const char*, 26> kBufferDesignations = {"Calibration OFF (1) / ON (0)",
                                                             "free",
                                                             "G(1)",
                                                             "G(2)",
                                                             "G(3)",
                                                             "G(5)",
                                                             "G(6)",
                                                             "G(7)",
                                                             "G(13)",
                                                             "@100",
                                                             "@101",
                                                             "@102",
                                                             "@103",
                                                             "@104",
                                                             "@105",
                                                             "@106",
                                                             "@107",
                                                             "@108",
                                                             "@109",
                                                             "@110",
                                                             "@111",
                                                             "@112",
                                                             "Axis 1 position",
                                                             "Axis 2 position",
                                                             "Axis 3 position",
                                                             "F value"};
constexpr std::array<const char*, 8> kStylusDesignations = {
    "Tool number (T number)",    "NO (0) / NC (1)",           "PIN4 (0) / PIN5 (1)",
    "Measuring sphere radius 1", "Measuring sphere radius 2", "Measuring sphere radius 3",
    "Measuring sphere radius 4", "Measuring sphere radius 5"};
constexpr std::array<const char*, 12> kCalibrationDesignations = {
    "Meas. direction axis 1",   "Meas. direction - axis 1", "Meas. direction axis 2",
    "Meas. direction - axis 2", "Meas. direction axis 3",   "Meas. direction - axis 3",
    "Meas. feed axis 1",        "Meas. feed - axis 1",      "Meas. feed axis 2",
    "Meas. feed - axis 2",      "Meas. feed axis 3",        "Meas. feed - axis 3"};
constexpr std::array<const char*, 3> kPointDesignations = {
    "Test point (command value)", "Test point (actual value)", "Deviation"};
constexpr std::array<const char*, 14> kResultDesignations = {"Measured value 1 (command)",
                                                             "Measured value 1 (actual)",
                                                             "Measured value 1 (deviation)",
                                                             "Measured value 2 (command)",
                                                             "Measured value 2 (actual)",
                                                             "Measured value 2 (deviation)",
                                                             "Comparison strategy",
                                                             "Comparison value (command)",
                                                             "Comparison value (actual)",
                                                             "Comparison value (deviation)",
                                                             "Dimensional accuracy",
                                                             "Average value",
                                                             "Correction value",
                                                             "Correction strategy"};

template <class F>
bool VisitMeasured(auto& v, int k, F&& f) {
  if (k == 0) f(v.command);
  if (k == 1) f(v.actual);
  if (k == 2) f(v.deviation);
  return k >= 0 && k <= 2;
}

// Calls f with the field that is element `e` of page `p` (const or not); false if there is none.
template <class P, class F>
bool VisitElement(P& p, int e, F&& f) {
  using T = std::remove_const_t<P>;
  if constexpr (std::is_same_v<T, BasisMessPage>) {
    switch (e) {
      case 1:
        return f(p.buffer_page), true;
      case 2:
        return f(p.stylus_page), true;
      case 3:
        return f(p.calibration_value_page), true;
      case 4:
        return f(p.point_page), true;
      case 5:
        return f(p.result_page), true;
      case 6:
        return f(p.PIN_DDS), true;
      case 7:
        return f(p.Pushbutton_contact), true;
      case 8:
        return f(p.measuring_axis_1), true;
      case 9:
        return f(p.measuring_axis_2), true;
      case 10:
        return f(p.measuring_axis_3), true;
    }
  } else if constexpr (std::is_same_v<T, ZwischenspeicherPage>) {
    if (e == 1) return f(p.calibration_off), true;
    if (e == 2) return f(p.free), true;
    if (e >= 3 && e <= 9) return f(p.g_group[e - 3]), true;
    if (e >= 10 && e <= 22) return f(p.variable[e - 10]), true;
    if (e >= 23 && e <= 25) return f(p.axis_position[e - 23]), true;
    if (e == 26) return f(p.F_value), true;
  } else if constexpr (std::is_same_v<T, TastwerkzeugPage>) {
    if (e == 1) return f(p.tool_number), true;
    if (e == 2) return f(p.normally_closed), true;
    if (e == 3) return f(p.pin5), true;
    if (e >= 4 && e <= 8) return f(p.sphere_radius[e - 4]), true;
  } else if constexpr (std::is_same_v<T, EichwertePage>) {
    if (e >= 1 && e <= 6) return f(p.measuring_direction[e - 1]), true;
    if (e >= 7 && e <= 12) return f(p.measuring_feed[e - 7]), true;
  } else if constexpr (std::is_same_v<T, PointPage>) {
    return e >= 1 && VisitMeasured(p.value, e - 1, f);
  } else if constexpr (std::is_same_v<T, ErgebnisPage>) {
    if (e >= 1 && e <= 3) return VisitMeasured(p.measured_value_1, e - 1, f);
    if (e >= 4 && e <= 6) return VisitMeasured(p.measured_value_2, e - 4, f);
    if (e == 7) return f(p.comparison_strategy), true;
    if (e >= 8 && e <= 10) return VisitMeasured(p.comparison_value, e - 8, f);
    if (e == 11) return f(p.dimensional_accuracy), true;
    if (e == 12) return f(p.average_value), true;
    if (e == 13) return f(p.correction_value), true;
    if (e == 14) return f(p.correction_strategy), true;
  }
  return false;
}

template <class T>
constexpr DataType TypeOf() {
  if constexpr (std::is_same_v<T, bool>) return DataType::kBool;
  if constexpr (std::is_same_v<T, int8_t>) return DataType::kSint;
  if constexpr (std::is_same_v<T, int16_t>) return DataType::kInt;
  if constexpr (std::is_same_v<T, int32_t>) return DataType::kDint;
  if constexpr (std::is_same_v<T, double>) return DataType::kReal;
}

// Calls f with a default page of kind `page`.
template <class F>
auto WithDefaultPage(Page page, F&& f) {
  switch (page) {
    case Page::kBasisMessPage:
      return f(BasisMessPage{});
    case Page::kZwischenspeicherPage:
      return f(ZwischenspeicherPage{});
    case Page::kTastwerkzeugPage:
      return f(TastwerkzeugPage{});
    case Page::kEichwertePage:
      return f(EichwertePage{});
    case Page::kPointPage:
      return f(PointPage{});
    case Page::kErgebnisPage:
      break;
  }
  return f(ErgebnisPage{});
}

std::string AddressText(const MtdAddress& a) {
  return "MTD(" + NcNumber(a.page) + "," + NcArgument(a.lv1) + "," + NcArgument(a.lv2) + "," +
         NcNumber(a.element) + ")";
}

// The page, control variables and element an address names, or why it names none.
struct Location {
  Page page = Page::kBasisMessPage;
  int lv1 = 0;  // process, or stylus 1..4
  int lv2 = 0;  // sphere 1..5, point or compare 1..LV2; 0 where the page has no LV2
  int element = 0;
  std::string error;
};

bool HasProcessLv1(Page p) { return p != Page::kTastwerkzeugPage && p != Page::kEichwertePage; }

int Lv2Count(const MeasuringPagesConfig& c, Page p) {
  switch (p) {
    case Page::kEichwertePage:
      return kSpheres;
    case Page::kPointPage:
      return c.points;
    case Page::kErgebnisPage:
      return c.results;
    default:
      return 0;
  }
}

Location Locate(const MeasuringPages& pages, const MtdAddress& a, int current_process) {
  Location at;
  auto fail = [&](std::string why) {
    at.error = AddressText(a) + ": " + std::move(why);
    return at;
  };
  const std::optional<int> number = WholeNumber(a.page);
  const std::optional<Page> page = number ? pages.PageOf(*number) : std::nullopt;
  if (!page) {
    const MeasuringPagesConfig& c = pages.config;
    return fail("page " + NcNumber(a.page) + " is not a measuring page (" +
                std::to_string(kBasisMessPageNumber) + ", " + std::to_string(c.buffer_page) + ", " +
                std::to_string(c.stylus_page) + ", " + std::to_string(c.calibration_value_page) +
                ", " + std::to_string(c.point_page) + ", " + std::to_string(c.result_page) + ")");
  }
  at.page = *page;
  const std::string name = PageName(at.page);

  // LV1: the process (omitted: the current one), or the stylus, which must be given.
  const int processes = pages.config.processes;
  if (HasProcessLv1(at.page)) {
    const std::optional<int> p = a.lv1 ? WholeNumber(*a.lv1) : std::optional<int>(current_process);
    if (!p || *p < 0 || *p >= processes)
      return fail(
          "LV1 " +
          (a.lv1 ? NcNumber(*a.lv1) : "(current process " + NcNumber(current_process) + ")") +
          " is not a process of " + name + " (0.." + std::to_string(processes - 1) + ")");
    at.lv1 = *p;
  } else {
    if (!a.lv1) return fail(name + " needs LV1, the stylus 1.." + std::to_string(kStyluses));
    const std::optional<int> s = WholeNumber(*a.lv1);
    if (!s || *s < 1 || *s > kStyluses)
      return fail("LV1 " + NcNumber(*a.lv1) + " is not a stylus of " + name + " (1.." +
                  std::to_string(kStyluses) + ")");
    at.lv1 = *s;
  }

  // LV2: only where the page has it, and then it must be given.
  const int lv2_count = Lv2Count(pages.config, at.page);
  if (lv2_count == 0) {
    if (a.lv2) return fail(name + " has no LV2");
  } else {
    if (!a.lv2) return fail(name + " needs LV2 (1.." + std::to_string(lv2_count) + ")");
    const std::optional<int> n = WholeNumber(*a.lv2);
    if (!n || *n < 1 || *n > lv2_count)
      return fail("LV2 " + NcNumber(*a.lv2) + " outside " + name + "'s 1.." +
                  std::to_string(lv2_count));
    at.lv2 = *n;
  }

  const int count = ElementCount(at.page);
  const std::optional<int> e = WholeNumber(a.element);
  if (!e || *e < 1 || *e > count)
    return fail("element " + NcNumber(a.element) + " outside " + name + "'s 1.." +
                std::to_string(count));
  at.element = *e;
  return at;
}

// Calls f(field) with the element at `at` of `pages` (const or not).
template <class Pages, class F>
void AtElement(Pages& pages, const Location& at, F&& f) {
  const size_t l1 = static_cast<size_t>(at.lv1), l2 = static_cast<size_t>(at.lv2);
  switch (at.page) {
    case Page::kBasisMessPage:
      VisitElement(pages.basis[l1], at.element, f);
      break;
    case Page::kZwischenspeicherPage:
      VisitElement(pages.buffer[l1], at.element, f);
      break;
    case Page::kTastwerkzeugPage:
      VisitElement(pages.stylus[l1 - 1], at.element, f);
      break;
    case Page::kEichwertePage:
      VisitElement(pages.calibration[l1 - 1][l2 - 1], at.element, f);
      break;
    case Page::kPointPage:
      VisitElement(pages.points[l1][l2 - 1], at.element, f);
      break;
    case Page::kErgebnisPage:
      VisitElement(pages.results[l1][l2 - 1], at.element, f);
      break;
  }
}

// "" if `value` fits a field of type T, else why not.
template <class T>
std::string Fits(double value) {
  if (!std::isfinite(value)) return "the value " + NcNumber(value) + " is not a number";
  if constexpr (std::is_same_v<T, bool>) {
    if (value != 0 && value != 1) return "BOOL takes 0 or 1, not " + NcNumber(value);
  } else if constexpr (std::is_integral_v<T>) {
    constexpr double lo = std::numeric_limits<T>::min(), hi = std::numeric_limits<T>::max();
    if (value != std::trunc(value) || value < lo || value > hi)
      return std::string(DataTypeName(TypeOf<T>())) + " takes a whole number " + NcNumber(lo) +
             ".." + NcNumber(hi) + ", not " + NcNumber(value);
  }
  return "";
}

}  // namespace

const char* PageName(Page page) {
  switch (page) {
    case Page::kBasisMessPage:
      return "BASISMESSPAGE";
    case Page::kZwischenspeicherPage:
      return "ZWISCHENSPEICHERPAGE";
    case Page::kTastwerkzeugPage:
      return "TASTWERKZEUGPAGE";
    case Page::kEichwertePage:
      return "EICHWERTEPAGE";
    case Page::kPointPage:
      return "POINTPAGE";
    case Page::kErgebnisPage:
      break;
  }
  return "ERGEBNISPAGE";
}

const char* DataTypeName(DataType type) {
  switch (type) {
    case DataType::kBool:
      return "BOOL";
    case DataType::kSint:
      return "SINT";
    case DataType::kInt:
      return "INT";
    case DataType::kDint:
      return "DINT";
    case DataType::kReal:
      break;
  }
  return "REAL";
}

int ElementCount(Page page) {
  switch (page) {
    case Page::kBasisMessPage:
      return kBasisDesignations.size();
    case Page::kZwischenspeicherPage:
      return kBufferDesignations.size();
    case Page::kTastwerkzeugPage:
      return kStylusDesignations.size();
    case Page::kEichwertePage:
      return kCalibrationDesignations.size();
    case Page::kPointPage:
      return kPointDesignations.size();
    case Page::kErgebnisPage:
      break;
  }
  return kResultDesignations.size();
}

std::optional<DataType> ElementType(Page page, int element) {
  return WithDefaultPage(page, [&](const auto& p) {
    std::optional<DataType> type;
    VisitElement(p, element,
                 [&](const auto& field) { type = TypeOf<std::remove_cvref_t<decltype(field)>>(); });
    return type;
  });
}

const char* ElementDesignation(Page page, int element) {
  if (element < 1 || element > ElementCount(page)) return "";
  const size_t i = static_cast<size_t>(element - 1);
  switch (page) {
    case Page::kBasisMessPage:
      return kBasisDesignations[i];
    case Page::kZwischenspeicherPage:
      return kBufferDesignations[i];
    case Page::kTastwerkzeugPage:
      return kStylusDesignations[i];
    case Page::kEichwertePage:
      return kCalibrationDesignations[i];
    case Page::kPointPage:
      return kPointDesignations[i];
    case Page::kErgebnisPage:
      break;
  }
  return kResultDesignations[i];
}

std::string Validate(const MeasuringPagesConfig& c) {
  if (c.processes < 1 || c.processes > 100)
    return "processes " + std::to_string(c.processes) + " outside 1..100";
  // 3.1 POINTPAGE / ERGEBNISPAGE: LV2 is 20 at installation and at most 50.
  if (c.points < 1 || c.points > kMaxPoints)
    return "POINTPAGE LV2 " + std::to_string(c.points) + " outside 1.." +
           std::to_string(kMaxPoints);
  if (c.results < 1 || c.results > kMaxPoints)
    return "ERGEBNISPAGE LV2 " + std::to_string(c.results) + " outside 1.." +
           std::to_string(kMaxPoints);
  // 7.1: user pages; 1..99 are Indramat's (90 the BASISMESSPAGE).
  std::set<int> seen;
  for (int n :
       {c.buffer_page, c.stylus_page, c.calibration_value_page, c.point_page, c.result_page}) {
    if (n < 100 || n > std::numeric_limits<int16_t>::max())
      return "page number " + std::to_string(n) + " is not a user page (100..32767)";
    if (!seen.insert(n).second) return "page number " + std::to_string(n) + " used twice";
  }
  return "";
}

MeasuringPages::MeasuringPages(const MeasuringPagesConfig& c) : config(c) {
  if (std::string error = Validate(c); !error.empty()) throw std::invalid_argument(error);
  BasisMessPage numbers;
  numbers.buffer_page = static_cast<int16_t>(c.buffer_page);
  numbers.stylus_page = static_cast<int16_t>(c.stylus_page);
  numbers.calibration_value_page = static_cast<int16_t>(c.calibration_value_page);
  numbers.point_page = static_cast<int16_t>(c.point_page);
  numbers.result_page = static_cast<int16_t>(c.result_page);
  const size_t n = static_cast<size_t>(c.processes);
  basis.assign(n, numbers);
  buffer.assign(n, {});
  stylus = {};
  calibration = {};
  points.assign(n, std::vector<PointPage>(static_cast<size_t>(c.points)));
  results.assign(n, std::vector<ErgebnisPage>(static_cast<size_t>(c.results)));
}

PointPage* MeasuringPages::Point(int process, int n) {
  return const_cast<PointPage*>(std::as_const(*this).Point(process, n));
}
const PointPage* MeasuringPages::Point(int process, int n) const {
  if (process < 0 || process >= config.processes || n < 1 || n > config.points) return nullptr;
  return &points[static_cast<size_t>(process)][static_cast<size_t>(n - 1)];
}
ErgebnisPage* MeasuringPages::Result(int process, int n) {
  return const_cast<ErgebnisPage*>(std::as_const(*this).Result(process, n));
}
const ErgebnisPage* MeasuringPages::Result(int process, int n) const {
  if (process < 0 || process >= config.processes || n < 1 || n > config.results) return nullptr;
  return &results[static_cast<size_t>(process)][static_cast<size_t>(n - 1)];
}

std::optional<Page> MeasuringPages::PageOf(int number) const {
  for (Page p : kPages)
    if (NumberOf(p) == number) return p;
  return std::nullopt;
}

int MeasuringPages::NumberOf(Page page) const {
  switch (page) {
    case Page::kBasisMessPage:
      return kBasisMessPageNumber;
    case Page::kZwischenspeicherPage:
      return config.buffer_page;
    case Page::kTastwerkzeugPage:
      return config.stylus_page;
    case Page::kEichwertePage:
      return config.calibration_value_page;
    case Page::kPointPage:
      return config.point_page;
    case Page::kErgebnisPage:
      break;
  }
  return config.result_page;
}

std::string RecordTestPoint(MeasuringPages& pages, int process, double point_number,
                            char measuring_axis, double command_mm, double actual_mm) {
  const std::optional<int> n = WholeNumber(point_number);
  PointPage* point = n ? pages.Point(process, *n) : nullptr;
  if (!point)
    return "point number " + NcNumber(point_number) + " outside POINTPAGE's 1.." +
           std::to_string(pages.config.points) + " of process " + std::to_string(process);
  // 4.1: only the linear main axes X, Y and Z measure.
  if (measuring_axis != 'X' && measuring_axis != 'Y' && measuring_axis != 'Z')
    return "measuring axis " + std::string(1, measuring_axis) + " is not X, Y or Z";
  if (!std::isfinite(command_mm) || !std::isfinite(actual_mm))
    return "test point " + std::to_string(*n) + ": a value that is not a number";
  point->value = {command_mm, actual_mm, actual_mm - command_mm};
  point->measuring_axis = measuring_axis;
  return "";
}

MtdRead ReadMtd(const MeasuringPages& pages, const MtdAddress& address, int current_process) {
  const Location at = Locate(pages, address, current_process);
  if (!at.error.empty()) return {0, at.error};
  MtdRead read;
  AtElement(pages, at, [&](const auto& field) { read.value = static_cast<double>(field); });
  return read;
}

std::string WriteMtd(MeasuringPages& pages, const MtdAddress& address, int current_process,
                     double value) {
  const Location at = Locate(pages, address, current_process);
  if (!at.error.empty()) return at.error;
  // 3.1: the page numbers are entered before the program download; the program reads them.
  if (at.page == Page::kBasisMessPage && at.element <= 5)
    return AddressText(address) + ": element " + std::to_string(at.element) + " (" +
           ElementDesignation(at.page, at.element) +
           ") of BASISMESSPAGE is set at installation, not by the NC program";
  std::string error;
  AtElement(pages, at, [&](auto& field) {
    using T = std::remove_cvref_t<decltype(field)>;
    error = Fits<T>(value);
    if (error.empty()) field = static_cast<T>(value);
  });
  if (!error.empty())
    return AddressText(address) + ": element " + std::to_string(at.element) + " (" +
           ElementDesignation(at.page, at.element) + ") of " + PageName(at.page) + ": " + error;
  return "";
}

}  // namespace vmt::control::measure
