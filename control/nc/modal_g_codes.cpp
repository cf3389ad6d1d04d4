#include "control/nc/modal_g_codes.hpp"

#include <charconv>

namespace vmt::control::nc {

bool SetModalG(int g, ModalState& m) {
  switch (g) {
    case 5:
    case 6:
      m.low_lag = g == 6;
      return true;
    case 15:
    case 16:
      m.diameter = g == 16;
      return true;
    case 17:
    case 18:
    case 19:
      m.plane = static_cast<Plane>(g);
      return true;
    case 30:
      m.transformation = Transformation::kOff;
      return true;
    case 40:
    case 41:
    case 42:
      m.compensation = static_cast<Compensation>(g);
      return true;
    case 47:
    case 48:
    case 49:
      m.tool_length = static_cast<ToolLength>(g);
      return true;
    case 53:
    case 54:
    case 55:
    case 56:
    case 57:
    case 58:
    case 59:
      m.zero_offset = g;
      return true;
    case 90:
    case 91:
      m.incremental = g == 91;
      return true;
    case 94:
    case 95:
      m.feed_per_revolution = g == 95;
      return true;
    default:
      return false;
  }
}

std::string ApplyInitialWord(std::string_view word, ModalState& m) {
  constexpr const char* kExpected =
      "expected a modal G code (G53..G59, G47..G49, G15/G16, G90/G91, G94/G95, G05/G06, "
      "G17..G19, G30, G40), Tn or Dn";
  if (word.size() < 2) return kExpected;
  const char letter = word[0];
  int n = 0;
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(word.data() + 1, end, n);
  if (ec == std::errc::result_out_of_range) return std::string(word) + ": the number is too large";
  if (ec != std::errc() || ptr != end || n < 0) return kExpected;
  switch (letter) {
    case 'G':
      if (n == 41 || n == 42)
        return std::string(word) + ": tool radius compensation starts with a move in a program";
      if (!SetModalG(n, m)) return kExpected;
      return "";
    case 'T':
      m.tool = n;
      return "";
    case 'D':
      m.correction = n;
      return "";
    default:
      return kExpected;
  }
}

std::vector<int> ActiveGCodes(const ModalState& m) {
  std::vector<int> g;
  const int motion = m.motion == Motion::kRapid          ? 0
                     : m.motion == Motion::kLinear       ? 1
                     : m.motion == Motion::kArcCw        ? 2
                     : m.motion == Motion::kArcCcw       ? 3
                     : m.motion == Motion::kThread       ? 33
                     : m.motion == Motion::kTapping      ? 63
                     : m.motion == Motion::kRigidTapping ? 64
                                                         : -1;
  if (motion >= 0) g.push_back(motion);
  g.push_back(GCode(m.plane));
  g.push_back(GCode(m.compensation));
  g.push_back(GCode(m.tool_length));
  g.push_back(m.zero_offset);
  g.push_back(m.incremental ? 91 : 90);
  g.push_back(m.feed_per_revolution ? 95 : 94);
  if (m.transformation != Transformation::kOff) g.push_back(GCode(m.transformation));
  return g;
}

}  // namespace vmt::control::nc
