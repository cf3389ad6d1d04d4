// Decode throughput of the NC front ends on generated 1M-block programs: straight moves, loops
// and subprograms, expressions. Counter blocks_per_second; the reference is LinuxCNC's
// interpreter at about 200-250k source lines/s on straight code (see README).

#include <benchmark/benchmark.h>

#include <string>

#include "control/nc/parser.hpp"

namespace {

using namespace vmt::control::nc;

constexpr int kBlocks = 1000000;

std::string StraightMtc200() {
  std::string s;
  s.reserve(kBlocks * 32);
  char line[96];
  for (int i = 0; i < kBlocks; ++i) {
    std::snprintf(line, sizeof line, "N%04d G01 X%.3f Z%.3f F%d\n", i % 10000, 10 + (i % 977) * 0.125,
                  -(i % 613) * 0.25, 500 + i % 7 * 100);
    s += line;
  }
  return s;
}

std::string ExpressionsIsg() {
  std::string s = "%expr\n";
  s.reserve(kBlocks * 48);
  char line[128];
  for (int i = 0; i < kBlocks; ++i) {
    std::snprintf(line, sizeof line, "N%d P%d = [P%d + %d.5] * 2 / [1 + P%d] X[P%d * 0.5 - %d]\n", i,
                  i % 50 + 1, (i + 7) % 50 + 1, i % 13, (i + 3) % 50 + 1, i % 50 + 1, i % 31);
    s += line;
  }
  return s;
}

std::string LoopsIsg() {
  // Loop and subprogram structure repeated: $FOR, $IF, $WHILE and L calls between moves.
  std::string s = "%loops\n";
  s.reserve(kBlocks * 24);
  for (int i = 0; i < kBlocks / 10; ++i) {
    s += "$FOR P1 = 1, 10, 1\n";
    s += "$IF P1 == 5\n";
    s += "L sub_a\n";
    s += "$ELSE\n";
    s += "G01 X[P1] Y[P1 * 2] F1000\n";
    s += "$ENDIF\n";
    s += "$WHILE P2 < 3\n";
    s += "P2 = P2 + 1\n";
    s += "$ENDWHILE\n";
    s += "$ENDFOR\n";
  }
  return s;
}

void Decode(benchmark::State& state, const std::string& text, Dialect dialect) {
  size_t blocks = 0;
  for (auto _ : state) {
    const ParseResult r = ParseProgram(text, "bench.nc", dialect);
    if (!r.ok()) state.SkipWithError(Format(r.errors[0], r.program.files).c_str());
    blocks += r.program.blocks.size();
    benchmark::DoNotOptimize(r.program.blocks.data());
  }
  state.counters["blocks_per_second"] = benchmark::Counter(double(blocks), benchmark::Counter::kIsRate);
  state.counters["source_mb_per_second"] =
      benchmark::Counter(double(text.size()) * state.iterations() / 1e6, benchmark::Counter::kIsRate);
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

BENCHMARK(BM_ParseStraightMtc200)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ParseExpressionsIsg)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ParseLoopsIsg)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
