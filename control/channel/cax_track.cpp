#include "control/channel/cax_track.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>

namespace vmt::control::channel {
namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

/// -180 < result <= 180.
double Wrap180(double deg) {
  double d = std::remainder(deg, 360.0);
  if (d <= -180) d += 360;
  return d;
}

// The options of #CAX TRACK ON that vmt runs (TwinCAT block search manual 4.2.2).
enum class CaxTrackOption : uint8_t { kNone, kAnglimit, kOffset };

CaxTrackOption CaxTrackOptionOf(std::string_view name) {
  if (name == "ANGLIMIT") return CaxTrackOption::kAnglimit;
  if (name == "OFFSET") return CaxTrackOption::kOffset;
  return CaxTrackOption::kNone;
}

double DegOf(double along, double across) {
  return std::atan2(across, along) * 180 / std::numbers::pi;
}

}  // namespace

std::optional<CaxTrackCommand> ParseCaxTrack(std::string_view original, std::string* error) {
  std::string upper(original);
  for (char& ch : upper) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  const std::string_view text = upper;
  std::string_view rest;
  for (std::string_view name : {"CAX TRACK", "CAXTRACK"})
    if (text.starts_with(name)) rest = Trim(text.substr(name.size()));
  if (rest.data() == nullptr) return std::nullopt;
  CaxTrackCommand c;
  auto fail = [&](const std::string& why) {
    if (error) *error = "#" + std::string(original) + ": " + why;
    return c;
  };
  if (rest.starts_with("ON")) {
    c.on = true;
    rest = Trim(rest.substr(2));
  } else if (rest.starts_with("OFF")) {
    rest = Trim(rest.substr(3));
  } else {
    return fail("ON or OFF expected");
  }
  if (rest.empty()) return c;
  if (rest.front() != '[' || rest.back() != ']') return fail("options go in brackets [...]");
  rest = rest.substr(1, rest.size() - 2);
  // Options as "NAME value" or "NAME=value", apart by commas or blanks.
  const auto separator = [](char ch) {
    return ch == ',' || std::isspace(static_cast<unsigned char>(ch));
  };
  size_t i = 0;
  while (true) {
    while (i < rest.size() && separator(rest[i])) ++i;
    if (i == rest.size()) break;
    const size_t name_at = i;
    while (i < rest.size() && std::isalpha(static_cast<unsigned char>(rest[i]))) ++i;
    const std::string_view name = rest.substr(name_at, i - name_at);
    const CaxTrackOption option = CaxTrackOptionOf(name);
    if (!c.on || option == CaxTrackOption::kNone)
      return fail("option " + std::string(name.empty() ? rest.substr(name_at) : name) +
                  " is not supported by vmt (docs/conformance.md: ANGLIMIT and OFFSET of #CAX "
                  "TRACK ON)");
    while (i < rest.size() && (rest[i] == '=' || std::isspace(static_cast<unsigned char>(rest[i]))))
      ++i;
    const size_t value_at = i;
    while (i < rest.size() && !separator(rest[i])) ++i;
    const std::string_view value = rest.substr(value_at, i - value_at);
    double v = 0;
    const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
    if (value.empty() || ec != std::errc{} || ptr != value.data() + value.size() ||
        !std::isfinite(v))
      return fail(std::string(name) + " needs a number of degrees");
    switch (option) {
      case CaxTrackOption::kAnglimit:
        if (v < 0 || v > 180) return fail("ANGLIMIT must lie in 0 .. 180 degrees");
        c.anglimit_deg = v;
        break;
      case CaxTrackOption::kOffset:
        c.offset_deg = v;
        break;
      case CaxTrackOption::kNone:
        break;
    }
  }
  return c;
}

CaxTrackStep TrackStep(const BlockMotion& motion, int p0, int p1, double c_deg,
                       const CaxTrackCommand& track) {
  CaxTrackStep step;
  step.start_deg = step.end_deg = c_deg;
  if (!motion.moves || p0 < 0 || p1 < 0) return step;
  const auto a0 = static_cast<size_t>(p0), a1 = static_cast<size_t>(p1);
  const std::vector<double> d0 = motion.Direction(0), d1 = motion.Direction(1);
  if (std::hypot(d0[a0], d0[a1]) < 1e-12 * std::max(1.0, motion.length)) return step;
  step.in_plane = true;
  const double tangent0 = DegOf(d0[a0], d0[a1]) + track.offset_deg;
  const double turn_to_start = Wrap180(tangent0 - c_deg);
  step.start_deg = c_deg + turn_to_start;
  step.align = std::abs(turn_to_start) > track.anglimit_deg + 1e-9;
  // Along the block the tangent turns by an arc's sweep (its sign as seen in the plane's
  // order of axes), not by the shorter way between its end directions: a half circle and more
  // turn C as far as the path turns.
  double turn = Wrap180(DegOf(d1[a0], d1[a1]) - DegOf(d0[a0], d0[a1]));
  const int arc0 = motion.arc_axes[0], arc1 = motion.arc_axes[1];
  if (arc0 == p0 && arc1 == p1) turn = motion.arc_sweep * 180 / std::numbers::pi;
  if (arc0 == p1 && arc1 == p0) turn = -motion.arc_sweep * 180 / std::numbers::pi;
  step.end_deg = step.start_deg + turn;
  return step;
}

}  // namespace vmt::control::channel
