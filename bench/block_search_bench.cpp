// Block search type 5 (twincat-cnc-block-search-de.md 3.4: decode to the program end, no
// interpolation, "for the fast test of NC programs") through the channel, on the generated
// 1M-block programs of nc_decode_bench: counter lines_per_second, the decoder's lines
// (block_count_r: loops and subprogram lines counted each time they are read) per second of
// wall time, parsing excluded.

#include <benchmark/benchmark.h>
#include <malloc.h>

#include <memory>
#include <string>
#include <vector>

#include "control/nc/parser.hpp"
#include "generated_programs.hpp"
#include "type5_search.hpp"

namespace {

using namespace vmt::control;
using namespace vmt::bench;

const bool kKeepFreedMemory = [] {
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  return true;
}();

void Search(benchmark::State& state,
            const std::vector<std::pair<std::string, nc::Dialect>>& files) {
  std::vector<nc::ParseResult> parsed;
  for (const auto& [text, dialect] : files)
    parsed.push_back(nc::ParseProgram(text, "bench.nc", dialect));
  for (const nc::ParseResult& r : parsed)
    if (!r.ok()) state.SkipWithError(nc::Format(r.errors[0], r.program.files).c_str());
  std::vector<const nc::Program*> programs;
  for (const nc::ParseResult& r : parsed) programs.push_back(&r.program);
  int64_t lines = 0;
  for (auto _ : state) {
    const Type5Result r = RunType5Search(programs);
    if (!r.error.empty()) state.SkipWithError(r.error.c_str());
    lines += int64_t(r.decoder_lines);
  }
  state.counters["lines_per_second"] =
      benchmark::Counter(double(lines), benchmark::Counter::kIsRate);
}

void BM_SearchToEndStraightMtc200(benchmark::State& state) {
  static const std::string text = StraightMtc200();
  Search(state, {{text, nc::Dialect::kMtc200}});
}
void BM_SearchToEndExpressionsIsg(benchmark::State& state) {
  static const std::string text = ExpressionsIsg();
  Search(state, {{text, nc::Dialect::kIsg}});
}
void BM_SearchToEndLoopsIsg(benchmark::State& state) {
  static const std::string text = LoopsIsg();
  Search(state, {{text, nc::Dialect::kIsg}, {LoopsIsgSubprogram(), nc::Dialect::kIsg}});
}

BENCHMARK(BM_SearchToEndStraightMtc200)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SearchToEndExpressionsIsg)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SearchToEndLoopsIsg)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
