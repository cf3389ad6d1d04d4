#include "control/gateway/signal_types.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "common/demand.hpp"

namespace vmt::control::gateway {

const char* ToString(SignalType type) {
  switch (type) {
    case SignalType::kBool:
      return "BOOL";
    case SignalType::kInt:
      return "INT";
    case SignalType::kUint:
      return "UINT";
    case SignalType::kWord:
      return "WORD";
    case SignalType::kDint:
      return "DINT";
    case SignalType::kUdint:
      return "UDINT";
    case SignalType::kDword:
      return "DWORD";
    case SignalType::kReal:
      return "REAL";
    case SignalType::kLreal:
      return "LREAL";
    case SignalType::kString:
      return "STRING(83)";
  }
  return "?";
}

const char* ToString(Direction direction) {
  switch (direction) {
    case Direction::kPlcToNc:
      return "PLC->NC";
    case Direction::kNcToPlc:
      return "NC->PLC";
    case Direction::kShared:
      return "NC<->PLC";
    case Direction::kMachineToPlc:
      return "MACHINE->PLC";
    case Direction::kPlcToMachine:
      return "PLC->MACHINE";
  }
  return "?";
}

const char* ToString(Scope scope) {
  switch (scope) {
    case Scope::kProcess:
      return "process";
    case Scope::kAxis:
      return "axis";
    case Scope::kSpindle:
      return "spindle";
    case Scope::kChangeover:
      return "changeover";
    case Scope::kGlobal:
      return "global";
    case Scope::kIo:
      return "io";
  }
  return "?";
}

bool PlcWrites(Direction direction) {
  return direction == Direction::kPlcToNc || direction == Direction::kShared ||
         direction == Direction::kPlcToMachine;
}

int RegisterCount(SignalType type) {
  switch (type) {
    case SignalType::kBool:
    case SignalType::kInt:
    case SignalType::kUint:
    case SignalType::kWord:
      return 1;
    case SignalType::kDint:
    case SignalType::kUdint:
    case SignalType::kDword:
    case SignalType::kReal:
      return 2;
    case SignalType::kLreal:
      return 4;
    case SignalType::kString:
      return kStringBytes / 2;
  }
  return 0;
}

bool IsInteger(SignalType type) {
  switch (type) {
    case SignalType::kInt:
    case SignalType::kUint:
    case SignalType::kWord:
    case SignalType::kDint:
    case SignalType::kUdint:
    case SignalType::kDword:
      return true;
    default:
      return false;
  }
}

int64_t MinValue(SignalType type) {
  VMT_DEMAND(IsInteger(type), "gateway: %s is not an integer type", ToString(type));
  switch (type) {
    case SignalType::kInt:
      return -32768;
    case SignalType::kDint:
      return -2147483648LL;
    case SignalType::kUint:
    case SignalType::kWord:
    case SignalType::kUdint:
    case SignalType::kDword:
      return 0;
    default:
      return 0;  // not an integer type: refused above
  }
}

int64_t MaxValue(SignalType type) {
  VMT_DEMAND(IsInteger(type), "gateway: %s is not an integer type", ToString(type));
  switch (type) {
    case SignalType::kInt:
      return 32767;
    case SignalType::kUint:
    case SignalType::kWord:
      return 65535;
    case SignalType::kDint:
      return 2147483647LL;
    case SignalType::kUdint:
    case SignalType::kDword:
      return 4294967295LL;
    default:
      return 0;  // not an integer type: refused above
  }
}

std::string ValueError(SignalType type, double value) {
  if (!std::isfinite(value)) return "a signal value must be a finite number";
  if (type == SignalType::kString) return "a STRING signal holds text, not a number";
  if (type == SignalType::kBool)
    return value == 0 || value == 1 ? "" : "BOOL holds 0 or 1 (true or false)";
  if (!IsInteger(type)) {
    // REAL is binary32: a larger magnitude would become infinity on the gateway.
    if (type == SignalType::kReal && std::abs(value) > std::numeric_limits<float>::max())
      return "outside REAL's range";
    return "";
  }
  char text[160];
  if (value != std::floor(value)) {
    std::snprintf(text, sizeof text, "%.17g is not an integer: %s", value, ToString(type));
    return text;
  }
  const int64_t lo = MinValue(type);
  const int64_t hi = MaxValue(type);
  if (value < static_cast<double>(lo) || value > static_cast<double>(hi)) {
    std::snprintf(text, sizeof text, "%.17g is outside %s's range %lld..%lld", value,
                  ToString(type), static_cast<long long>(lo), static_cast<long long>(hi));
    return text;
  }
  return "";
}

}  // namespace vmt::control::gateway
