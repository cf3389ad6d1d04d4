#pragma once
// The NC <-> PLC signals the four manuals in ../shared/seeds name, as data: one row per signal
// family (a name pattern with the Pxx / Axx placeholder), the values some of them take (HLI_BS_*,
// HLI_SC_*, FEHLER_NR ...), and the names the manuals use that are deliberately not gateway
// signals. BuildSignalTable (signal_table.hpp) instantiates the families for a machine.
//
// Sources are written "<manual file> <section>"; "vmt" marks the few operator-panel signals the
// NC needs that no manual names (mode selection, cycle start/stop, Control-Reset, overrides,
// error state). Their names follow the manuals' scheme PxxC.<mnemonic> / PxxS.<mnemonic>.

#include <cstdint>
#include <span>
#include <string_view>

#include "control/gateway/signal_types.hpp"

namespace vmt::control::gateway {

/// One signal family. `pattern` is the manuals' spelling with its placeholder kept:
///  - "PxxC.REPOS", "PxxS.CREST": process control/status signals (repositioning 7; the manuals
///    also write them without the dot, "PxxSSTOP", "AxxCJGPOS": those spellings are aliases);
///  - "AxxC.JGPOS", "AxxS.IDDS": axis signals (c-axis 4.2);
///  - "Pxx.<name>", "Axx.<name>": per-process / per-axis cells of names the manuals write
///    without a Pxx/Axx prefix (events "Pxx.EV29", Q functions "Pxx.Q9992", standard functions
///    "Axx.ROTMOD", AXD ident numbers "Axx.AXD.65012", TwinCAT CNC objects and HLI elements
///    "Pxx.mc_cmd_bs_type_w", "Pxx.bahn_state.block_search_state_r");
///  - fixed names for kGlobal ("QMFB1A00.ENABLE": pins of the fast-measurement function block).
struct SignalFamily {
  std::string_view pattern;
  Scope scope;
  SignalType type;
  Direction direction;
  std::string_view meaning;  ///< one line, from the manual's text
  std::string_view source;   ///< "<manual file> <section>[; ...]" or "vmt ..."
  std::string_view unit = {};
  std::string_view aliases = {};  ///< other spellings in the manuals, ';'-separated
  double preset = 0;              ///< value before anyone writes (e.g. QMFB1Axx input presets)
  /// Empty: vmt reads (PLC->NC) or writes (NC->PLC) the signal as its meaning says. Otherwise
  /// why vmt neither evaluates nor drives it: the cell is there for the PLC program, but a
  /// write changes nothing, or it stays at its preset.
  std::string_view not_evaluated = {};
};

/// A named value or bit of a signal family (state numbers, bit masks, error numbers).
struct ValueName {
  std::string_view pattern;  ///< the SignalFamily::pattern whose values these are
  std::string_view name;     ///< manual's constant (HLI_BS_ACTIVE); empty if it gives a number only
  int64_t value;
  bool bit_mask;  ///< `value` is a bit mask within the signal, not a whole value
  std::string_view meaning;
  std::string_view source;
};

/// A name the manuals use near the gateway that is not a gateway signal, and why.
struct Unrepresented {
  std::string_view name;
  std::string_view reason;
  std::string_view source;
};

/// Every signal family, in the order the table lists them.
std::span<const SignalFamily> SignalFamilies();
/// Named values of the families (HLI_BS_*, HLI_SC_*, FEHLER_NR, ident 65012 bits ...).
std::span<const ValueName> SignalValues();
/// Names around the gateway deliberately left out of the table.
std::span<const Unrepresented> UnrepresentedNames();

/// The Q functions and events the manuals fix (fast-measurement 4.1: "Q9992, Q9998 and Q9999
/// and the NC events E7, E29 and E30"); a machine may add its own (GatewayLayout).
inline constexpr int kManualQFunctions[] = {9992, 9998, 9999};
inline constexpr int kManualEvents[] = {7, 29, 30};

}  // namespace vmt::control::gateway
