#pragma once
// The convert phase of the NC pipeline: executes a parsed program's control flow (variables,
// branches, events, subroutines, $-structures, loops) and its words, and hands the channel one
// PreparedBlock per block that does something (moves, switches, waits). Program coordinates;
// the channel applies zero offsets, tool corrections and interpolation.
//
// Errors at run time (an undefined subprogram, division by zero, a loop without end) stop the
// program with a Diagnostic at the offending place, as the manuals' error state does.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "control/nc/program.hpp"

namespace vmt::control::nc {

/// Modal group 1. G33, G63 and G64 are spindle-synchronous moves (vmt's reading of the
/// manuals, which name them but give no syntax): a straight move of the programmed linear axes
/// whose lead, mm per spindle revolution along the axis that travels furthest, is
/// ModalState::lead. kThread (G33) follows the spindle's actual position; kTapping (G63, with
/// a compensating chuck) runs at lead x S; kRigidTapping (G64, without) interpolates the
/// spindle's position with the axes.
enum class Motion : uint8_t {
  kNone,
  kRapid,
  kLinear,
  kArcCw,
  kArcCcw,
  kThread,
  kTapping,
  kRigidTapping
};

/// G33, G63 or G64.
inline bool SpindleSynchronous(Motion m) {
  return m == Motion::kThread || m == Motion::kTapping || m == Motion::kRigidTapping;
}

// The modal G groups. Each value is its G number, which G(n) reads and the REPOS screen shows.

/// G group 2, the plane of arcs and of the tool nose radius compensation (a lathe works in G18).
enum class Plane : uint8_t { kXY = 17, kZX = 18, kYZ = 19 };
/// G group 7, tool nose radius compensation: off, tool left or right of the contour.
enum class Compensation : uint8_t { kOff = 40, kLeft = 41, kRight = 42 };
/// G group 8, tool length correction: off, added, subtracted.
enum class ToolLength : uint8_t { kOff = 47, kAdd = 48, kSubtract = 49 };
/// G group 17, coordinate transformation (control/nc/coordinate_transformation.hpp): off, the end
/// face (X1/Y1 in the face), the cylinder surface (Y1 the arc length).
enum class Transformation : uint8_t { kOff = 30, kFace = 31, kCylinder = 32 };

inline int GCode(Plane p) { return static_cast<int>(p); }
inline int GCode(Compensation c) { return static_cast<int>(c); }
inline int GCode(ToolLength t) { return static_cast<int>(t); }
inline int GCode(Transformation t) { return static_cast<int>(t); }

/// Modal state as programs set it. Group numbers for G(n) reads are ModalGroup.
struct ModalState {
  Motion motion = Motion::kRapid;    ///< G00 G01 G02 G03 G33 G63 G64
  Plane plane = Plane::kZX;          ///< G17 G18 G19
  bool incremental = false;          ///< G91 | G90
  bool feed_per_revolution = false;  ///< G95 | G94
  bool diameter = false;             ///< G16 diameter | G15 radius programming of X (MTC200)
  int zero_offset = 53;              ///< G53 .. G59
  Compensation compensation = Compensation::kOff;  ///< G40 G41 G42
  ToolLength tool_length = ToolLength::kOff;  ///< G47 G48 G49
  bool low_lag = false;              ///< G06 (MTC200)
  Transformation transformation = Transformation::kOff;  ///< G30 G31 G32
  double cylinder_radius = 0;  ///< G32: X (radius, mm) when G32 became active
  int spindle = 5;                   ///< M3 M4 M5 M19
  int coolant = 9;                   ///< M7 M8 M9
  double feed = 0;                   ///< F, mm/min or mm/rev
  /// Lead of G33/G63/G64, mm per spindle revolution: MTC200 F while one of them is active,
  /// ISG K. Kept apart from `feed`, so a later G01 finds its feed undisturbed; modal like F.
  double lead = 0;
  double spindle_speed = 0;      ///< S, rpm
  int tool = 0, correction = 0;  ///< T, D
};

/// G(n) / M(n) group numbers (MTC200 data access to modal state).
int ModalGroupValue(const ModalState& m, char letter, int group, bool& known);

struct AuxFunction {
  char letter;  ///< M S T D H Q
  int index;    ///< address index: S1 -> 1, S -> 0
  double value;
};

/// One argument of a call as the program wrote it: omitted (SETTING (X, Z, , 18 ...), an
/// omitted control variable of MTD(105,,1,13)), a bare name (an axis designation: SETTING's
/// A..C, PROBE's F), or a value.
struct InstructionArg {
  enum class Kind : uint8_t { kOmitted, kName, kValue };
  Kind kind = Kind::kOmitted;
  double value = 0;
  std::string name;
};

/// An instruction of the fast-measurement manual with its arguments evaluated where the program
/// stands when the interpreter executes the block (section 2: SETTING, SAVE, MOVE, PROBE,
/// COMPARE, CORRECTION, RESTORE).
struct InstructionCall {
  Instruction instruction = Instruction::kNone;
  std::vector<InstructionArg> args;
  uint32_t statement = 0;  ///< Program::statements index: the source position
};

/// A reverse vector: the label a reverse (the reverse program start) branches to before `.HOME`.
/// `REV .LABEL` makes it valid from its block on, in the flow of the program, until the next REV.
struct ReverseLabel {
  int32_t program = -1;  ///< index into the interpreter's program list; -1: none valid
  int32_t block = -1;    ///< the labelled block
  bool valid() const { return program >= 0; }
};

struct PreparedBlock {
  uint32_t program = 0;  ///< index into the interpreter's program list
  int32_t block = -1;    ///< Program::blocks index: the source position
  Motion motion = Motion::kNone;
  std::vector<double> target;    ///< per channel axis, absolute program coordinates
  uint64_t programmed = 0;       ///< bit per channel axis written in this block
  double centre[3] = {0, 0, 0};  ///< I J K (relative to the start point)
  bool has_centre = false;
  double radius = 0;                         ///< R (arc by radius)
  double effective_distance[3] = {0, 0, 0};  ///< RX RY RZ: C-axis path velocity (C-axis manual 1.2)
  uint8_t has_effective_distance = 0;        ///< bit 0 RX, 1 RY, 2 RZ
  std::vector<AuxFunction> aux;
  double dwell_s = 0;            ///< G04
  bool homing = false;           ///< G74: the programmed axes home
  bool set_position = false;     ///< G92: the programmed values become the current position
  bool repos = false;            ///< G77: return the programmed axes to the interruption point
  bool measuring = false;        ///< G100: measuring move (ISG)
  bool feed_programmed = false;  ///< an F word in this block (G77 needs one, REPOS manual 4.2)
  /// X1/Y1 of G31/G32 programmed: X and C (set in target and programmed) move on a straight
  /// line of the fictive Cartesian plane (G77: return along one, REPOS manual 5.2).
  bool fictive = false;
  /// RTS at the top of a subroutine run on its own (RunSubroutine): the run is over.
  bool returned = false;
  std::vector<uint32_t> instructions;  ///< MTP, MRY, SETTING(...), #-commands: Program::statements
  std::vector<InstructionCall> calls;  ///< the measuring instructions among them, evaluated
  std::vector<std::pair<int, bool>> events;  ///< SE n (true) / RE n (false), in block order
  bool end = false;                          ///< M30 / M02 / RET of the main program
  ReverseLabel reverse;                      ///< the reverse vector valid in this block
  ModalState modal;                          ///< after the block
  /// Block counter of the block's line (TwinCAT block search manual 3.2 "Satzzähler", 5.6
  /// block_count_r): every line the decoder reads since program start, comment and blank
  /// lines, loop passes and called subprograms' lines included. See Interpreter::block_count.
  uint32_t block_count = 0;
  /// The block lies in a region #BLOCKSEARCH LOCKED ... RELEASED (manual 6): block search must
  /// not continue here. Subprograms called inside the region are locked too.
  bool search_locked = false;
  DistanceCommand distance_command = DistanceCommand::kNone;  ///< #DISTANCE PROG START (4.1.2)
};

/// MTC200 data access (TLD(...) tool data, OTD(...) zero offsets, MTD(...) machine data pages):
/// read in expressions, written by assignments `TLD(...) = value`. The channel provides it. Each
/// returns "" or an error text, which stops the program at the call.
struct DataAccess {
  std::function<std::string(Instruction data, const std::vector<InstructionArg>& args,
                            double& value)>
      read;
  std::function<std::string(Instruction data, const std::vector<InstructionArg>& args,
                            double value)>
      write;
};

struct InterpreterConfig {
  std::vector<std::string> axes = {"X", "Z", "C"};  ///< the channel's axis names
  ModalState initial;
  int max_call_depth = 16;
  int64_t max_steps_per_block = 1000000;  ///< statements run without a block: an endless loop
};

class Interpreter {
 public:
  /// Programs by name (upper case, without extension), the first is the main program.
  Interpreter(std::vector<const Program*> programs, InterpreterConfig config);

