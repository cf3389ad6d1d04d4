#include "control/nc/program_check.hpp"

namespace vmt::control::nc {
namespace {

using Kind = Statement::Kind;

struct Open {
  int32_t block;
  uint32_t statement;  ///< index into Program::statements
  Kind kind;
};

const char* Closer(Kind k) {
  switch (k) {
    case Kind::kIf:
    case Kind::kElseIf:
    case Kind::kElse:
      return "$ENDIF";
    case Kind::kFor:
      return "$ENDFOR";
    default:
      return "$ENDWHILE";
  }
}

}  // namespace

void CheckProgram(Program& p, std::vector<Diagnostic>& errors) {
  // Labels first: a branch may jump forward.
  p.labels.clear();
  for (size_t b = 0; b < p.blocks.size(); ++b) {
    const Block& block = p.blocks[b];
    if (block.label == 0 || p.dialect == Dialect::kIsg) continue;
    if (!p.labels.emplace(block.label, static_cast<int32_t>(b)).second) {
      const Block& first = p.blocks[p.labels[block.label]];
      errors.push_back({block.pos, "label ." + p.symbols.Name(block.label) +
                                       " is already defined on line " +
                                       std::to_string(first.pos.line)});
    }
  }

  // Fast measurement 4.4 CAUTION: the control writes the reverse vectors of MOVE / PROBE as
  // `rev .*$...` and reserves their beginning. vmt reads `REV .LABEL` as the statement (the
  // user's reverse vectors take that form), and since the manual leaves open whether the
  // reserved letters are also the labels', keeps labels beginning with REV for the control in a
  // program whose MOVE / PROBE make reverse vectors (the reverse program would branch into the
  // user's block).
  if (p.dialect == Dialect::kMtc200) {
    bool reverse_vectors = false;
    for (const Statement& st : p.statements)
      if (st.kind == Kind::kInstruction &&
          (st.instruction == Instruction::kMove || st.instruction == Instruction::kProbe))
        reverse_vectors = true;
    for (size_t b = 0; b < p.blocks.size() && reverse_vectors; ++b) {
      const Block& block = p.blocks[b];
      if (block.label != 0 && p.symbols.Name(block.label).starts_with("REV"))
        errors.push_back({block.pos, "label ." + p.symbols.Name(block.label) +
                                         ": labels beginning with REV are the reverse vectors' "
                                         "(fast measurement 4.4)"});
    }
  }

  std::vector<Open> open;
  for (size_t b = 0; b < p.blocks.size(); ++b) {
    const Block& block = p.blocks[b];
    for (uint32_t i = block.first_statement; i < block.first_statement + block.num_statements;
         ++i) {
      Statement& st = p.statements[i];
      switch (st.kind) {
        case Kind::kBranch:
        case Kind::kEventBranch:
        case Kind::kCall:
          if (p.dialect == Dialect::kIsg) break;  // L name: a subprogram of the program store
          if (auto it = p.labels.find(st.target); it != p.labels.end())
            st.jump = it->second;
          else
            errors.push_back({st.pos, "label ." + p.symbols.Name(st.target) + " is not defined"});
          break;
        case Kind::kReverse:
          // A reverse vector names a label of its own program, as a branch does.
          if (auto it = p.labels.find(st.target); it != p.labels.end())
            st.jump = it->second;
          else
            errors.push_back({st.pos, "REV: the reverse label ." + p.symbols.Name(st.target) +
                                          " is not defined"});
          break;
        case Kind::kIf:
        case Kind::kFor:
        case Kind::kWhile:
          open.push_back({static_cast<int32_t>(b), i, st.kind});
          break;
        case Kind::kElseIf:
        case Kind::kElse: {
          const bool ok =
              !open.empty() && (open.back().kind == Kind::kIf || open.back().kind == Kind::kElseIf);
          if (!ok) {
            errors.push_back({st.pos, std::string(st.kind == Kind::kElse ? "$ELSE" : "$ELSEIF") +
                                          " without $IF"});
            break;
          }
          // The previous branch of the $IF jumps here when its condition fails.
          Statement& prev = p.statements[open.back().statement];
          prev.jump = static_cast<int32_t>(b);
          open.back() = {static_cast<int32_t>(b), i, st.kind};
          break;
        }
        case Kind::kEndIf:
        case Kind::kEndFor:
        case Kind::kEndWhile: {
          const Kind want = st.kind == Kind::kEndIf    ? Kind::kIf
                            : st.kind == Kind::kEndFor ? Kind::kFor
                                                       : Kind::kWhile;
          const bool matches =
              !open.empty() && (open.back().kind == want ||
                                (want == Kind::kIf && (open.back().kind == Kind::kElseIf ||
                                                       open.back().kind == Kind::kElse)));
          if (!matches) {
            const char* name = st.kind == Kind::kEndIf    ? "$ENDIF"
                               : st.kind == Kind::kEndFor ? "$ENDFOR"
                                                          : "$ENDWHILE";
            std::string msg = std::string(name) + " without its opening statement";
            if (!open.empty())
              msg += " (line " + std::to_string(p.blocks[open.back().block].pos.line) +
                     " expects " + Closer(open.back().kind) + ")";
            errors.push_back({st.pos, msg});
            break;
          }
          // Opening statement jumps past the end; the end jumps back to a loop's head.
          Statement& head = p.statements[open.back().statement];
          head.jump = static_cast<int32_t>(b);
          st.jump = open.back().block;
          open.pop_back();
          break;
        }
        default:
          break;
      }
    }
  }
  for (const Open& o : open) {
    const Statement& st = p.statements[o.statement];
    errors.push_back({st.pos, std::string("missing ") + Closer(o.kind) + " for this statement"});
  }
}

}  // namespace vmt::control::nc
