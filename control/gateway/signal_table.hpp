#pragma once
// The gateway signal table of one machine: the catalog's families (signal_catalog.hpp)
// instantiated for its processes and axes, plus the machine's own I/O points, each with a
// Modbus address for an external PLC.
//
// Naming rules (from the manuals):
//  - Pxx -> P00, P01, ...: two digits, process numbers from 0 (fast-measurement 3.1: "the
//    master process (process 0)"; repositioning 8.2 and fast-measurement 7.2 write P00C.REPOS,
//    P00S.RUN). For the TwinCAT names Pxx is the HLI channel index (gpCh[xx], from 0).
//  - Axx -> A01, A02, ...: two digits, axis numbers from 1 to 32 (fast-measurement 7.2:
//    QMFB1Axx rejects axis numbers < 1 and > 32 and wires axis 1 to A01C.QDDS; repositioning
//    8.1: "the spindle whose axis number is 'xx'"; c-axis 3.2: axis number 0 means "none").
//  - The canonical spelling has the dot (PxxS.STOP); the manuals' undotted spellings
//    (PxxSSTOP, AxxCJGPOS) are aliases.
//  - Names are case-sensitive (QMFB1A00.Q_MTstKol and the manual's variant Q_MTstKOl differ).
//
// Modbus (for an external PLC, Modbus TCP): BOOL signals the PLC writes are coils, BOOL signals
// it reads are discrete inputs, numeric ones it writes are holding registers, numeric ones it
// reads are input registers. "Writes" includes the shared signals (events, AXD idents) and the
// machine outputs. Addresses run from 0 per area in table order, without gaps. Register layout
// of multi-register values: see ToRegisters in signal_image.hpp.

#include <string>
#include <vector>

#include "control/gateway/signal_catalog.hpp"
#include "control/gateway/signal_types.hpp"

namespace vmt::control::gateway {

/// Where an external PLC finds a signal over Modbus. `count` is in bits for the bit areas and in
/// 16-bit registers for the register areas.
struct ModbusAddress {
  enum Area { kCoil, kDiscreteInput, kHoldingRegister, kInputRegister } area;
  int address;
  int count;
};

const char* ToString(ModbusAddress::Area area);

/// One signal of a machine's gateway.
struct Signal {
  std::string name;  ///< instantiated name: "P00C.REPOS", "A03.ROTMOD_Q", "QMFB1A00.ENABLE"
  SignalType type;
  Direction direction;
  std::string meaning;  ///< the family's meaning, with " [unit]" appended where it has one
  std::string source;   ///< "<manual file> <section>", "vmt ...", or "machine model" for I/O
  ModbusAddress modbus;
  std::string pattern;  ///< the family's pattern ("PxxC.REPOS"); the name itself for I/O
  Scope scope;
  int instance;               ///< process or axis number; -1 for global signals and I/O
  std::string instance_name;  ///< the axis name (program address) for axis signals, else empty
  std::string unit;
  std::vector<std::string> aliases;  ///< other spellings in the manuals, instantiated
  double preset;                     ///< initial value
  /// Empty when vmt evaluates or drives the signal, else why not (SignalFamily::not_evaluated).
  std::string not_evaluated;
  bool operator_input = false;  ///< an operator's key or selector of the machine's I/O
};

/// What a machine has: its NC processes, axes and I/O points.
struct GatewayLayout {
  std::vector<int> processes;  ///< process numbers, e.g. {0} -> P00
  struct Axis {
    int number;        ///< 1..32 -> A01..A32
    std::string name;  ///< program address: X, Z, S1, C
    /// Main spindle or main spindle with rotary axis capability: gets the spindle-related
    /// signals (c-axis 4.2 "*"), ROTMOD/ROTMOD_Q/SPMOD/SPMOD_Q and the AXD idents.
    bool spindle_capable = false;
    /// Rotary axis taking part in a spindle <-> C changeover (the separate C servo): gets the AXD
    /// idents 65012..65015, which the SPS writes for both drives (c-axis 4.4).
    bool rotary = false;
  };
  std::vector<Axis> axes;
  struct Io {
    std::string name;  ///< e.g. QROTMODE (valve), IROTMODE (switch)
    bool output;       ///< true: the PLC writes it (kPlcToMachine); false: reads it
    std::string meaning;
    bool integer = false;  ///< an INT (a selector's position), not a BOOL
    int preset = 0;
    bool operator_input = false;  ///< a key or selector: the operator sets it, not the machine
  };
  std::vector<Io> io;
  /// Q functions (Pxx.Qnnnn, Pxx.Qnnnn_Q) beyond the manuals' 9992, 9998, 9999; 0..9999.
  std::vector<int> q_functions;
  /// Events (Pxx.EVn) beyond the manuals' 7, 29, 30; 0..999.
  std::vector<int> events;
};

/// Lowest and highest axis number (QMFB1Axx FEHLER_NR 2..7, fast-measurement 7.2).
inline constexpr int kMinAxisNumber = 1;
inline constexpr int kMaxAxisNumber = 32;
inline constexpr int kMaxProcessNumber = 99;

/// The instantiated name of `pattern` for process or axis `number`: "PxxC.REPOS", 0 ->
/// "P00C.REPOS"; "AxxCJGPOS", 3 -> "A03CJGPOS". Patterns without a Pxx/Axx prefix come back
/// unchanged; a prefixed pattern with a number outside 0..99 throws std::out_of_range.
std::string InstanceName(std::string_view pattern, int number);

/// The signal table of a machine: per process (in layout order) its process families, extra Q
/// functions and events; per axis its axis families; then the global signals; then the I/O.
/// Families keep the catalog order. Throws std::invalid_argument naming the offending layout
/// field for duplicate or out-of-range process/axis/Q/event numbers, empty or duplicate names,
/// or a Modbus area that overflows 65536 addresses.
std::vector<Signal> BuildSignalTable(const GatewayLayout& layout);

/// The holding register an external PLC writes to step the simulation in lockstep (vmt serve
/// --lockstep, control/plc/modbus_server.hpp): one past the table's last holding register.
int LockstepCycleRegister(const std::vector<Signal>& table);
/// First of the six holding registers of the Modbus AXD_WR block (modbus_server.hpp) that vmt
/// serve offers an external PLC: right after the lockstep cycle register, in real time too.
int AxdWrRegister(const std::vector<Signal>& table);

}  // namespace vmt::control::gateway
