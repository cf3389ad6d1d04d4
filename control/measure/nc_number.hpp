#pragma once
// Numbers as the measuring instructions and MTD( ) receive them: reals from NC expressions, of
// which indices must be whole, and which error texts show as the program would write them.

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

namespace vmt::control::measure {

/// `v` as an NC program writes it: 13, -0.5, nan.
inline std::string NcNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", v);
  return text;
}

/// `v` as an index if it is a whole number of moderate size, else nullopt (NaN, 2.5, 1e300).
inline std::optional<int> WholeNumber(double v) {
  if (!std::isfinite(v) || v != std::trunc(v) || std::abs(v) > 1e9) return std::nullopt;
  return static_cast<int>(v);
}

/// An omitted argument prints empty: COMPARE(7,4,6,).
inline std::string NcArgument(const std::optional<double>& v) {
  return v ? NcNumber(*v) : std::string();
}

}  // namespace vmt::control::measure
