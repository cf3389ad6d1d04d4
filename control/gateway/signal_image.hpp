#pragma once
// The signal image: the current value of every gateway signal, read and written by the NC
// kernel, the PLC runtime and the Modbus adapter every cycle. Names are resolved to ids once
// (Find / Require); the per-tick get/set is an index into flat arrays with a type check.

#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "control/gateway/signal_table.hpp"

namespace vmt::control::gateway {

class SignalImage {
 public:
  /// Takes the table (usually BuildSignalTable's) and sets every signal to its preset. Throws
  /// std::invalid_argument if a name occurs twice.
  explicit SignalImage(std::vector<Signal> table);

  /// Id of the signal called exactly `name` (case-sensitive; aliases are not names), or -1.
  int Find(std::string_view name) const;
  /// Id of `name`; aborts naming it if the table has no such signal (for code that needs it).
  int Require(std::string_view name) const;

  const std::vector<Signal>& table() const { return table_; }
  int size() const { return static_cast<int>(table_.size()); }
  /// table()[id].type from a dense array: the type dispatch of a per-cycle access touches no
  /// signal's name or description. `id` must be within the table.
  SignalType type(int id) const { return types_[id]; }

  // Accessors abort (with the signal's name) on an id out of range, on the wrong type (Bool
  // for kBool; Int for the integer types; Real for kReal and kLreal; String for kString) and
  // on an integer outside its type's range or a string longer than 83 bytes.
  [[gnu::always_inline]] bool Bool(int id) const {
    Check(id, IsBool, "Bool");
    return cells_[id] != 0;
  }
  [[gnu::always_inline]] void SetBool(int id, bool v) {
    Check(id, IsBool, "SetBool");
    Store(id, v ? 1 : 0);
  }
  [[gnu::always_inline]] int64_t Int(int id) const {
    Check(id, IsInteger, "Int");
    return cells_[id];
  }
  [[gnu::always_inline]] void SetInt(int id, int64_t v) {
    Check(id, IsInteger, "SetInt");
    if (v < range_[id].min || v > range_[id].max) [[unlikely]]
      RefuseRange(id, v);
    Store(id, v);
  }
  /// kReal values are stored rounded to binary32, as a REAL variable and its registers hold them.
  [[gnu::always_inline]] double Real(int id) const {
    Check(id, IsReal, "Real");
    return std::bit_cast<double>(cells_[id]);
  }
  [[gnu::always_inline]] void SetReal(int id, double v) {
    Check(id, IsReal, "SetReal");
    Store(id, RealBits(types_[id], v));
  }
  const std::string& String(int id) const;
  void SetString(int id, std::string_view v);
  /// Any signal as a number: BOOL 0/1, the integers, REAL/LREAL; a STRING reads 0.
  [[gnu::always_inline]] double Number(int id) const {
    Check(id, AnyType, "Number");
    const int64_t cell = cells_[id];
    switch (types_[id]) {
      case SignalType::kBool:
        return cell != 0 ? 1 : 0;
      case SignalType::kReal:
      case SignalType::kLreal:
        return std::bit_cast<double>(cell);
      case SignalType::kString:
        return 0;
      default:
        return static_cast<double>(cell);
    }
  }
  /// A number into a signal of any numeric type (BOOL: != 0; integers rounded half away from
  /// zero, as std::llround); a STRING is left as it is.
  [[gnu::always_inline]] void SetNumber(int id, double value) {
    Check(id, AnyType, "SetNumber");
    switch (types_[id]) {
      case SignalType::kBool:
        Store(id, value != 0 ? 1 : 0);
        return;
      case SignalType::kReal:
      case SignalType::kLreal:
        Store(id, RealBits(types_[id], value));
        return;
      case SignalType::kString:
        return;
      default:
        SetInt(id, RoundHalfAway(value));
    }
  }

