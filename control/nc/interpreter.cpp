// The interpreter's flow: block after block, the statements of a block around its words
// (interpreter_words.cpp), calls, returns, $-structures and loops, and the block counter.
#include "control/nc/interpreter.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string_view>

namespace vmt::control::nc {
namespace {

using Kind = Statement::Kind;

std::string Upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

// "GSP.nc" -> "GSP": programs are stored and called by name without extension.
std::string Stem(const std::string& name) { return Upper(name.substr(0, name.find('.'))); }

// MTC200's branches test the last computed @ value.
bool BranchTaken(Instruction branch, double r) {
  switch (branch) {
    case Instruction::kBra:
      return true;
    case Instruction::kBeq:
      return r == 0;
    case Instruction::kBne:
      return r != 0;
    case Instruction::kBgt:
      return r > 0;
    case Instruction::kBlt:
      return r < 0;
    case Instruction::kBge:
      return r >= 0;
    case Instruction::kBle:
      return r <= 0;
    default:
      return false;
  }
}

bool HasEffect(const PreparedBlock& b) {
  return b.motion != Motion::kNone || !b.aux.empty() || !b.events.empty() || b.dwell_s > 0 ||
         b.homing || b.set_position || b.repos || b.measuring || !b.instructions.empty() || b.end ||
         b.returned;
}

}  // namespace

int ModalGroupValue(const ModalState& m, char letter, int group, bool& known) {
  known = true;
  if (letter == 'G') {
    switch (group) {
      case 1:
        switch (m.motion) {
          case Motion::kThread:
            return 33;
          case Motion::kTapping:
            return 63;
          case Motion::kRigidTapping:
            return 64;
          default:
            return static_cast<int>(m.motion) - 1;  // 0..3
        }
      case 2:
        return GCode(m.plane);
      case 3:
        return m.incremental ? 91 : 90;
      case 4:
        return m.feed_per_revolution ? 95 : 94;
      case 5:
        return m.diameter ? 16 : 15;
      case 6:
        return m.zero_offset;
      case 7:
        return GCode(m.compensation);
      case 8:
        return GCode(m.tool_length);
      case 9:
        return m.low_lag ? 6 : 5;
      case 17:
        return GCode(m.transformation);
    }
  } else if (letter == 'M') {
    switch (group) {
      case 1:
        return m.spindle;
      case 5:
        return m.coolant;
    }
  }
  known = false;
  return 0;
}

Interpreter::Interpreter(std::vector<const Program*> programs, InterpreterConfig config)
    : programs_(std::move(programs)), config_(std::move(config)), modal_(config_.initial) {
  for (size_t i = 0; i < programs_.size(); ++i) by_name_.emplace(Stem(programs_[i]->name), i);
  position_.assign(config_.axes.size(), 0.0);
  var_cache_.per_program.resize(programs_.size());
  axis_cache_.resize(programs_.size());
  size_t stack = 1;
  for (const Program* p : programs_) stack = std::max<size_t>(stack, p->max_stack);
  stack_.assign(stack, 0.0);
}

namespace {

int32_t LabelBlock(const Program& p, const std::string& label) {
  const std::string bare = label.starts_with('.') ? label.substr(1) : label;
  for (const std::string& name : {bare, "." + bare}) {
    const uint32_t id = p.symbols.Find(name);
    if (auto it = p.labels.find(id); id != 0 && it != p.labels.end()) return it->second;
  }
  return -1;
}

}  // namespace

bool Interpreter::JumpTo(const std::string& label) {
  const int32_t block = LabelBlock(*programs_[0], label);
  if (block < 0) return false;
  current_ = 0;
  pc_ = block;
  calls_.clear();
  loops_.clear();
  ended_ = false;
  subroutine_ = false;
  reverse_part_ = false;
  Jumped();
  return true;
}

bool Interpreter::Reverse(ReverseLabel label) {
  const int32_t home = LabelBlock(*programs_[0], "HOME");
  if (home < 0) return false;
  calls_.clear();
  loops_.clear();
  ended_ = false;
  subroutine_ = false;
  // An error of the program is what the reverse program leaves it by (fast measurement 6.1).
  error_.reset();
  home_block_ = home;
  reverse_part_ = label.valid() && static_cast<size_t>(label.program) < programs_.size() &&
                  label.block >= 0 &&
                  static_cast<size_t>(label.block) < programs_[label.program]->blocks.size();
  current_ = reverse_part_ ? static_cast<uint32_t>(label.program) : 0;
  pc_ = reverse_part_ ? label.block : home;
  // The label brought the reverse here: a reverse during the reverse program goes to `.HOME`
  // unless the reverse program names another reverse vector itself.
  reverse_ = {};
  Jumped();
  return true;
}

void Interpreter::EndReversePart(int32_t& next) {
  reverse_part_ = false;
  current_ = 0;
  next = home_block_;
}

void Interpreter::Jumped() {
  count_line_ = kJumped;
  count_events_ = 0;
  while_back_ = false;
  reread_for_ = -1;
  idle_steps_ = 0;
}

bool Interpreter::StartAt(uint32_t file_offset) {
  if (started_ || programs_.empty()) return false;
  const Program& p = *programs_[0];
  // The shortened program's first line: the first that starts at or after the offset.
  const auto line = std::lower_bound(p.line_starts.begin(), p.line_starts.end(), file_offset);
  if (line == p.line_starts.end()) return false;
  const auto entry_line = static_cast<uint32_t>(line - p.line_starts.begin()) + 1;
  const auto block = std::lower_bound(p.blocks.begin(), p.blocks.end(), entry_line,
                                      [](const Block& b, uint32_t l) { return b.pos.line < l; });
  if (block == p.blocks.end()) return false;
  current_ = 0;
  pc_ = static_cast<int32_t>(block - p.blocks.begin());
  count_ = 0;
  count_line_ = entry_line - 1;
  return true;
}

int Interpreter::FindSubroutine(const std::string& label) const {
  if (programs_.empty()) return -1;
  if (LabelBlock(*programs_[0], label) >= 0) return 0;
  if (auto it = by_name_.find("99");
      it != by_name_.end() && LabelBlock(*programs_[it->second], label) >= 0)
    return static_cast<int>(it->second);
  for (size_t i = 1; i < programs_.size(); ++i)
    if (LabelBlock(*programs_[i], label) >= 0) return static_cast<int>(i);
  return -1;
}

bool Interpreter::RunSubroutine(uint32_t program, const std::string& label) {
  if (program >= programs_.size()) return false;
  const int32_t block = LabelBlock(*programs_[program], label);
  if (block < 0) return false;
  current_ = program;
  pc_ = block;
  calls_.clear();
  loops_.clear();
  ended_ = false;
  subroutine_ = true;
  reverse_part_ = false;
  Jumped();
  return true;
}

const std::string& Interpreter::ErrorFile() const { return programs_[error_program_]->files[0]; }

double Interpreter::Variable(const std::string& name) const {
  auto it = variables_.find(Upper(name));
  return it == variables_.end() ? 0.0 : it->second;
}

void Interpreter::SetVariable(const std::string& name, double value) {
  variables_[Upper(name)] = value;
}

void Interpreter::SetVariables(std::map<std::string, double> variables) {
  variables_ = std::move(variables);
  // The cache points into the map's old nodes.
  for (std::vector<double*>& cache : var_cache_.per_program) cache.clear();
}

bool Interpreter::Fail(uint32_t offset, std::string message) {
  if (!error_) {
    error_ = Diagnostic{program().PosAt(offset), std::move(message)};
    error_program_ = current_;
  }
  return false;
}

void Interpreter::Fault(uint32_t rank, uint32_t offset, std::string message) {
  if (fault_ && rank >= fault_rank_) return;
  fault_ = true;
  fault_rank_ = rank;
  fault_offset_ = offset;
  fault_message_ = std::move(message);
}

// Inline: on the decode benchmark's short blocks a call here cost a tenth of the time.
[[gnu::always_inline]] inline void Interpreter::Begin(PreparedBlock& out, uint32_t program,
                                                      int32_t block) const {
  out.program = program;
  out.block = block;
  out.motion = Motion::kNone;
  // Not `out.target = position_`: GCC makes that a call when Next() grows, a fifth of the time
  // the decode benchmark spends per block outside the block's own work.
  if (out.target.size() != position_.size()) [[unlikely]]
    out.target.resize(position_.size());
  std::copy(position_.begin(), position_.end(), out.target.begin());
  out.programmed = 0;
  out.has_centre = false;
  out.radius = 0;
  out.has_effective_distance = 0;
  out.aux.clear();
  out.instructions.clear();
  out.calls.clear();
  out.events.clear();
  out.dwell_s = 0;
  out.homing = out.set_position = out.repos = out.measuring = out.end = false;
  out.feed_programmed = out.returned = out.fictive = false;
  out.search_locked = search_lock_;
  out.distance_command = DistanceCommand::kNone;
  out.reverse = reverse_;
}

[[gnu::always_inline]] inline bool Interpreter::Idle(uint32_t program, int32_t block) {
  if (++idle_steps_ <= config_.max_steps_per_block) [[likely]]
    return true;
  return EndlessLoop(program, block);
}

bool Interpreter::EndlessLoop(uint32_t program, int32_t block) {
  // The block's own program: a call in the block has already made another one current.
  if (!error_) {
    error_ = Diagnostic{
        programs_[program]->blocks[block].pos,
        "no block with an effect after " + std::to_string(idle_steps_) + " blocks: endless loop?"};
    error_program_ = program;
  }
  return false;
}

// The rare places: one inlined copy of Begin keeps the hot loop's copy of the target inline.
[[gnu::noinline]] void Interpreter::BeginCold(PreparedBlock& out, uint32_t program,
                                              int32_t block) const {
  Begin(out, program, block);
}

bool Interpreter::Next(PreparedBlock& out, const std::function<bool(int)>& events,
                       const DataAccess& data) {
  call_event_ = &events;
  call_data_ = &data;
  const bool more = Next(out);
  call_event_ = nullptr;
  call_data_ = nullptr;
  return more;
}

bool Interpreter::Next(PreparedBlock& out) {
  started_ = true;
  if (reread_for_ >= 0 && !ended_ && !error_) [[unlikely]] {
    // The $ENDFOR handed out last time looped back: now the $FOR line it re-read
    // (SetEveryBlock).
    const int32_t head = reread_for_;
    reread_for_ = -1;
    BeginCold(out, reread_program_, head);
    out.block_count = reread_count_;
    out.modal = modal_;
    return Idle(reread_program_, head);
  }
  while (!ended_ && !error_) {
    const Program& p = program();
    if (pc_ >= static_cast<int32_t>(p.blocks.size())) {
      // The end of a file: an ISG subprogram returns, a main program ends.
      if (!calls_.empty()) {
        current_ = calls_.back().program;
        pc_ = calls_.back().return_block;
        calls_.pop_back();
        count_line_ = kJumped;
        continue;
      }
      if (reverse_part_) [[unlikely]] {  // the part at the reverse label ends with its file
        EndReversePart(pc_);
        count_line_ = kJumped;
        continue;
      }
      ended_ = true;
      idle_steps_ = 0;
      out = PreparedBlock{};
      out.program = current_;
      out.end = true;
      out.target = position_;
      out.modal = modal_;
      out.block_count = count_;
      out.search_locked = search_lock_;
      out.reverse = reverse_;
      return true;
    }
    const int32_t here = pc_;
    // The part at the reverse label has reached `.HOME` in its flow: from here on the reverse
    // program is `.HOME`'s, whose own RET ends it.
    if (reverse_part_ && current_ == 0 && here == home_block_) [[unlikely]]
      reverse_part_ = false;
    int32_t next = pc_ + 1;
    const uint32_t file = current_;
    Begin(out, file, here);
    if (!Execute(p.blocks[here], out, next)) return false;
    ++executed_;
    pc_ = next;
    out.modal = modal_;
    // Counted after the block (nothing in it reads the count): fewer values live across it.
    const uint32_t line = p.blocks[here].pos.line;
    const uint32_t count_before = count_;
    count_ += line > count_line_ ? line - count_line_ : 1;
    out.block_count = count_;
    count_line_ = next == here + 1 && current_ == file ? line : kJumped;
    bool counted = true;
    if (count_events_) [[unlikely]] {
      if (count_events_ & (kForBack | kWhileExit)) {
        count_line_ = p.blocks[loop_line_block_].pos.line;
      }
      if (count_events_ & kForBack) {
        out.block_count = count_before;
        count_ = count_before + 1;
        if (every_block_ && (HasEffect(out) || current_ != file)) {
          reread_program_ = file, reread_for_ = loop_line_block_, reread_count_ = count_;
        } else if (every_block_) {
          BeginCold(out, file, loop_line_block_);
          out.block_count = count_;
          out.modal = modal_;
        }
      }
      if (count_events_ & kWhileExit) {
        out.block_count = count_ = count_before;
        counted = false;
      }
      if (count_events_ & kEnteredFile) {
        count_line_ = 0;
      }
      count_events_ = 0;
    }
    if (HasEffect(out)) {
      idle_steps_ = 0;
      for (size_t a = 0; a < position_.size(); ++a)
        if (out.programmed >> a & 1) position_[a] = out.target[a];
      if (out.end) ended_ = true, reread_for_ = -1;
      return true;
    }
    if (!Idle(file, here)) return false;
    if (every_block_ && counted) return true;
  }
  return false;
}

bool Interpreter::Execute(const Block& block, PreparedBlock& out, int32_t& next) {
  const Program& p = program();
  const auto statements = p.Statements(block);
  const int32_t here = static_cast<int32_t>(&block - p.blocks.data());
  // Source order within a block: computations first, then the words (their values may use
  // them), then the flow of control (G77 X0 F2000 RTS moves, then returns).
  for (const Statement& st : statements)
    if (st.kind == Kind::kAssign || st.kind == Kind::kInstruction || st.kind == Kind::kHashCommand)
      if (!Statement_(st, here, out, next)) return false;
  if (!Words(block, out)) return false;
  for (const Statement& st : statements)
    if (st.kind != Kind::kAssign && st.kind != Kind::kInstruction && st.kind != Kind::kHashCommand)
      if (!Statement_(st, here, out, next)) return false;
  return true;
}

bool Interpreter::Statement_(const Statement& st, int32_t block, PreparedBlock& out,
                             int32_t& next) {
  eval_failed_ = false;
  switch (st.kind) {
    case Kind::kAssign:
      return Assign(st);
    case Kind::kBranch:
      if (BranchTaken(st.instruction, last_result_)) next = st.jump;
      return true;
    case Kind::kEventBranch: {
      const int event = static_cast<int>(Eval(st.value));
      if (!EvalSucceeded()) return false;
      const std::function<bool(int)>& source = events();
      const bool set = (source && source(event));
      if ((st.instruction == Instruction::kBes) == set) next = st.jump;
      return true;
    }
    case Kind::kCall:
      return CallSubprogram(st, next);
    case Kind::kReturn:
      return Return(st, block, out, next);
    case Kind::kReverse:
      reverse_ = {static_cast<int32_t>(current_), st.jump};
      out.reverse = reverse_;
      return true;
    case Kind::kInstruction:
      return InstructionStatement(st, out);
    case Kind::kHashCommand:
      return HashCommand(st, out);
    case Kind::kIf:
    case Kind::kElseIf:
    case Kind::kElse:
    case Kind::kEndIf:
      return IfStructure(st, next);
    case Kind::kFor:
    case Kind::kEndFor:
    case Kind::kWhile:
    case Kind::kEndWhile:
      return LoopStructure(st, block, next);
    case Kind::kProgramEnd:
      out.end = true;
      return true;
  }
  return true;
}

// The statement kinds below are inlined into Statement_, as the one switch they were: the
// executed loops of nc_decode_bench run through them for every block.
[[gnu::always_inline]] inline bool Interpreter::EvalSucceeded() {
  return eval_failed_ ? Fail(eval_fail_offset_, eval_fail_message_) : true;
}

[[gnu::always_inline]] inline bool Interpreter::Assign(const Statement& st) {
  const Program& p = program();
  const double v = Eval(st.value);
  if (!EvalSucceeded()) return false;
  if (st.data != kNoExpr) {
    std::vector<InstructionArg> args;
    if (!EvalArguments(st.data, args)) return EvalSucceeded();
    const DataAccess& access = data();
    if (!access.write)
      return Fail(st.pos.offset,
                  "writing " + p.symbols.Name(st.name) + "(...) data is not available here");
    std::string error = access.write(st.instruction, args, v);
    if (!error.empty()) return Fail(st.pos.offset, std::move(error));
    last_result_ = v;
    return true;
  }
  Var(st.name) = v;
  last_result_ = v;
  return true;
}

[[gnu::always_inline]] inline bool Interpreter::CallSubprogram(const Statement& st, int32_t& next) {
  const Program& p = program();
  if (static_cast<int>(calls_.size()) >= config_.max_call_depth)
    return Fail(st.pos.offset,
                "subprogram calls nested deeper than " + std::to_string(config_.max_call_depth));
  if (p.dialect == Dialect::kMtc200) {
    calls_.push_back({current_, next});
    next = st.jump;
    return true;
  }
  const std::string& target = p.symbols.Name(st.target);
  const auto it = by_name_.find(Stem(target));
  if (it == by_name_.end())
    return Fail(st.pos.offset, "subprogram " + target + " is not in the program store");
  calls_.push_back({current_, next});
  current_ = it->second;
  next = 0;
  count_events_ |= kEnteredFile;
  return true;
}

[[gnu::always_inline]] inline bool Interpreter::Return(const Statement& st, int32_t block,
                                                       PreparedBlock& out, int32_t& next) {
  if (!calls_.empty()) {
    current_ = calls_.back().program;
    next = calls_.back().return_block;
    calls_.pop_back();
    return true;
  }
  if (reverse_part_) {
    // The part at the reverse label is over: the NC goes on at `.HOME` (REPOS manual 4.1).
    // RET too: there it would end the program before the reverse program has run.
    EndReversePart(next);
    return true;
  }
  if (subroutine_) {
    // REPOS manual 4.1: only RTS returns from a subroutine run on its own and keeps the
    // state of the program it serves; RET is a program end, which would reset that state.
    if (st.instruction == Instruction::kRet)
      return Fail(st.pos.offset,
                  "RET ends a program: a subroutine run on its own (.REPOS) ends with RTS");
    out.returned = true;  // the subroutine run on its own is over (RunSubroutine)
    ended_ = true;
    next = block;
    return true;
  }
  if (st.instruction == Instruction::kRts) return Fail(st.pos.offset, "RTS without JSR");
  out.end = true;  // RET: end of the main program
  return true;
}

[[gnu::always_inline]] inline bool Interpreter::InstructionStatement(const Statement& st,
                                                                     PreparedBlock& out) {
  const Program& p = program();
  // SE n / RE n: set or reset event n (MTC200; fast-measurement 4.1: SE 30, RE 29).
  const bool set = st.instruction == Instruction::kSe;
  if ((set || st.instruction == Instruction::kRe) && st.value != kNoExpr) {
    const double n = Eval(st.value);
    if (eval_failed_) return Fail(eval_fail_offset_, eval_fail_message_);
    if (n < 0 || n > 999 || n != std::floor(n))
      return Fail(st.pos.offset, p.symbols.Name(st.name) + ": event number " + std::to_string(n) +
                                     " is not in 0..999");
    out.events.emplace_back(static_cast<int>(n), set);
    return true;
  }
  const auto index = static_cast<uint32_t>(&st - p.statements.data());
  out.instructions.push_back(index);
  if (IsMeasuringCall(st.instruction)) {
    // Evaluated here, where the program's variables have the values the call sees.
    InstructionCall call{st.instruction, {}, index};
    if (st.value != kNoExpr && !EvalArguments(st.value, call.args))
      return Fail(eval_fail_offset_, eval_fail_message_);
    out.calls.push_back(std::move(call));
  }
  return true;
}

[[gnu::always_inline]] inline bool Interpreter::HashCommand(const Statement& st,
                                                            PreparedBlock& out) {
  const Program& p = program();
  // They stay instructions as well: the channel sees the block in any case.
  out.instructions.push_back(static_cast<uint32_t>(&st - p.statements.data()));
  const SearchCommand c = ReadSearchCommand(p.texts[st.text]);
  switch (c.kind) {
    // Both commands' own blocks belong to the region (manual 6, example 1: "im Bereich der
    // NC-Sätze N40-N100", N40 LOCKED and N100 RELEASED): a LOCKED block is locked, a
    // RELEASED one keeps the state before it. A second LOCKED changes nothing: the first
    // RELEASED ends the region (example 2).
    case SearchCommand::Kind::kLock:
      search_lock_ = out.search_locked = true;
      break;
    case SearchCommand::Kind::kRelease:
      search_lock_ = false;
      break;
    case SearchCommand::Kind::kDistance:
      out.distance_command = c.distance;
      break;
    case SearchCommand::Kind::kInvalid:  // the parser reports it; a program built by hand
      return Fail(st.pos.offset, c.message);
    case SearchCommand::Kind::kOther:
      break;
  }
  return true;
}

[[gnu::always_inline]] inline bool Interpreter::IfStructure(const Statement& st, int32_t& next) {
  const Program& p = program();
  // The statement that opens or continues a $-structure in a block.
  auto structure_at = [&](int32_t b) -> const Statement* {
    for (const Statement& s : p.Statements(p.blocks[b]))
      if (s.kind >= Kind::kIf && s.kind <= Kind::kEndWhile) return &s;
    return nullptr;
  };
  switch (st.kind) {
    case Kind::kIf:
    case Kind::kElseIf: {
      if (st.kind == Kind::kElseIf && !entering_) {
        // Reached from a branch that ran: go to the $ENDIF at the end of the chain.
        int32_t j = st.jump;
        for (const Statement* s = structure_at(j); s && s->kind != Kind::kEndIf;
             s = structure_at(j))
          j = s->jump;
        next = j;
        return true;
      }
      entering_ = false;
      const bool condition = Eval(st.value) != 0;
      if (!EvalSucceeded()) return false;
      if (!condition) {
        next = st.jump;
        entering_ = true;
      }
      return true;
    }
    case Kind::kElse:
      if (!entering_) next = st.jump;
      entering_ = false;
      return true;
    default:  // $ENDIF
      entering_ = false;
      return true;
  }
}

[[gnu::always_inline]] inline bool Interpreter::LoopStructure(const Statement& st, int32_t block,
                                                              int32_t& next) {
  switch (st.kind) {
    case Kind::kFor: {
      const double start = Eval(st.value), limit = Eval(st.limit);
      const double step = st.step == kNoExpr ? 1.0 : Eval(st.step);
      if (!EvalSucceeded()) return false;
      if (step == 0) return Fail(st.pos.offset, "$FOR with step 0 never ends");
      Var(st.name) = start;
      if (step > 0 ? start > limit : start < limit)
        next = st.jump + 1;
      else
        loops_.push_back({current_, block, st.name, limit, step});
      return true;
    }
    case Kind::kEndFor: {
      if (loops_.empty() || loops_.back().head != st.jump || loops_.back().program != current_)
        return Fail(st.pos.offset, "$ENDFOR reached without its $FOR");
      Loop& loop = loops_.back();
      double& v = Var(loop.variable);
      v += loop.step;
      if (loop.step > 0 ? v <= loop.limit : v >= loop.limit) {
        next = loop.head + 1;
        count_events_ |= kForBack;
        loop_line_block_ = loop.head;
      } else {
        loops_.pop_back();
      }
      return true;
    }
    case Kind::kWhile: {
      const bool back = while_back_;
      while_back_ = false;
      const bool condition = Eval(st.value) != 0;
      if (!EvalSucceeded()) return false;
      if (!condition) {
        next = st.jump + 1;
        if (back) {
          count_events_ |= kWhileExit;
          loop_line_block_ = st.jump;
        }
      }
      return true;
    }
    default:  // $ENDWHILE
      next = st.jump;
      while_back_ = true;
      return true;
  }
}

}  // namespace vmt::control::nc
