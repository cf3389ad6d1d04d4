#include "control/gateway/signal_table.hpp"

#include <algorithm>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string_view>

namespace vmt::control::gateway {

const char* ToString(ModbusAddress::Area area) {
  switch (area) {
    case ModbusAddress::kCoil:
      return "coil";
    case ModbusAddress::kDiscreteInput:
      return "discrete_input";
    case ModbusAddress::kHoldingRegister:
      return "holding_register";
    case ModbusAddress::kInputRegister:
      return "input_register";
  }
  return "?";
}

std::string InstanceName(std::string_view pattern, int number) {
  const bool placeholder = pattern.size() >= 3 && (pattern[0] == 'P' || pattern[0] == 'A') &&
                           pattern.substr(1, 2) == "xx";
  if (!placeholder) return std::string(pattern);
  if (number < 0 || number > 99) {
    throw std::out_of_range("InstanceName: " + std::string(pattern) +
                            " needs a number 0..99, not " + std::to_string(number));
  }
  std::string name(pattern);
  name[1] = static_cast<char>('0' + number / 10);
  name[2] = static_cast<char>('0' + number % 10);
  return name;
}

namespace {

[[noreturn]] void Reject(const std::string& field, const std::string& why) {
  throw std::invalid_argument("GatewayLayout." + field + ": " + why);
}

std::vector<std::string> SplitAliases(std::string_view aliases, int number) {
  std::vector<std::string> out;
  while (!aliases.empty()) {
    const size_t end = aliases.find(';');
    out.push_back(InstanceName(aliases.substr(0, end), number));
    if (end == std::string_view::npos) break;
    aliases.remove_prefix(end + 1);
  }
  return out;
}

Signal FromFamily(const SignalFamily& family, int number, std::string instance_name) {
  Signal s;
  s.name = InstanceName(family.pattern, number);
  s.type = family.type;
  s.direction = family.direction;
  s.meaning = std::string(family.meaning);
  if (!family.unit.empty()) s.meaning += " [" + std::string(family.unit) + "]";
  s.source = std::string(family.source);
  s.modbus = {};
  s.pattern = std::string(family.pattern);
  s.scope = family.scope;
  s.instance = family.scope == Scope::kGlobal ? -1 : number;
  s.instance_name = std::move(instance_name);
  s.unit = std::string(family.unit);
  s.aliases = SplitAliases(family.aliases, number);
  s.preset = family.preset;
  s.not_evaluated = std::string(family.not_evaluated);
  return s;
}

Signal Plain(std::string name, SignalType type, Direction direction, std::string meaning,
             std::string source, std::string pattern, Scope scope, int instance) {
  Signal s;
  s.name = std::move(name);
  s.type = type;
  s.direction = direction;
  s.meaning = std::move(meaning);
  s.source = std::move(source);
  s.modbus = {};
  s.pattern = std::move(pattern);
  s.scope = scope;
  s.instance = instance;
  s.unit = {};
  s.preset = 0;
  return s;
}

bool AxisHas(Scope scope, const GatewayLayout::Axis& axis) {
  switch (scope) {
    case Scope::kAxis:
      return true;
    case Scope::kSpindle:
      return axis.spindle_capable;
    case Scope::kChangeover:
      return axis.spindle_capable || axis.rotary;
    default:
      return false;
  }
}

void CheckNumbers(const std::vector<int>& numbers, const std::string& field, int lo, int hi,
                  const char* rule) {
  std::set<int> seen;
  for (size_t i = 0; i < numbers.size(); ++i) {
    const std::string at = field + "[" + std::to_string(i) + "]";
    if (numbers[i] < lo || numbers[i] > hi) {
      Reject(at, std::to_string(numbers[i]) + " is out of range " + std::to_string(lo) + ".." +
                     std::to_string(hi) + " (" + rule + ")");
    }
    if (!seen.insert(numbers[i]).second) Reject(at, std::to_string(numbers[i]) + " is repeated");
  }
}

void CheckLayout(const GatewayLayout& layout) {
  CheckNumbers(layout.processes, "processes", 0, kMaxProcessNumber, "two-digit process number");
  std::vector<int> axis_numbers;
  std::set<std::string> axis_names;
  for (size_t i = 0; i < layout.axes.size(); ++i) {
    axis_numbers.push_back(layout.axes[i].number);
    const std::string& name = layout.axes[i].name;
    if (name.empty()) Reject("axes[" + std::to_string(i) + "].name", "empty axis name");
    if (!axis_names.insert(name).second) {
      Reject("axes[" + std::to_string(i) + "].name", "'" + name + "' is repeated");
    }
  }
  CheckNumbers(axis_numbers, "axes[].number", kMinAxisNumber, kMaxAxisNumber,
               "mtc200-fast-measurement.md 7.2: axis numbers run from 1 to 32");
  for (int q : layout.q_functions) {
    if (std::find(std::begin(kManualQFunctions), std::end(kManualQFunctions), q) !=
        std::end(kManualQFunctions)) {
      Reject("q_functions",
             std::string("Q") + std::to_string(q) + " is already in the manuals' table");
    }
  }
  CheckNumbers(layout.q_functions, "q_functions", 0, 9999, "four-digit Q function number");
  for (int e : layout.events) {
    if (std::find(std::begin(kManualEvents), std::end(kManualEvents), e) !=
        std::end(kManualEvents)) {
      Reject("events", "event " + std::to_string(e) + " is already in the manuals' table");
    }
  }
  CheckNumbers(layout.events, "events", 0, 999, "event number");
  for (size_t i = 0; i < layout.io.size(); ++i) {
    const std::string& name = layout.io[i].name;
    const bool printable = std::all_of(name.begin(), name.end(), [](unsigned char c) {
      return c > ' ' && c < 0x7f && c != ',' && c != '"';
    });
    if (name.empty() || !printable) {
      Reject("io[" + std::to_string(i) + "].name",
             "'" + name + "' must be non-empty printable ASCII without blanks, commas, quotes");
    }
  }
}

void AssignModbus(std::vector<Signal>& table) {
  int next[4] = {0, 0, 0, 0};
  for (Signal& s : table) {
    const bool bit = s.type == SignalType::kBool;
    const bool writes = PlcWrites(s.direction);
    const ModbusAddress::Area area =
        bit ? (writes ? ModbusAddress::kCoil : ModbusAddress::kDiscreteInput)
            : (writes ? ModbusAddress::kHoldingRegister : ModbusAddress::kInputRegister);
    const int count = RegisterCount(s.type);
    if (next[area] + count > 65536) {
      Reject("(whole layout)", std::string("Modbus ") + ToString(area) +
                                   " addresses exceed 65536 at signal " + s.name);
    }
    s.modbus = {area, next[area], count};
    next[area] += count;
  }
}

}  // namespace

std::vector<Signal> BuildSignalTable(const GatewayLayout& layout) {
  CheckLayout(layout);
  const auto families = SignalFamilies();
  std::vector<Signal> table;

  for (int p : layout.processes) {
    for (const SignalFamily& f : families) {
      if (f.scope == Scope::kProcess) table.push_back(FromFamily(f, p, {}));
    }
    const std::string prefix = InstanceName("Pxx", p);
    for (int q : layout.q_functions) {
      const std::string qn = "Q" + std::to_string(q);
      table.push_back(Plain(prefix + "." + qn, SignalType::kBool, Direction::kNcToPlc,
                            "Q function " + std::to_string(q) + " output (Q_FKT), machine-specific",
                            "machine model", "Pxx." + qn, Scope::kProcess, p));
      table.push_back(Plain(prefix + "." + qn + "_Q", SignalType::kBool, Direction::kPlcToNc,
                            "Acknowledgement of " + qn + " (Q_FKT_Q)", "machine model",
                            "Pxx." + qn + "_Q", Scope::kProcess, p));
    }
    for (int e : layout.events) {
      const std::string en = "EV" + std::to_string(e);
      table.push_back(Plain(prefix + "." + en, SignalType::kBool, Direction::kShared,
                            "Event " + std::to_string(e) + ", machine-specific", "machine model",
                            "Pxx." + en, Scope::kProcess, p));
    }
  }
  for (const GatewayLayout::Axis& axis : layout.axes) {
    for (const SignalFamily& f : families) {
      if (AxisHas(f.scope, axis)) table.push_back(FromFamily(f, axis.number, axis.name));
    }
  }
  for (const SignalFamily& f : families) {
    if (f.scope == Scope::kGlobal) table.push_back(FromFamily(f, -1, {}));
  }
  for (const GatewayLayout::Io& io : layout.io) {
    table.push_back(Plain(io.name, io.integer ? SignalType::kInt : SignalType::kBool,
                          io.output ? Direction::kPlcToMachine : Direction::kMachineToPlc,
                          io.meaning, "machine model", io.name, Scope::kIo, -1));
    table.back().preset = io.preset;
    table.back().operator_input = io.operator_input;
  }

  // Machine I/O names come from the model and may collide with NC signal names.
  std::set<std::string_view> names;
  for (const Signal& s : table) {
    if (!names.insert(s.name).second) {
      Reject(s.scope == Scope::kIo ? "io" : "(whole layout)",
             "signal name '" + s.name + "' occurs twice");
    }
  }
  AssignModbus(table);
  return table;
}

int LockstepCycleRegister(const std::vector<Signal>& table) {
  int end = 0;
  for (const Signal& s : table)
    if (s.modbus.area == ModbusAddress::kHoldingRegister)
      end = std::max(end, s.modbus.address + s.modbus.count);
  return end;
}

int AxdWrRegister(const std::vector<Signal>& table) { return LockstepCycleRegister(table) + 1; }

}  // namespace vmt::control::gateway