  /// Events (BES/BEC, E in the manuals) come from the machine and the PLC; SE/RE of the
  /// program travel in PreparedBlock::events to the channel, which sets them.
  void SetEventSource(std::function<bool(int)> source) { event_ = std::move(source); }
  /// TLD/OTD/MTD go here; without it they are an error at run time.
  void SetDataAccess(DataAccess access) { data_ = std::move(access); }

  /// Executes up to the next block with an effect (with SetEveryBlock(true): the next block).
  /// False at the end or after an error.
  bool Next(PreparedBlock& out);
  /// Next() with the events and data access of this call in place of the ones set: an owner
  /// that is copied (the channel) hands in its own each time, so that the interpreter holds
  /// nothing that leads back into it and copies as a plain value.
  bool Next(PreparedBlock& out, const std::function<bool(int)>& events, const DataAccess& data);
  /// While on, Next() hands out every line the block counter counts, also blocks without an
  /// effect (P1 = 0, $FOR, a block with only an N number, #BLOCKSEARCH ...): block search
  /// may continue at any of them (manual 10: N100 P100 = 1). A $ENDFOR that loops back is not
  /// counted: the $FOR line it re-reads is handed out instead (a block of that line, nothing
  /// executed); a $WHILE whose condition fails after a loop-back is not counted nor handed
  /// out. Blocks with an effect are handed out either way. max_steps_per_block still counts
  /// the blocks without an effect in a row, so an endless loop is still an error.
  void SetEveryBlock(bool on) { every_block_ = on; }
  /// The block counter now: the count of the last line counted (PreparedBlock::block_count).
  uint32_t block_count() const { return count_; }
  /// The entry point of manual 3.6 (mc_command_file_offset_w): call before the first Next().
  /// The main program starts at the first block whose line starts at or after `file_offset`
  /// in its file, as if the program were shortened by that offset ("Die Auswertung beginnt wie
  /// bei einem um den Dateioffset verkürzten Programm"): nothing before it runs, and the
  /// block counter counts lines from the line that starts at or after the offset as line 1
  /// (an entry at a block's line gives that block the count 1). False, and nothing changes,
  /// if no block starts at or after the offset or the program has already run.
  bool StartAt(uint32_t file_offset);

