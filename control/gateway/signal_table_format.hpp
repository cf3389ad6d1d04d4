#pragma once
// The signal table for the PLC engineer: CSV for a spreadsheet or a PLC tool's import, JSON for
// programs. This pair is the only part of control/gateway that uses nlohmann_json; link it
// separately from the kernel.

#include <string>
#include <vector>

#include "control/gateway/signal_table.hpp"

namespace vmt::control::gateway {

/// The `vmt` column: "evaluated" when vmt reads or drives the signal as its meaning says, else
/// "not evaluated: <why>" (the cell is there, nothing in vmt acts on it or sets it).
std::string VmtColumn(const Signal& s);

/// One line per signal under the header
/// `name,type,direction,area,address,count,meaning,source,vmt`
/// (RFC 4180 quoting: a field with a comma, quote or line break is enclosed in quotes, quotes
/// doubled; lines end with "\n"). type: BOOL, INT, ...; direction: PLC->NC, NC->PLC, NC<->PLC,
/// MACHINE->PLC, PLC->MACHINE; area: coil, discrete_input, holding_register, input_register.
std::string FormatCsv(const std::vector<Signal>& table);

/// {"format": "vmt-gateway-signals", "version": 1, "modbus": {...encoding...},
///  "signals": [{name, type, direction, scope, instance, axis_name, pattern, modbus: {area,
///  address, count}, meaning, unit, source, aliases, preset, vmt: "evaluated" | "not evaluated",
///  not_evaluated: why}],
///  "values": [{signal_pattern, name, value, bit_mask, meaning, source}] (those of the families
///  present in the table), "unrepresented": [{name, reason, source}]}, indented by 2.
std::string FormatJson(const std::vector<Signal>& table);

}  // namespace vmt::control::gateway
