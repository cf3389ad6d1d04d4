#pragma once
// Vocabulary of the gateway between NC and PLC: the data type of a signal, who writes it, and
// how many instances of a signal family a machine has.

#include <cstdint>
#include <string>

namespace vmt::control::gateway {

/// IEC 61131-3 type of a signal as the PLC declares it. The manuals' types map onto these:
/// MTC200 BOOL/INT/UINT; TwinCAT BOOLEAN -> kBool, SGN16 -> kInt, UN16/UNS16 -> kUint,
/// SGN32 -> kDint, UN32/UNS32/UDINT -> kUdint, REAL64 -> kLreal, STRING -> kString.
enum class SignalType : uint8_t {
  kBool,
  kInt,     ///< 16-bit signed
  kUint,    ///< 16-bit unsigned number
  kWord,    ///< 16-bit bit string (e.g. ident number 65012, c-axis 2.2)
  kDint,    ///< 32-bit signed
  kUdint,   ///< 32-bit unsigned number
  kDword,   ///< 32-bit bit string
  kReal,    ///< IEEE-754 binary32
  kLreal,   ///< IEEE-754 binary64 (TwinCAT REAL64)
  kString,  ///< STRING(83): 84 bytes with the terminating NUL (twincat 5.2.1, 5.4)
};

/// Who writes a signal. The manuals call PLC -> NC "control signals" (PxxC.*, AxxC.*) and
/// NC -> PLC "status signals" (PxxS.*, AxxS.*); TwinCAT CNC objects ending in _w are written by
/// the PLC, those ending in _r are read.
enum class Direction : uint8_t {
  kPlcToNc,
  kNcToPlc,
  /// Both sides write: MTC200 events (the NC by SE/RE, the SPS by its event write; which side
  /// sets which event depends on the program: fast-measurement 6.2 vs. repositioning 8.3) and
  /// the AXD ident numbers marked [Read/Write] (c-axis 2.2).
  kShared,
  kMachineToPlc,  ///< machine input the PLC reads (switch, probe contact)
  kPlcToMachine,  ///< machine output the PLC writes (valve, probe activation)
};

/// How many instances a signal family has on a machine.
enum class Scope : uint8_t {
  kProcess,     ///< one per NC process (channel): Pxx
  kAxis,        ///< one per axis: Axx
  kSpindle,     ///< one per spindle-capable axis (the spindle-related signals, c-axis 4.2 "*")
  kChangeover,  ///< spindle-capable axes and rotary axes: spindle <-> C changeover data
  kGlobal,      ///< one per machine (fixed name)
  kIo,          ///< machine I/O point named by the machine model
};

const char* ToString(SignalType type);
const char* ToString(Direction direction);
const char* ToString(Scope scope);

/// True for the directions in which the PLC writes the signal (Modbus coils and holding
/// registers); false where it only reads (discrete inputs and input registers).
bool PlcWrites(Direction direction);

/// Number of 16-bit Modbus registers a value of `type` occupies (1 for kBool: one coil or
/// discrete input).
int RegisterCount(SignalType type);

/// Bytes of a kString value including the terminating NUL (TwinCAT: "maximal 84 Zeichen").
inline constexpr int kStringBytes = 84;

/// True for the integer types (kInt .. kDword); kBool, kReal, kLreal and kString are not.
bool IsInteger(SignalType type);
/// Range of an integer type; aborts for the other types.
int64_t MinValue(SignalType type);
int64_t MaxValue(SignalType type);

/// Why a signal of `type` cannot hold `value` ("1.5 is not an integer: INT", "40000 is outside
/// INT's range -32768..32767"), or empty if it can. Every path that writes a value the user
/// gave (scene presets, PLC constants, timeline steps, --set) asks this before writing, so
/// that a wrong value is refused with its place instead of aborting the gateway.
std::string ValueError(SignalType type, double value);

}  // namespace vmt::control::gateway