  const std::optional<Diagnostic>& error() const { return error_; }
  const std::string& ErrorFile() const;
  const ModalState& modal() const { return modal_; }
  const std::vector<double>& position() const { return position_; }
  /// Where the axes stand before the first block (incremental moves start from here).
  void SetPosition(const std::vector<double>& position) { position_ = position; }
  /// Where one channel axis stands now, in program coordinates: the next block's increment
  /// and an unprogrammed target start here. The channel sets the rotary axis when a changeover
  /// to rotary axis mode ends, as the spindle has turned since the program last positioned it.
  /// An axis outside the channel is ignored.
  void SetAxisPosition(size_t axis, double value) {
    if (axis < position_.size()) position_[axis] = value;
  }
  /// A variable (@100, P1, V.L.X) by name; 0 if never set.
  double Variable(const std::string& name) const;
  /// Sets a variable (RESTORE of fast measurement writes @100..@112 back).
  void SetVariable(const std::string& name, double value);
  /// Every variable set so far, by name (upper case).
  const std::map<std::string, double>& variables() const { return variables_; }
  /// Replaces all variables: an interpreter running in another's place in the same process
  /// shares its variable set (the REPOS subroutine, REPOS manual 8.3: `@100=M(5)`).
  void SetVariables(std::map<std::string, double> variables);
  /// The modal state from here on (SETTING of fast measurement makes its G codes modal, as the
  /// blocks the real control generates for it do).
  void SetModal(const ModalState& modal) { modal_ = modal; }
  bool ended() const { return ended_; }
  /// Continues the main program at `label` (the reverse program `.HOME`): calls and loops in
  /// progress are dropped. False if the main program has no such label.
  bool JumpTo(const std::string& label);
  /// The reverse program from where the program stands (REPOS manual 4.1, fast measurement
  /// 4.4): with a valid `label` it runs from that label first, and its RTS or RET at the top
  /// level (or reaching `.HOME` in the flow) continues at the main program's `.HOME`; without,
  /// it runs `.HOME` at once. Calls and loops in progress are dropped, and no reverse vector is
  /// valid until the reverse program programs one (a second reverse goes to `.HOME`). An error
  /// of the program is cleared: the reverse program is the way out of it. False, and nothing
  /// changes, if the main program has no `.HOME`.
  bool Reverse(ReverseLabel label);
  /// The reverse vector valid after the last block executed.
  const ReverseLabel& reverse_label() const { return reverse_; }
  int64_t executed_blocks() const { return executed_; }
  /// The program holding `label` as a subroutine for the REPOS function (REPOS manual 4.1): the
  /// main program, else program 99, else the other programs of the store (vmt's NC-cycle
  /// memory), in their order. -1 if none has it.
  int FindSubroutine(const std::string& label) const;
  /// Runs from `label` in program `program` as a subroutine of its own: its RTS ends the run
  /// (a block with `returned`) instead of failing as an RTS without JSR. Calls and loops in
  /// progress are dropped. False if the program has no such label.
  bool RunSubroutine(uint32_t program, const std::string& label);

