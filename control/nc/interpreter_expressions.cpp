// The interpreter's expressions: the postfix code of arithmetic, variables, functions, and the
// arguments of the data access and measuring instructions (TLD/OTD/MTD, SETTING...), which
// take bare names where an expression would give a value.
#include <cmath>
#include <numbers>

#include "control/nc/interpreter.hpp"

namespace vmt::control::nc {
namespace {

using Kind = Statement::Kind;
constexpr double kRadPerDeg = std::numbers::pi / 180;

}  // namespace

std::vector<InstructionArg> Interpreter::ArgumentForms(ExprId id, size_t call) const {
  // A walk of the postfix code that keeps, instead of values, what each stack entry is: an
  // omitted argument, a bare name (kVariable alone), or a computed value. Jumps of AND/OR only
  // skip their right operand, which pushes and pops back to the same depth.
  using Op = ExprOp;
  using Kind = InstructionArg::Kind;
  const Program& p = program();
  std::vector<InstructionArg> stack;
  auto value = [] { return InstructionArg{Kind::kValue, 0, {}}; };
  auto pop_to_value = [&](size_t n) {
    stack.resize(stack.size() >= n ? stack.size() - n : 0);
    stack.push_back(value());
  };
  for (size_t pc = static_cast<size_t>(id); pc <= call && pc < p.code.size();) {
    const uint32_t unit = p.code[pc++];
    const bool wide = (unit >> 8) == kWideImmediate;
    switch (OpOf(unit)) {
      case Op::kEnd:
        return {};
      case Op::kInt:
        stack.push_back(value());
        break;
      case Op::kNumber:
        if (wide) ++pc;
        stack.push_back(value());
        break;
      case Op::kVariable: {
        const uint32_t name = wide ? p.code[pc++] : unit >> 8;
        const std::string& text = p.symbols.Name(name);
        // X, Z, XYZ: an axis designation; @100, P1, V.L.X are variables whose value counts.
        const bool bare = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
          return std::isalpha(static_cast<unsigned char>(c));
        });
        stack.push_back(bare ? InstructionArg{Kind::kName, 0, text} : value());
        break;
      }
      case Op::kOmitted:
        stack.push_back({Kind::kOmitted, 0, {}});
        break;
      case Op::kNeg:
      case Op::kNot:
      case Op::kAnd:
      case Op::kOr:
        pop_to_value(1);
        break;
      case Op::kDiv:
      case Op::kMod:
        pc += 2;
        pop_to_value(2);
        break;
      case Op::kAndSkip:
      case Op::kOrSkip:
        ++pc;
        if (!stack.empty()) stack.pop_back();
        break;
      case Op::kCall:
      case Op::kArgs: {
        if (wide) ++pc;
        const uint32_t count = CountOf(p.code[pc]);
        if (pc - 1 - (wide ? 1 : 0) == call) {
          const size_t n = std::min<size_t>(count, stack.size());
          return {stack.end() - static_cast<std::ptrdiff_t>(n), stack.end()};
        }
        pc += 3;
        pop_to_value(count);
        break;
      }
      default:  // the binary operators
        pop_to_value(2);
        break;
    }
  }
  return {};
}

bool Interpreter::EvalArguments(ExprId id, std::vector<InstructionArg>& args) {
  args.clear();
  capture_ = &args;
  Eval(id);
  capture_ = nullptr;
  return !eval_failed_;
}

double Interpreter::ReadData(uint32_t name, Instruction instruction,
                             std::vector<InstructionArg> args, std::span<const double> values,
                             uint32_t offset, uint32_t rank) {
  for (size_t i = 0; i < args.size() && i < values.size(); ++i)
    if (args[i].kind != InstructionArg::Kind::kOmitted) {
      args[i].kind = InstructionArg::Kind::kValue;  // a bare name in data access is a variable
      args[i].value = values[i];
    }
  const DataAccess& access = data();
  if (!access.read) {
    Fault(rank, offset, program().symbols.Name(name) + "(...) data access is not available here");
    return 0;
  }
  double v = 0;
  std::string error = access.read(instruction, args, v);
  if (!error.empty()) Fault(rank, offset, std::move(error));
  return v;
}


