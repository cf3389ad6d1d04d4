#pragma once
// The texts of the messages vmt's PLC programs write to the NC with MSG_WR / MSG_WR_N. On the
// MTC200 the texts belong to the PLC program (fast-measurement 7.2: each MSG_WR network carries
// its number and text, '@' standing for the MSG_WR_N value); vmt keeps them here, for the
// programs in control/plc/programs.

#include <cstdint>
#include <string>

namespace vmt::control::plc {

/// The text of PLC message `number` with '@' replaced by `parameter`; empty if no program of
/// vmt's writes that number.
inline std::string PlcMessageText(int number, int64_t parameter) {
  const char* text = "";
  switch (number) {
    // The measuring block's typical application (fast-measurement 7.2, networks 13-30).
    case 202:
      text = "probe 2 deflected already";
      break;
    case 203:
      text = "probe 1 deflected already";
      break;
    case 204:
      text = "NC program error, type 2";
      break;
    case 205:
      text = "NC program error, type 1";
      break;
    case 206:
    case 207:
    case 208:
      text = "error @ of the measuring function block";
      break;
    // The C-axis changeover program (c_axis_changeover.hpp, MSG_ROTERR / MSG_SPERR).
    case 220:
      text = "clutch not engaged in time: no rotary axis mode (Control-Reset)";
      break;
    case 221:
      text = "clutch not released in time: no spindle mode (Control-Reset)";
      break;
    default:
      break;
  }
  std::string s = text;
  if (const size_t at = s.find('@'); at != std::string::npos)
    s.replace(at, 1, std::to_string(parameter));
  return s;
}

}  // namespace vmt::control::plc
