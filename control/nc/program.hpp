#pragma once
// The one block representation both dialect front ends produce (DESIGN.md control/nc): a program
// is a list of blocks with their source positions; a block holds address words (G01, X-30,
// S1=0, RX50, F2000) and statements (assignments, branches, calls, instructions, #-commands,
// structured control). Expressions live in one arena per program so that decoding a million
// blocks allocates per block, not per node.

#include <cstdint>
#include <deque>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

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
};

using ExprId = int32_t;  ///< index into Program::exprs; -1 = none
inline constexpr ExprId kNoExpr = -1;

struct Expr {
  enum class Op : uint8_t {
    kNumber,    ///< number
    kVariable,  ///< name: "@100" (MTC200), "P1", "V.L.DIST" (ISG); name 0 = omitted argument
    kCall,      ///< name(args...): G(2), M(5), SIN[30], TLD(1,2)
    kNeg,
    kNot,
    kAdd,
    kSub,
    kMul,
    kDiv,
    kMod,
    kPow,
    kEq,
    kNe,
    kLt,
    kLe,
    kGt,
    kGe,
    kAnd,
    kOr,
    kXor,
  };
  // 32 bytes: expression-heavy programs are mostly these nodes.
  double number = 0;
  uint32_t name = 0;
  ExprId lhs = kNoExpr, rhs = kNoExpr;  ///< operands; for kCall: lhs = first argument
  ExprId next = kNoExpr;                ///< next argument of a call
  uint32_t offset = 0;                  ///< in the file; Program::PosAt gives line and column
  Op op = Op::kNumber;
};

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
  };
  Kind kind = Kind::kInstruction;
  uint32_t name = 0;       ///< mnemonic, variable or instruction name
  uint32_t target = 0;     ///< label or subprogram name
  ExprId value = kNoExpr;  ///< assigned value, condition, event, or first argument (args chain)
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
  std::vector<Expr> exprs;
  std::vector<std::string> texts;  ///< #-command texts (kept out of Statement: it stays small)
  Symbols symbols;
  std::map<uint32_t, int32_t> labels;  ///< label -> block index
  std::vector<uint32_t> line_starts;   ///< file offset of each line, for PosAt

  /// Line and column of a file offset (words and expressions keep only the offset).
  SourcePos PosAt(uint32_t offset) const;

  std::span<const Word> Words(const Block& b) const {
    return {words.data() + b.first_word, b.num_words};
  }
  std::span<const Statement> Statements(const Block& b) const {
    return {statements.data() + b.first_statement, b.num_statements};
  }
};

struct ParseResult {
  Program program;
  std::vector<Diagnostic> errors;
  bool ok() const { return errors.empty(); }
};

}  // namespace vmt::control::nc
