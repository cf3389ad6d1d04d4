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

/// Who sets the signal's value: "vmt (the NC)", "vmt (the machine)", "the operator (vmt:
/// timeline, station)", "the PLC", "the PLC and the NC".
std::string WrittenBy(const Signal& s);

/// One line per signal under the header
/// `name,type,direction,area,address (0-based),count,meaning,source,vmt,written_by`
/// (RFC 4180 quoting: a field with a comma, quote or line break is enclosed in quotes, quotes
/// doubled; lines end with "\n"), then the two register blocks of vmt serve that are not
/// signals: "(lockstep cycle)" and "(AXD_WR block)", then every register of the NC status block
/// (nc_status_block.hpp; the unit in the meaning's brackets). type: BOOL, INT, ...; direction:
/// PLC->NC, NC->PLC, NC<->PLC, MACHINE->PLC, PLC->MACHINE; area: coil, discrete_input,
/// holding_register, input_register; addresses from 0, as the Modbus PDU carries them.
std::string FormatCsv(const std::vector<Signal>& table);

/// {"format": "vmt-gateway-signals", "version": 1, "modbus": {...encoding...},
///  "signals": [{name, type, direction, scope, instance, axis_name, pattern, modbus: {area,
///  address, count}, meaning, unit, source, aliases, preset, vmt: "evaluated" | "not evaluated",
///  not_evaluated: why, written_by}],
///  "nc_status": [{name, type, direction, modbus, meaning, unit, written_by}] (the NC status
///  block, nc_status_block.hpp; modbus.nc_status_register is its first register),
///  "values": [{signal_pattern, name, value, bit_mask, meaning, source}] (those of the families
///  present in the table), "unrepresented": [{name, reason, source}]}, indented by 2.
std::string FormatJson(const std::vector<Signal>& table);

}  // namespace vmt::control::gateway
