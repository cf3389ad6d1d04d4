#include "control/gateway/signal_table_format.hpp"

#include <nlohmann/json.hpp>
#include <set>
#include <string_view>

#include "control/gateway/nc_status_block.hpp"

namespace vmt::control::gateway {
namespace {

std::string CsvField(std::string_view field) {
  if (field.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(field);
  std::string out = "\"";
  for (char c : field) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

}  // namespace

std::string VmtColumn(const Signal& s) {
  return s.not_evaluated.empty() ? "evaluated" : "not evaluated: " + s.not_evaluated;
}

std::string WrittenBy(const Signal& s) {
  switch (s.direction) {
    case Direction::kNcToPlc:
      return "vmt (the NC)";
    case Direction::kMachineToPlc:
      return s.operator_input ? "the operator (vmt: timeline, station)" : "vmt (the machine)";
    case Direction::kPlcToNc:
    case Direction::kPlcToMachine:
      return "the PLC";
    case Direction::kShared:
      return "the PLC and the NC";
  }
  return "";
}

std::string FormatCsv(const std::vector<Signal>& table) {
  // Modbus addresses as the protocol data unit carries them, from 0 (mbpoll: -0; tools that
  // count from 1 add one).
  std::string out =
      "name,type,direction,area,address (0-based),count,meaning,source,vmt,written_by\n";
  for (const Signal& s : table) {
    out += CsvField(s.name) + ',' + ToString(s.type) + ',' + ToString(s.direction) + ',' +
           ToString(s.modbus.area) + ',' + std::to_string(s.modbus.address) + ',' +
           std::to_string(s.modbus.count) + ',' + CsvField(s.meaning) + ',' + CsvField(s.source) +
           ',' + CsvField(VmtColumn(s)) + ',' + CsvField(WrittenBy(s)) + '\n';
  }
  // vmt serve's registers beyond the signals (control/plc/modbus_server.hpp).
  out += "(lockstep cycle),UINT,PLC->NC,holding_register," +
         std::to_string(LockstepCycleRegister(table)) +
         ",1,\"vmt serve --lockstep: the PLC writes the next cycle number (modulo 65536) after its "
         "outputs; vmt runs that PLC cycle, then answers\",vmt serve,evaluated,the PLC\n";
  out += "(AXD_WR block),WORD,PLC->NC,holding_register," + std::to_string(AxdWrRegister(table)) +
         ",6,\"a drive parameter write: axis, ident, value (DINT, 2 registers), result (read "
         "only), writes done (read only)\",vmt serve (fast-measurement 7.2 AXD_WR),evaluated,"
         "the PLC\n";
  // The NC status block: read only, refreshed by vmt serve after every cycle.
  for (const NcStatusField& f : NcStatusLayoutOf(table).Fields()) {
    out += f.name + ',' + ToString(f.type) + ",NC->PLC,input_register," +
           std::to_string(f.address) + ',' + std::to_string(f.count) + ',' +
           CsvField(f.unit.empty() ? f.meaning : f.meaning + " [" + f.unit + "]") +
           ",vmt serve (NC status block),evaluated,vmt (the NC)\n";
  }
  return out;
}

std::string FormatJson(const std::vector<Signal>& table) {
  using nlohmann::ordered_json;
  const NcStatusLayout nc_status = NcStatusLayoutOf(table);
  ordered_json doc;
  doc["format"] = "vmt-gateway-signals";
  doc["version"] = 1;
  doc["modbus"] = {
      {"coil", "BOOL the PLC writes"},
      {"discrete_input", "BOOL the PLC reads"},
      {"holding_register", "numeric or STRING the PLC writes"},
      {"input_register", "numeric or STRING the PLC reads"},
      {"addressing", "0-based: the address the Modbus PDU carries (mbpoll: -0)"},
      {"lockstep_cycle_register", LockstepCycleRegister(table)},
      {"axd_wr_register", AxdWrRegister(table)},
      {"nc_status_register", nc_status.address},
      {"encoding",
       "16-bit registers, most significant word first; INT two's complement; DINT/UDINT/DWORD 2 "
       "registers; REAL IEEE-754 binary32 in 2 registers; LREAL binary64 in 4; STRING(83) 42 "
       "registers, first character in the high byte, NUL-padded"},
  };
  ordered_json signals = ordered_json::array();
  std::set<std::string> patterns;
  for (const Signal& s : table) {
    patterns.insert(s.pattern);
    ordered_json j;
    j["name"] = s.name;
    j["type"] = ToString(s.type);
    j["direction"] = ToString(s.direction);
    j["scope"] = ToString(s.scope);
    j["instance"] = s.instance;
    if (!s.instance_name.empty()) j["axis_name"] = s.instance_name;
    j["pattern"] = s.pattern;
    j["modbus"] = {{"area", ToString(s.modbus.area)},
                   {"address", s.modbus.address},
                   {"count", s.modbus.count}};
    j["meaning"] = s.meaning;
    if (!s.unit.empty()) j["unit"] = s.unit;
    j["source"] = s.source;
    if (!s.aliases.empty()) j["aliases"] = s.aliases;
    if (s.preset != 0) j["preset"] = s.preset;
    j["vmt"] = s.not_evaluated.empty() ? "evaluated" : "not evaluated";
    j["written_by"] = WrittenBy(s);
    if (!s.not_evaluated.empty()) j["not_evaluated"] = s.not_evaluated;
    signals.push_back(std::move(j));
  }
  doc["signals"] = std::move(signals);
  ordered_json status = ordered_json::array();
  for (const NcStatusField& f : nc_status.Fields()) {
    ordered_json j;
    j["name"] = f.name;
    j["type"] = ToString(f.type);
    j["direction"] = ToString(Direction::kNcToPlc);
    j["modbus"] = {{"area", "input_register"}, {"address", f.address}, {"count", f.count}};
    j["meaning"] = f.meaning;
    if (!f.unit.empty()) j["unit"] = f.unit;
    j["written_by"] = "vmt (the NC)";
    status.push_back(std::move(j));
  }
  doc["nc_status"] = std::move(status);

  ordered_json values = ordered_json::array();
  for (const ValueName& v : SignalValues()) {
    if (patterns.count(std::string(v.pattern)) == 0) continue;
    values.push_back({{"signal_pattern", v.pattern},
                      {"name", v.name},
                      {"value", v.value},
                      {"bit_mask", v.bit_mask},
                      {"meaning", v.meaning},
                      {"source", v.source}});
  }
  doc["values"] = std::move(values);

  ordered_json unrepresented = ordered_json::array();
  for (const Unrepresented& u : UnrepresentedNames()) {
    unrepresented.push_back({{"name", u.name}, {"reason", u.reason}, {"source", u.source}});
  }
  doc["unrepresented"] = std::move(unrepresented);
  return doc.dump(2) + "\n";
}

}  // namespace vmt::control::gateway