double Interpreter::Eval(ExprId id) {
  using Op = ExprOp;
  const Program& p = program();
  const uint32_t* pc = p.code.data() + id;
  // The stack holds what the deepest expression of the programs needs (Program::max_stack).
  double* sp = stack_.data();
  fault_ = false;
  auto immediate = [&](uint32_t unit) {
    const uint32_t value = unit >> 8;
    return value == kWideImmediate ? *pc++ : value;
  };
  for (;;) {
    const uint32_t unit = *pc++;
    switch (OpOf(unit)) {
      case Op::kEnd:
        if (fault_ && !eval_failed_) {
          eval_failed_ = true;
          eval_fail_offset_ = fault_offset_;
          eval_fail_message_ = std::move(fault_message_);
        }
        return sp[-1];
      case Op::kInt:
        *sp++ = static_cast<double>(static_cast<int32_t>(unit) >> 8);
        break;
      case Op::kNumber:
        *sp++ = p.numbers[immediate(unit)];
        break;
      case Op::kVariable:
        *sp++ = Var(immediate(unit));
        break;
      case Op::kOmitted:
        *sp++ = 0;
        break;
      case Op::kNeg:
        sp[-1] = -sp[-1];
        break;
      case Op::kNot:
        sp[-1] = sp[-1] == 0 ? 1 : 0;
        break;
      case Op::kAdd:
        --sp;
        sp[-1] = sp[-1] + sp[0];
        break;
      case Op::kSub:
        --sp;
        sp[-1] = sp[-1] - sp[0];
        break;
      case Op::kMul:
        --sp;
        sp[-1] = sp[-1] * sp[0];
        break;
      case Op::kDiv:
      case Op::kMod: {
        const double d = *--sp;
        if (d == 0) {
          Fault(pc[1], pc[0], OpOf(unit) == Op::kDiv ? "division by zero" : "MOD by zero");
          sp[-1] = 0;
        } else {
          sp[-1] = OpOf(unit) == Op::kDiv ? sp[-1] / d : std::fmod(sp[-1], d);
        }
        pc += 2;
        break;
      }
      case Op::kPow:
      case Op::kEq:
      case Op::kNe:
      case Op::kLt:
      case Op::kLe:
      case Op::kGt:
      case Op::kGe:
      case Op::kXor:
        --sp;
        sp[-1] = ApplyBinary(OpOf(unit), sp[-1], sp[0]);
        break;
      case Op::kAndSkip:
        // A zero left operand decides: the right one is not evaluated (nor its faults).
        if (sp[-1] == 0) {
          sp[-1] = 0;
          pc += *pc + 1;
        } else {
          --sp;
          ++pc;
        }
        break;
      case Op::kOrSkip:
        if (sp[-1] != 0) {
          sp[-1] = 1;
          pc += *pc + 1;
        } else {
          --sp;
          ++pc;
        }
        break;
      case Op::kAnd:
      case Op::kOr:
        sp[-1] = sp[-1] != 0;
        break;
      case Op::kCall:
      case Op::kArgs: {
        const size_t at = static_cast<size_t>(pc - 1 - p.code.data());
        const uint32_t name = immediate(unit);
        const uint32_t count = CountOf(pc[0]);
        sp -= count;
        *sp = CallValue(id, at, OpOf(unit), name, pc, {sp, count});
        pc += 3;
        ++sp;
        break;
      }
    }
  }
}

double Interpreter::CallValue(ExprId id, size_t call, ExprOp op, uint32_t name,
                              const uint32_t* operands, std::span<const double> values) {
  const uint32_t offset = operands[1], rank = operands[2];
  const Function function = FunctionOfUnit(operands[0]);
  if (capture_ && OpOf(operands[3]) == ExprOp::kEnd) {
    // EvalArguments: the call that ends the expression is not made, its arguments are.
    *capture_ = ArgumentForms(id, call);
    for (size_t i = 0; i < capture_->size() && i < values.size(); ++i)
      if ((*capture_)[i].kind == InstructionArg::Kind::kValue) (*capture_)[i].value = values[i];
    return 0;
  }
  if (op == ExprOp::kArgs) return 0;
  if (const Instruction data = DataAccessOf(function); data != Instruction::kNone)
    return ReadData(name, data, ArgumentForms(id, call), values, offset, rank);
  return Call(name, function, values, offset, rank);
}

double Interpreter::Call(uint32_t id, Function function, std::span<const double> args,
                         uint32_t offset, uint32_t rank) {
  auto fail = [&](std::string message) {
    Fault(rank, offset, std::move(message));
    return 0.0;
  };
  auto one = [&](double (*f)(double)) {
    if (args.size() != 1) return fail(program().symbols.Name(id) + " takes one argument");
    return f(args[0]);
  };
  switch (function) {
    case Function::kG:
    case Function::kM: {
      if (args.size() != 1) break;
      const char letter = function == Function::kG ? 'G' : 'M';
      bool known;
      const int v = ModalGroupValue(modal_, letter, static_cast<int>(args[0]), known);
      if (!known)
        return fail(std::string(1, letter) + "(" + std::to_string(static_cast<int>(args[0])) +
                    "): no such modal group");
      return v;
    }
    case Function::kSin:
      return one([](double x) { return std::sin(x * kRadPerDeg); });
    case Function::kCos:
      return one([](double x) { return std::cos(x * kRadPerDeg); });
    case Function::kTan:
      return one([](double x) { return std::tan(x * kRadPerDeg); });
    case Function::kAsin:
      return one([](double x) { return std::asin(x) / kRadPerDeg; });
    case Function::kAcos:
      return one([](double x) { return std::acos(x) / kRadPerDeg; });
    case Function::kAtan:
      return one([](double x) { return std::atan(x) / kRadPerDeg; });
    case Function::kAbs:
      return one([](double x) { return std::abs(x); });
    case Function::kInt:
      return one([](double x) { return std::trunc(x); });
    case Function::kRound:
      return one([](double x) { return std::round(x); });
    case Function::kExp:
      return one([](double x) { return std::exp(x); });
    case Function::kSqrt:
      if (args.size() == 1 && args[0] < 0) return fail("SQRT of a negative number");
      return one([](double x) { return std::sqrt(x); });
    case Function::kLn:
      if (args.size() == 1 && args[0] <= 0) return fail("LN of a number <= 0");
      return one([](double x) { return std::log(x); });
    case Function::kNone:
    case Function::kTld:  // Eval reads them through the data access
    case Function::kOtd:
    case Function::kMtd:
      break;
  }
  return fail("function " + program().symbols.Name(id) +
              " is not supported by vmt (docs/conformance.md)");
}

}  // namespace vmt::control::nc
