#pragma once
// The names of the NC language that the control acts on, typed: the instruction a statement
// names (MTP, BEQ, SETTING, TLD) and the built-in function an expression calls (SIN, G, TLD)
// are looked up once, when the program is parsed, and the interpreter and the channel switch
// on the value. The name as written stays in the program for the messages.

#include <cstdint>
#include <string_view>

namespace vmt::control::nc {

/// The instructions of both dialects, each named as in its manual.
enum class Instruction : uint8_t {
  /// No instruction: an assignment to a variable, a $-structure, a #-command.
  kNone,
  // MTC200 flow of control: branches on the result of the last computation, event branches,
  // subroutine call and returns, the reverse vector.
  kBra,
  kBeq,
  kBne,
  kBgt,
  kBlt,
  kBge,
  kBle,
  kBes,
  kBec,
  kJsr,
  kRts,
  kRet,
  kRev,
  /// ISG: L name, the call of a subprogram.
  kL,
  // MTC200 tool storage (turret) instructions and MRY, the wait for it.
  kMtp,
  kMmp,
  kMrf,
  kMhp,
  kMfp,
  kMop,
  kMry,
  // MTC200 set and reset of an event.
  kSe,
  kRe,
  // MTC200 data access: tool data, zero offsets, machine data pages.
  kTld,
  kOtd,
  kMtd,
  // The fast-measurement instructions (fast measurement manual 2).
  kSetting,
  kSave,
  kMove,
  kProbe,
  kCompare,
  kCorrection,
  kRestore,
};

/// The ISG #-commands the control acts on, by the words they begin with (the statement keeps
/// the whole text for their options): the steering commands of block search, #CAX TRACK and
/// #VECTOR OFFSET.
enum class HashCommand : uint8_t {
  kOther,              ///< any other #-command: refused when its block runs
  kDistanceProgStart,  ///< #DISTANCE PROG START ON | OFF (block search 4.1.2)
  kBlockSearch,        ///< #BLOCKSEARCH LOCKED | RELEASED (block search 6)
  kCaxTrack,           ///< #CAX TRACK or #CAXTRACK (block search 4.2.2)
  kVectorOffset,       ///< #VECTOR OFFSET (block search 4.2.3)
};

/// The command a #-command's text (upper case, single spaces, as the ISG front end keeps it)
/// begins with.
HashCommand HashCommandOf(std::string_view text);

/// The instruction `name` (upper case, as the front ends intern it) names; kNone for any other
/// name.
Instruction InstructionOf(std::string_view name);
/// The manual's name of `instruction` ("MTP", "SETTING"); "" for kNone.
const char* InstructionName(Instruction instruction);

/// TLD, OTD, MTD.
inline bool IsDataAccess(Instruction i) {
  return i == Instruction::kTld || i == Instruction::kOtd || i == Instruction::kMtd;
}
/// SETTING, SAVE, MOVE, PROBE, COMPARE, CORRECTION, RESTORE: the instructions of
/// InstructionCall.
inline bool IsMeasuringCall(Instruction i) {
  return i >= Instruction::kSetting && i <= Instruction::kRestore;
}

/// The built-in functions of expressions: the modal state G(n) / M(n) (MTC200 data access to
/// the modal groups), arithmetic, and the data access functions, which read through the
/// channel.
enum class Function : uint8_t {
  kNone,  ///< a name that is no built-in function: its call is an error when evaluated
  kG,
  kM,
  kSin,
  kCos,
  kTan,
  kAsin,
  kAcos,
  kAtan,
  kAbs,
  kInt,
  kRound,
  kExp,
  kSqrt,
  kLn,
  kTld,
  kOtd,
  kMtd,
};

/// The built-in function `name` (upper case) names; kNone for any other name.
Function FunctionOf(std::string_view name);

/// The data access instruction a data function reads (TLD, OTD, MTD); kNone for the others.
inline Instruction DataAccessOf(Function f) {
  switch (f) {
    case Function::kTld:
      return Instruction::kTld;
    case Function::kOtd:
      return Instruction::kOtd;
    case Function::kMtd:
      return Instruction::kMtd;
    default:
      return Instruction::kNone;
  }
}

}  // namespace vmt::control::nc