  /// Every signal's stored cell (BOOL/integer value, REAL/LREAL bits, a STRING's slot), by id.
  /// A cell that compares equal to an earlier copy holds the same value (strings aside), so a
  /// watcher of thousands of signals finds the few that changed without a typed read of each.
  std::span<const int64_t> cells() const { return cells_; }
  /// Counts the writes that changed a value (a string's too; a reset or a copy of all values
  /// counts as one): a watcher that finds the count it saw last has nothing new to read.
  uint64_t changes() const { return changes_; }

  /// Every signal back to its preset (Control-Reset of a simulation, not of the NC).
  void Reset();

  /// Every value from `other`, an image of the same table (the PLC latching its inputs).
  void CopyValuesFrom(const SignalImage& other);
  /// One signal's value from `other`, an image of the same table (the PLC writing an output).
  void CopyValue(int id, const SignalImage& other);

 private:
  // Inline, because the NC, the PLC and the watchers make tens of these accesses each NC cycle;
  // the refusal, with its message, out of line. `accepts` is the accessor's test of the type.
  // Forced: left to itself, the link-time optimiser kept out-of-line copies that call the test
  // through its pointer.
  template <class TypeTest>
  [[gnu::always_inline]] void Check(int id, TypeTest accepts, const char* accessor) const {
    if (id < 0 || id >= size() || !accepts(types_[id])) [[unlikely]]
      Refuse(id, accessor);
  }
  static bool IsBool(SignalType t) { return t == SignalType::kBool; }
  static bool IsInteger(SignalType t) { return t >= SignalType::kInt && t <= SignalType::kDword; }
  static bool IsReal(SignalType t) { return t == SignalType::kReal || t == SignalType::kLreal; }
  static bool IsString(SignalType t) { return t == SignalType::kString; }
  static bool AnyType(SignalType) { return true; }
  [[noreturn]] void Refuse(int id, const char* accessor) const;
  [[noreturn]] void RefuseRange(int id, int64_t v) const;
  // A REAL cell holds the binary32 value widened, so that Real() equals what the PLC reads.
  static int64_t RealBits(SignalType type, double v) {
    if (type == SignalType::kReal) v = static_cast<double>(static_cast<float>(v));
    return std::bit_cast<int64_t>(v);
  }
  // std::llround without the library call for the values a signal can hold: below 2^63 the
  // truncation and the fraction it leaves are exact; NaN and larger magnitudes go to llround.
  static int64_t RoundHalfAway(double v) {
    if (!(std::fabs(v) < 9.2e18)) [[unlikely]]
      return std::llround(v);
    const int64_t i = static_cast<int64_t>(v);
    const double fraction = v - static_cast<double>(i);
    return i + (fraction >= 0.5) - (fraction <= -0.5);
  }
  [[gnu::always_inline]] void Store(int id, int64_t cell) {
    if (cells_[id] == cell) return;
    cells_[id] = cell;
    ++changes_;
  }

  std::vector<Signal> table_;
  std::vector<SignalType> types_;  // by id: the type check without touching table_
  struct Range {
    int64_t min = 0, max = 0;
  };
  std::vector<Range> range_;          // by id: an integer type's values (empty range otherwise)
  std::vector<int64_t> cells_;        // by id: BOOL/integer value, REAL/LREAL bits, string slot
  std::vector<std::string> strings_;  // by string slot
  std::vector<int> by_name_;          // ids sorted by name, for Find
  uint64_t changes_ = 0;
};

/// Modbus register image of a non-BOOL signal; `out.size()` must be its modbus.count. Words are
/// sent most significant first: INT/UINT/WORD one register (INT two's complement);
/// DINT/UDINT/DWORD two registers, high word first; REAL the IEEE-754 binary32 bits, high word
/// first; LREAL the binary64 bits, most significant word first; STRING two bytes per register,
/// first character in the high byte, NUL-padded to 84 bytes.
void ToRegisters(const SignalImage& image, int id, std::span<uint16_t> out);
/// The inverse of ToRegisters. Every frame decodes: integers are read within the type's width
/// (0xFFFF is -1 for INT, 65535 for UINT), a STRING ends at its first NUL or after 83 bytes.
void FromRegisters(SignalImage& image, int id, std::span<const uint16_t> in);

}  // namespace vmt::control::gateway
