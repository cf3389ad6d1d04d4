#pragma once
// The one block representation both dialect front ends produce (DESIGN.md control/nc): a program
// is a list of blocks with their source positions; a block holds address words (G01, X-30,
// S1=0, RX50, F2000) and statements (assignments, branches, calls, instructions, #-commands,
// structured control). Expressions live in one arena per program so that decoding a million
// blocks allocates per block, not per node.

#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "control/nc/instruction.hpp"
#include "control/nc/source_pos.hpp"

namespace vmt::control::nc {

enum class Dialect : uint8_t { kMtc200, kIsg };

const char* ToString(Dialect d);

/// Interned names: addresses ("X", "S1", "RX"), labels, instructions, variables.
class Symbols {
 public:
  uint32_t Intern(std::string_view name);
  const std::string& Name(uint32_t id) const { return names_[id]; }
  /// 0 if never interned.
  uint32_t Find(std::string_view name) const;

 private:
  std::deque<std::string> names_{""};  ///< id 0 is "no name"; a deque keeps the views valid
  std::unordered_map<std::string_view, uint32_t> ids_;
  // Recently interned short names (P1, X, @100) by their bytes: programs name the same few
  // things millions of times, and the hash map's lookup was a tenth of the decode time.
  struct Cached {
    uint64_t key = 0;  ///< up to 7 bytes of the name, its length in the top byte; 0 = empty
    uint32_t id = 0;
  };
  std::array<Cached, 256> cache_{};
};

using ExprId = int32_t;  ///< start of an expression in Program::code; -1 = none
inline constexpr ExprId kNoExpr = -1;

/// Expressions are postfix code for a value stack, one 32-bit unit per operation: the operation
/// in the low byte, an immediate in the upper 24 bits. A decoded tree of 32-byte nodes made the
/// code of a million-block program half a gigabyte, and first touches of fresh pages dominated
/// its decoding; this is about a fifth of that. An immediate of kWideImmediate means the value
/// is in the next unit. Only the places an evaluation can fail (/ MOD calls) keep their source
/// offset.
enum class ExprOp : uint8_t {
  kEnd,       ///< the value of the expression is the top of the stack
  kInt,       ///< push the immediate, a signed 24-bit integer
  kNumber,    ///< push Program::numbers[immediate]
  kVariable,  ///< push the variable named by the immediate: @100, P1, V.L.DIST, a bare name
  kOmitted,   ///< push 0 for an omitted argument (SETTING (X, Z, , 18))
  kNeg,
  kNot,
  kAdd,
  kSub,
  kMul,
  kPow,
  kEq,
  kNe,
  kLt,
  kLe,
  kGt,
  kGe,
  kXor,
  /// Divisor on top; next units: source offset, failure rank (see kCall).
  kDiv,
  kMod,
  /// `lhs AND rhs`: lhs, kAndSkip, n, rhs, kAnd. A zero lhs is the result and the n units after
  /// it are skipped (the rhs is not evaluated, so its faults are not reported).
  kAndSkip,
  kOrSkip,  ///< as kAndSkip: a non-zero lhs gives 1
  kAnd,     ///< top = top != 0, after the rhs of AND
  kOr,
  /// name(args): immediate = name; next units: the argument count (low 24 bits) with the
  /// built-in function the name is (Function, top byte; kNone for kArgs), source offset of the
  /// name, and the failure rank: the order in which the faults of an expression would be met by
  /// evaluating its tree (the divisor of / and MOD and the exponent of ^ before their left
  /// operand, as the interpreter always did); the first in that order is reported.
  kCall,
  kArgs,  ///< an instruction's argument list, laid out as kCall; nothing evaluates it
};

inline constexpr uint32_t kWideImmediate = 0xFFFFFF;
inline constexpr uint32_t ExprUnit(ExprOp op, uint32_t immediate = 0) {
  return static_cast<uint32_t>(op) | immediate << 8;
}
inline constexpr ExprOp OpOf(uint32_t unit) { return static_cast<ExprOp>(unit & 0xFF); }
/// The count unit after kCall / kArgs: the number of arguments and the function called.
inline constexpr uint32_t kMaxArguments = 0xFFFFFF;
inline constexpr uint32_t CountUnit(uint32_t count, Function f) {
  return count | static_cast<uint32_t>(f) << 24;
}
inline constexpr uint32_t CountOf(uint32_t count_unit) { return count_unit & kMaxArguments; }
inline constexpr Function FunctionOfUnit(uint32_t count_unit) {
  return static_cast<Function>(count_unit >> 24);
}

/// The binary operators kAdd .. kMod on values (a divisor is not 0). One definition for the
/// interpreter and the parser's constant folding, so that both compute the same bits.
inline double ApplyBinary(ExprOp op, double l, double r) {
  switch (op) {
    case ExprOp::kAdd:
      return l + r;
    case ExprOp::kSub:
      return l - r;
    case ExprOp::kMul:
      return l * r;
    case ExprOp::kPow:
      return std::pow(l, r);
    case ExprOp::kEq:
      return l == r;
    case ExprOp::kNe:
      return l != r;
    case ExprOp::kLt:
      return l < r;
    case ExprOp::kLe:
      return l <= r;
    case ExprOp::kGt:
      return l > r;
    case ExprOp::kGe:
      return l >= r;
    case ExprOp::kXor:
      return (l != 0) != (r != 0);
    case ExprOp::kDiv:
      return l / r;
    case ExprOp::kMod:
      return std::fmod(l, r);
    case ExprOp::kAnd:
      return (l != 0) && (r != 0);
    case ExprOp::kOr:
      return (l != 0) || (r != 0);
    default:
      return 0;
  }
}

/// An address with a value: G01, X-30.5, S1=0, RX50, F2000, M=@100, X[P1*2]. Most values are
/// plain numbers; they are kept in the word, not in the expression arena (a million-block
/// program would otherwise be mostly expression nodes).
struct Word {
  uint32_t address = 0;    ///< interned address, index included ("S1", "X1", "RX")
  ExprId value = kNoExpr;  ///< computed value, or kNoExpr: the value is `number`
  double number = 0;
  uint32_t offset = 0;  ///< in the file; Program::PosAt gives line and column
};

struct Statement {
  enum class Kind : uint8_t {
    kAssign,       ///< variable = value (@100=..., P1 = ...), or data = value (TLD(...) = ...)
    kBranch,       ///< BRA/BEQ/BNE/BGT/BLT/BGE/BLE .LABEL (name = mnemonic, target = label)
    kEventBranch,  ///< BES/BEC .LABEL event (value = event number)
    kCall,         ///< JSR .LABEL (MTC200) | L name (ISG)
    kReturn,       ///< RTS | RET
    kInstruction,  ///< MTP, MRY, SE 29, SETTING(...), TLD(...): name + args
    kHashCommand,  ///< ISG #-command: text after '#', normalised spaces
    kIf,
    kElseIf,
    kElse,
    kEndIf,
    kFor,
    kEndFor,
    kWhile,
    kEndWhile,
    kProgramEnd,  ///< M30 / M02 as program end (ISG); MTC200 uses RET
    /// REV .LABEL (MTC200): the reverse vector valid from this block on (target = label).
    kReverse,
  };
  Kind kind = Kind::kInstruction;
  /// The mnemonic or instruction `name` is, resolved by the front end (kBranch .. kInstruction,
  /// kReverse, and kAssign to a data location: TLD, OTD, MTD); kNone for the other kinds.
  Instruction instruction = Instruction::kNone;
  HashCommand hash = HashCommand::kOther;  ///< kHashCommand: what its text begins with
  uint32_t name = 0;       ///< mnemonic, variable or instruction name
  uint32_t target = 0;     ///< label or subprogram name
  ExprId value = kNoExpr;  ///< assigned value, condition, event, or argument list (kArgs)
  ExprId limit = kNoExpr, step = kNoExpr;  ///< $FOR var = value, limit, step
  ExprId data = kNoExpr;  ///< kAssign to a data location: the call TLD(...) | OTD(...) | MTD(...)
  uint32_t text = 0;      ///< #-command text: index into Program::texts
  int32_t jump = -1;      ///< resolved: block index of the target / matching structure block
  SourcePos pos;
};

struct Block {
  SourcePos pos;
  uint32_t counter = 0;    ///< 1-based block counter in its file (block search type 3)
  int32_t number = -1;     ///< N number, -1 if none
  uint32_t label = 0;      ///< ".REPOS" -> interned "REPOS"; 0 if none
  bool skippable = false;  ///< '/' block skip
  // The block's words and statements are ranges of the program's arenas (no allocation per
  // block): Program::Words(block), Program::Statements(block).
  uint32_t first_word = 0, num_words = 0;
  uint32_t first_statement = 0, num_statements = 0;
};

struct Program {
  std::string name;  ///< "%name" (ISG) or the file stem
  Dialect dialect = Dialect::kMtc200;
  std::vector<std::string> files;
  std::vector<Block> blocks;
  std::vector<Word> words;
  std::vector<Statement> statements;
  std::vector<uint32_t> code;      ///< expressions, see ExprOp
  std::vector<double> numbers;     ///< constants of the code that are not small integers
  uint32_t max_stack = 0;          ///< deepest value stack an expression of `code` needs
  std::vector<std::string> texts;  ///< #-command texts (kept out of Statement: it stays small)
  Symbols symbols;
  std::map<uint32_t, int32_t> labels;  ///< label -> block index
  std::vector<uint32_t> line_starts;   ///< file offset of each line, for PosAt

