#include "control/measure/correction_target.hpp"

#include <cmath>

namespace vmt::control::measure {

std::optional<int> WearElement(char axis) {
  switch (axis) {
    case 'Z':
      return 11;
    case 'X':
      return 12;
    case 'Y':
      return 13;
  }
  return std::nullopt;
}

std::optional<int> OtdTable(int g) {
  if (g < 54 || g > 59) return std::nullopt;
  return g - 50;
}

CorrectionWrite CorrectionFor(const CorrectionTarget& target, const ErgebnisPage& entry,
                              double old_value) {
  CorrectionWrite w;
  w.kind = target.kind;
  w.axis = entry.measuring_axis;
  if (entry.measuring_axis == 0) {
    w.error = "the result has no COMPARE: no measuring axis to correct";
    return w;
  }
  if (!std::isfinite(old_value)) {
    w.error = "the register's old value is not a number";
    return w;
  }
  if (target.kind == CorrectionTarget::Kind::kToolWear) {
    const std::optional<int> element = WearElement(entry.measuring_axis);
    if (target.tool < 1) {
      w.error = "tool wear correction without a T number";
      return w;
    }
    if (!element) {
      w.error = std::string("no wear register along ") + entry.measuring_axis;
      return w;
    }
    w.tool = target.tool;
    w.edge = target.edge;
    w.tld_element = *element;
  } else {
    const std::optional<int> table = OtdTable(target.zero_offset_g);
    if (!table) {
      w.error = "zero offset G" + std::to_string(target.zero_offset_g) + " is not G54..G59";
      return w;
    }
    w.zero_offset_g = target.zero_offset_g;
    w.otd_table = *table;
  }
  w.value = old_value + entry.correction_value;
  return w;
}

}  // namespace vmt::control::measure