 private:
  struct Frame {
    uint32_t program;
    int32_t return_block;  ///< block to continue at in the caller
  };
  struct Loop {
    uint32_t program;
    int32_t head;  ///< block of the $FOR
    uint32_t variable;
    double limit, step;
  };

  /// Clears `out` for block `block` of the current program.
  void Begin(PreparedBlock& out, uint32_t program, int32_t block) const;
  void BeginCold(PreparedBlock& out, uint32_t program, int32_t block) const;
  /// One more block without an effect; false (an error) after max_steps_per_block in a row.
  bool Idle(uint32_t program, int32_t block);
  [[gnu::cold]] bool EndlessLoop(uint32_t program, int32_t block);
  /// JumpTo / RunSubroutine: the flow goes elsewhere, the counter counts a jump.
  void Jumped();
  /// The part at the reverse label is over: `next` becomes `.HOME` of the main program.
  void EndReversePart(int32_t& next);
  bool Execute(const Block& block, PreparedBlock& out, int32_t& next);
  bool Statement_(const Statement& st, int32_t block, PreparedBlock& out, int32_t& next);
  // One kind of statement each (Statement_ dispatches on the kind).
  bool Assign(const Statement& st);
  bool CallSubprogram(const Statement& st, int32_t& next);  ///< JSR, L, a named call
  bool Return(const Statement& st, int32_t block, PreparedBlock& out, int32_t& next);
  bool InstructionStatement(const Statement& st, PreparedBlock& out);
  bool HashCommand(const Statement& st, PreparedBlock& out);  ///< ISG #-commands
  bool IfStructure(const Statement& st, int32_t& next);       ///< $IF, $ELSEIF, $ELSE, $ENDIF
  /// $FOR, $WHILE and their ends.
  bool LoopStructure(const Statement& st, int32_t block, int32_t& next);
  /// False (the program fails at the fault) if the last evaluation faulted.
  bool EvalSucceeded();
  bool Words(const Block& block, PreparedBlock& out);
  /// A G word of value `v` at `offset`: its modal group, or the block's G04/G74/G77/G92/G100.
  bool GWord(double v, uint32_t offset, PreparedBlock& out);
  /// An auxiliary function word (M, S, T, D, H, Q; `index` its j of Mj=) into the block's
  /// output and the modal state it sets; false for any other letter.
  bool AuxWord(char letter, int index, double v, PreparedBlock& out);
  /// X1/Y1 of G31/G32 (values in `fictive`, NaN: not programmed) into the targets of X and C.
  bool FictiveWords(const double fictive[2], uint32_t offset, uint8_t ijk,
                    const uint32_t ijk_offset[3], PreparedBlock& out);
  /// The channel axis named `name`, -1 if none.
  int NamedAxis(const char* name) const;
  /// The lead of a G33/G63/G64 block (F in MTC200, K in ISG) into modal_.lead.
  bool Lead(Dialect dialect, std::optional<double> f_word, uint32_t f_offset, uint8_t ijk,
            const uint32_t ijk_offset[3], uint32_t block_offset, PreparedBlock& out);
  double Eval(ExprId id);
  /// The arguments of the call that ends expression `id` (an instruction's list, or the data
  /// location TLD(...) of an assignment), evaluated but not called; false after a fault.
  bool EvalArguments(ExprId id, std::vector<InstructionArg>& args);
  /// Kinds and names of the arguments of the call at code unit `call` of the expression that
  /// starts at `id`; values are filled in by the caller.
  std::vector<InstructionArg> ArgumentForms(ExprId id, size_t call) const;
  /// TLD/OTD/MTD(...) in an expression, through data_.
  double ReadData(uint32_t name, Instruction instruction, std::vector<InstructionArg> args,
                  std::span<const double> values, uint32_t offset, uint32_t rank);
  /// The value a call or argument list leaves on the expression stack: `call` its code unit's
  /// index in expression `id`, `op` kCall or kArgs, `operands` its count, function, offset and
  /// rank units (followed by the next operation), `values` its arguments.
  double CallValue(ExprId id, size_t call, ExprOp op, uint32_t name, const uint32_t* operands,
                   std::span<const double> values);
  /// A built-in function (`name` for the messages).
  double Call(uint32_t name, Function function, std::span<const double> args, uint32_t offset,
              uint32_t rank);
  /// A fault of the expression being evaluated; the first in tree order (lowest rank) counts.
  [[gnu::cold]] void Fault(uint32_t rank, uint32_t offset, std::string message);
  bool Fail(uint32_t offset, std::string message);
  double& Var(uint32_t name);
  int AxisOf(uint32_t address);  ///< channel axis of an address symbol, -1 if none
  const Program& program() const { return *programs_[current_]; }

