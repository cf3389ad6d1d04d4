#pragma once
// The NC's message list as the operator reads it: the error that stopped the program (its number
// and text, channel_messages.hpp) and the message the PLC writes to the NC with the standard
// functions MSG_WR / MSG_WR_N (fast-measurement 6.3 and 7.2: the PLC program reports to the NC
// what it monitors, a probe displaced, a clutch that did not switch).

#include <cstdint>
#include <string>
#include <vector>

namespace vmt::control::channel {

/// What the PLC writes with MSG_WR (number, 0 = none) and MSG_WR_N (the number shown in place
/// of '@' in the message text). The PLC holds it as a level: it stands until the PLC writes 0.
struct PlcMessage {
  int number = 0;
  int64_t parameter = 0;
  bool operator==(const PlcMessage&) const = default;
};

/// One line of the message list.
struct OperatorMessage {
  enum class Source : uint8_t { kNc, kPlc };
  Source source = Source::kNc;
  int number = 0;
  int64_t parameter = 0;  ///< MSG_WR_N of a PLC message
  std::string text;       ///< the NC's text; empty for a PLC message (the PLC program's own)
};

inline const char* ToString(OperatorMessage::Source s) {
  return s == OperatorMessage::Source::kNc ? "nc" : "plc";
}

}  // namespace vmt::control::channel
