// The name tables of the typed instructions and functions: one place that says which word is
// which, read by both front ends and the expression parser.

#include "control/nc/instruction.hpp"

#include <array>
#include <utility>

namespace vmt::control::nc {
namespace {

using I = Instruction;
constexpr std::array<std::pair<std::string_view, Instruction>, 33> kInstructions{{
    {"BRA", I::kBra},         {"BEQ", I::kBeq},         {"BNE", I::kBne},
    {"BGT", I::kBgt},         {"BLT", I::kBlt},         {"BGE", I::kBge},
    {"BLE", I::kBle},         {"BES", I::kBes},         {"BEC", I::kBec},
    {"JSR", I::kJsr},         {"RTS", I::kRts},         {"RET", I::kRet},
    {"REV", I::kRev},         {"L", I::kL},             {"MTP", I::kMtp},
    {"MMP", I::kMmp},         {"MRF", I::kMrf},         {"MHP", I::kMhp},
    {"MFP", I::kMfp},         {"MOP", I::kMop},         {"MRY", I::kMry},
    {"SE", I::kSe},           {"RE", I::kRe},           {"TLD", I::kTld},
    {"OTD", I::kOtd},         {"MTD", I::kMtd},         {"SETTING", I::kSetting},
    {"SAVE", I::kSave},       {"MOVE", I::kMove},       {"PROBE", I::kProbe},
    {"COMPARE", I::kCompare}, {"CORRECTION", I::kCorrection}, {"RESTORE", I::kRestore},
}};

using F = Function;
constexpr std::array<std::pair<std::string_view, Function>, 17> kFunctions{{
    {"G", F::kG},     {"M", F::kM},       {"SIN", F::kSin},   {"COS", F::kCos},
    {"TAN", F::kTan}, {"ASIN", F::kAsin}, {"ACOS", F::kAcos}, {"ATAN", F::kAtan},
    {"ABS", F::kAbs}, {"INT", F::kInt},   {"ROUND", F::kRound}, {"EXP", F::kExp},
    {"SQRT", F::kSqrt}, {"LN", F::kLn},   {"TLD", F::kTld},   {"OTD", F::kOtd},
    {"MTD", F::kMtd},
}};

// Every value but kNone once, in the order of the enum: InstructionName indexes the table.
constexpr bool InOrder() {
  for (size_t i = 0; i < kInstructions.size(); ++i)
    if (static_cast<size_t>(kInstructions[i].second) != i + 1) return false;
  return static_cast<size_t>(I::kRestore) == kInstructions.size();
}
static_assert(InOrder());

}  // namespace

Instruction InstructionOf(std::string_view name) {
  for (const auto& [text, instruction] : kInstructions)
    if (text == name) return instruction;
  return I::kNone;
}

const char* InstructionName(Instruction instruction) {
  const auto i = static_cast<size_t>(instruction);
  return i == 0 || i > kInstructions.size() ? "" : kInstructions[i - 1].first.data();
}

HashCommand HashCommandOf(std::string_view text) {
  using H = HashCommand;
  constexpr std::pair<std::string_view, H> kCommands[] = {
      {"DISTANCE PROG START", H::kDistanceProgStart},
      {"BLOCKSEARCH", H::kBlockSearch},
      {"CAX TRACK", H::kCaxTrack},
      {"CAXTRACK", H::kCaxTrack},
      {"VECTOR OFFSET", H::kVectorOffset},
  };
  for (const auto& [start, command] : kCommands)
    if (text.starts_with(start)) return command;
  return H::kOther;
}

Function FunctionOf(std::string_view name) {
  // Called for every call an expression writes while the program is parsed: a name longer than
  // any function's is let go at once.
  if (name.size() > 5) return F::kNone;
  for (const auto& [text, function] : kFunctions)
    if (text == name) return function;
  return F::kNone;
}

}  // namespace vmt::control::nc