  std::vector<const Program*> programs_;
  std::map<std::string, uint32_t> by_name_;
  InterpreterConfig config_;
  ModalState modal_;
  std::vector<double> position_;
  std::map<std::string, double> variables_;
  /// Per program, per symbol id: the variable's node in variables_. A copy starts empty (its
  /// pointers would lead into the other interpreter's map); a move keeps them, the nodes move
  /// along with the map.
  struct VariableCache {
    std::vector<std::vector<double*>> per_program;
    VariableCache() = default;
    VariableCache(const VariableCache& o) : per_program(o.per_program.size()) {}
    VariableCache& operator=(const VariableCache& o) {
      per_program.assign(o.per_program.size(), {});
      return *this;
    }
    VariableCache(VariableCache&&) noexcept = default;
    VariableCache& operator=(VariableCache&&) noexcept = default;
  };
  VariableCache var_cache_;
  std::vector<std::vector<int8_t>> axis_cache_;  ///< per program, per symbol: axis, -1 none, -2 ?
  std::vector<Frame> calls_;
  std::vector<Loop> loops_;
  std::function<bool(int)> event_;
  DataAccess data_;
  /// The events and data access of the Next() call in progress, null between calls.
  const std::function<bool(int)>* call_event_ = nullptr;
  const DataAccess* call_data_ = nullptr;
  const std::function<bool(int)>& events() const { return call_event_ ? *call_event_ : event_; }
  const DataAccess& data() const { return call_data_ ? *call_data_ : data_; }
  std::vector<InstructionArg>* capture_ = nullptr;  ///< EvalArguments: the call to capture
  uint32_t current_ = 0;
  int32_t pc_ = 0;
  double last_result_ = 0;  ///< MTC200: BEQ/BNE/... test the last computed @ value
  bool ended_ = false;
  bool subroutine_ = false;  ///< RunSubroutine: a top-level RTS returns
  ReverseLabel reverse_;     ///< REV: the reverse vector valid now
  /// Reverse(): the part at a reverse label runs; its top-level RTS / RET goes to `.HOME`.
  bool reverse_part_ = false;
  int32_t home_block_ = -1;  ///< Reverse(): `.HOME` of the main program
  int64_t executed_ = 0;
  std::optional<Diagnostic> error_;
  uint32_t error_program_ = 0;
  // Block counter (manual 3.2). A block counts the lines from the one the counter stands at:
  // in sequence its line minus count_line_; after a jump (branch, call target, return,
  // $-structure) one, for the target line (count_line_ = kJumped); the first block of a file
  // entered by a call or at program start all lines of that file up to its own
  // (count_line_ = 0).
  static constexpr uint32_t kJumped = UINT32_MAX;
  uint32_t count_ = 0;
  uint32_t count_line_ = 0;  ///< line of the current file the counter stands at, or kJumped
  /// What the block just executed did to the count beyond the flow of control (bits, checked
  /// once per block): an ISG call entered another file at its first block, or a loop statement
  /// changed the count (manual 9.2.1, figure 3): a $ENDFOR that loops back is not counted but
  /// re-reads its $FOR line; a $WHILE that fails after a loop-back is not counted, and counting
  /// goes on from its $ENDWHILE.
  enum CountEvent : uint8_t { kEnteredFile = 1, kForBack = 2, kWhileExit = 4 };
  uint8_t count_events_ = 0;
  int32_t loop_line_block_ = -1;  ///< kForBack: the $FOR; kWhileExit: the $ENDWHILE
  bool while_back_ = false;       ///< the $ENDWHILE jumped back to its $WHILE
  int32_t reread_for_ = -1;       ///< SetEveryBlock: a re-read $FOR line still to hand out
  uint32_t reread_program_ = 0, reread_count_ = 0;
  bool every_block_ = false;
  bool search_lock_ = false;   ///< #BLOCKSEARCH LOCKED .. RELEASED (manual 6)
  int64_t idle_steps_ = 0;     ///< blocks without an effect in a row (max_steps_per_block)
  bool started_ = false;       ///< Next() has run: StartAt is too late
  bool entering_ = false;      ///< a failed $IF/$ELSEIF condition jumped to the next branch
  std::vector<double> stack_;  ///< Eval's value stack
  bool fault_ = false;
  uint32_t fault_rank_ = 0, fault_offset_ = 0;
  std::string fault_message_;
  bool eval_failed_ = false;
  uint32_t eval_fail_offset_ = 0;
  std::string eval_fail_message_;
};

// In the header: both the expressions' postfix loop and the assignments read variables through
// it, and they are in two files.
inline double& Interpreter::Var(uint32_t name) {
  auto& cache = var_cache_.per_program[current_];
  if (cache.size() <= name) cache.resize(name + 1, nullptr);
  if (!cache[name]) cache[name] = &variables_[program().symbols.Name(name)];
  return *cache[name];
}

}  // namespace vmt::control::nc