  /// Line and column of a file offset (words and expressions keep only the offset).
  SourcePos PosAt(uint32_t offset) const;
  /// An expression as fully parenthesised infix text, e.g. "((@100 + 2) * (3 ^ 2))",
  /// "SETTING(X, Z, , 18)": for tests and diagnostics.
  std::string ExprText(ExprId id) const;

  std::span<const Word> Words(const Block& b) const {
    return {words.data() + b.first_word, b.num_words};
  }
  std::span<const Statement> Statements(const Block& b) const {
    return {statements.data() + b.first_statement, b.num_statements};
  }
};

/// #DISTANCE PROG START ON | OFF | CLEAR (TwinCAT block search manual 4.1.2): whether the
/// distance from program start counts the following moves (ON, OFF: modal), or restarts at 0
/// (CLEAR). kNone: the block holds no such command.
enum class DistanceCommand : uint8_t { kNone, kOn, kOff, kClear };

/// What a #-command text (Program::texts: upper case, single spaces) says to block search:
/// #BLOCKSEARCH LOCKED | RELEASED (manual 6) or #DISTANCE PROG START ON | OFF | CLEAR (4.1.2).
/// The front end uses it to point at a wrong word, the interpreter to act on a right one, so
/// that both read the commands the same way.
struct SearchCommand {
  enum class Kind : uint8_t { kOther, kLock, kRelease, kDistance, kInvalid };
  Kind kind = Kind::kOther;  ///< kOther: a #-command that is none of these
  DistanceCommand distance = DistanceCommand::kNone;
  /// kInvalid: index in the text of the wrong word, or the text's size if a word is missing.
  size_t at = 0;
  std::string message;  ///< kInvalid
};
SearchCommand ReadSearchCommand(std::string_view text);

struct ParseResult {
  Program program;
  std::vector<Diagnostic> errors;
  bool ok() const { return errors.empty(); }
};

}  // namespace vmt::control::nc
