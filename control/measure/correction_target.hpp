#pragma once
// Where a CORRECTION's value goes (mtc200-fast-measurement.md 2.1 CORRECTION, 5.5, 5.6): into a
// tool's wear register by TLD or into a zero offset by OTD, as the manual's programs do it,
//   TLD(1,3,,1,11,) = TLD(1,3,,1,11,) + MTD(105,,1,13)
//   OTD(,,4,1) = OTD(,,4,1) + MTD(105,,1,13)
// i.e. the register's new content is its old content plus ERGEBNISPAGE element 13. This names
// the register for a measuring axis and computes the new content; the NC's TLD/OTD wiring that
// reads and writes the register is the channel's.

#include <optional>
#include <string>

#include "control/measure/measuring_pages.hpp"

namespace vmt::control::measure {

/// TLD data element of the wear register along measuring axis `axis`: 5.6 corrects the Z face
/// with wear L1 (element 11) and the X diameter with wear L2 (12); Y with L3 (13) is vmt's
/// continuation of the pattern. nullopt for other axes.
std::optional<int> WearElement(char axis);

/// OTD's table index of zero offset G`g` (54..59): the manual's example OTD(,,4,1) is "the shift
/// according to G54", so G54..G59 are tables 4..9. nullopt outside G54..G59.
std::optional<int> OtdTable(int g);

/// The register a correction is meant for.
struct CorrectionTarget {
  enum class Kind { kToolWear, kZeroOffset };
  Kind kind = Kind::kToolWear;
  int tool = 0;            ///< kToolWear: T number
  int edge = 1;            ///< kToolWear: cutting edge (D)
  int zero_offset_g = 54;  ///< kZeroOffset: G54..G59
};

/// The register to write and its new content, or why there is none.
struct CorrectionWrite {
  std::string error;  ///< "" when the fields below hold
  CorrectionTarget::Kind kind = CorrectionTarget::Kind::kToolWear;
  int tool = 0, edge = 1;
  int tld_element = 0;                   ///< kToolWear: 11 (wear L1), 12 (L2), 13 (L3)
  int zero_offset_g = 0, otd_table = 0;  ///< kZeroOffset
  char axis = 0;     ///< the measuring axis: the offset's axis, the wear's direction
  double value = 0;  ///< the register's new content, mm: old + correction value
};

/// The write that takes ERGEBNISPAGE entry `entry`'s correction value (element 13) into
/// `target`, whose register holds `old_value` (mm). The correction value is added as it is,
/// as in the manual's programs: a diameter comparison (strategies 3, 4) gives a diameter.
CorrectionWrite CorrectionFor(const CorrectionTarget& target, const ErgebnisPage& entry,
                              double old_value);

}  // namespace vmt::control::measure
