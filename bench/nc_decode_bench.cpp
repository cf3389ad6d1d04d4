// Decode throughput of the NC front ends on generated 1M-block programs: straight moves, loops
// and subprograms, expressions. Counter blocks_per_second; the reference is LinuxCNC's
// interpreter at about 200-250k source lines/s on straight code (see README).

#include <benchmark/benchmark.h>
#include <malloc.h>

#include <string>

#include "control/nc/interpreter.hpp"
#include "control/nc/parser.hpp"
#include "generated_programs.hpp"

namespace {

using namespace vmt::control::nc;
using namespace vmt::bench;

// As the vmt command does (sim/cli/main.cpp): keep freed memory in the process. First touches
// of fresh pages cost ~20 us each on the project's VMs and would otherwise dominate.
const bool kKeepFreedMemory = [] {
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  return true;
}();

void Decode(benchmark::State& state, const std::string& text, Dialect dialect) {
  size_t blocks = 0;
  for (auto _ : state) {
    const ParseResult r = ParseProgram(text, "bench.nc", dialect);
    if (!r.ok()) state.SkipWithError(Format(r.errors[0], r.program.files).c_str());
    blocks += r.program.blocks.size();
    benchmark::DoNotOptimize(r.program.blocks.data());
  }
  state.counters["blocks_per_second"] =
      benchmark::Counter(double(blocks), benchmark::Counter::kIsRate);
  state.counters["source_mb_per_second"] = benchmark::Counter(
      double(text.size()) * state.iterations() / 1e6, benchmark::Counter::kIsRate);
}

void BM_ParseStraightMtc200(benchmark::State& state) {
  static const std::string text = StraightMtc200();
  Decode(state, text, Dialect::kMtc200);
}
void BM_ParseExpressionsIsg(benchmark::State& state) {
  static const std::string text = ExpressionsIsg();
  Decode(state, text, Dialect::kIsg);
}
void BM_ParseLoopsIsg(benchmark::State& state) {
  static const std::string text = LoopsIsg();
  Decode(state, text, Dialect::kIsg);
}

// Executed blocks: loops, branches and subprogram calls run by the interpreter, each pass
// producing a move (LinuxCNC reference: about 250k executed blocks/s on loop-heavy code).
void Execute(benchmark::State& state, const std::vector<std::pair<std::string, Dialect>>& files) {
  std::vector<ParseResult> parsed;
  for (const auto& [text, dialect] : files)
    parsed.push_back(ParseProgram(text, "bench.nc", dialect));
  std::vector<const Program*> programs;
  for (const ParseResult& r : parsed) programs.push_back(&r.program);
  int64_t executed = 0;
  for (auto _ : state) {
    Interpreter interpreter(programs, {});
    PreparedBlock b;
    while (interpreter.Next(b) && !b.end) benchmark::DoNotOptimize(b.target.data());
    if (interpreter.error()) state.SkipWithError(interpreter.error()->message.c_str());
    executed += interpreter.executed_blocks();
  }
  state.counters["executed_blocks_per_second"] =
      benchmark::Counter(double(executed), benchmark::Counter::kIsRate);
}

void BM_ExecuteLoopsIsg(benchmark::State& state) {
  Execute(state, {{"%main\n"
                   "N10 $FOR P1 = 1, 100000, 1\n"
                   "N20 $IF P1 MOD 3 == 0\n"
                   "N30 L sub\n"
                   "N40 $ELSE\n"
                   "N50 G01 X[P1 * 0.001] Z[-P1 * 0.002] F1000\n"
                   "N60 $ENDIF\n"
                   "N70 $ENDFOR\n"
                   "N80 M30\n",
                   Dialect::kIsg},
                  {"%sub\nN10 P2 = P2 + 1\nN20 G01 Z[P2 * 0.01]\nN30 M17\n", Dialect::kIsg}});
}

void BM_ExecuteLoopsMtc200(benchmark::State& state) {
  Execute(state, {{"N0001 @100=100000\n"
                   "N0002 .LOOP\n"
                   "N0003 JSR .MOVE\n"
                   "N0004 @100=@100-1 BGT .LOOP\n"
                   "N0005 RET\n"
                   "N0006 .MOVE\n"
                   "N0007 @101=@100*0.001\n"
                   "N0008 G01 X@101 Z-@101 F1000 RTS\n",
                   Dialect::kMtc200}});
}

BENCHMARK(BM_ExecuteLoopsIsg)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ExecuteLoopsMtc200)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ParseStraightMtc200)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ParseExpressionsIsg)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ParseLoopsIsg)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
