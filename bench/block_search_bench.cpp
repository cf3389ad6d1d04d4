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

#include "control/channel/channel.hpp"
#include "control/nc/parser.hpp"
#include "generated_programs.hpp"

namespace {

using namespace vmt::control;
using namespace vmt::bench;

const bool kKeepFreedMemory = [] {
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  return true;
}();

channel::ChannelAxis Axis(const std::string& name, int drive) {
  channel::ChannelAxis a;
  a.name = name;
  a.number = drive + 1;
  a.drive = drive;
  a.rapid_per_s = 500;
  a.acceleration = 4000;
  return a;
}

void Search(benchmark::State& state, const std::vector<std::pair<std::string, nc::Dialect>>& files) {
  std::vector<nc::ParseResult> parsed;
  for (const auto& [text, dialect] : files)
    parsed.push_back(nc::ParseProgram(text, "bench.nc", dialect));
  for (const nc::ParseResult& r : parsed)
    if (!r.ok()) state.SkipWithError(nc::Format(r.errors[0], r.program.files).c_str());
  std::vector<const nc::Program*> programs;
  for (const nc::ParseResult& r : parsed) programs.push_back(&r.program);
  channel::ChannelConfig config;
  config.axes = {Axis("X", 0), Axis("Y", 1), Axis("Z", 2)};
  channel::BlockSearchParameters p;
  p.type = channel::BlockSearchType::kProgramEnd;
  int64_t lines = 0;
  for (auto _ : state) {
    channel::Channel ch(config, programs);
    AmplifierTelegram at;
    MasterTelegram mdt;
    at.feedback.resize(3);
    for (DriveFeedback& f : at.feedback) f.status = drive_status::kReady;
    mdt.setpoints.resize(3);
    ch.SetBlockSearch(p);
    ch.Start();
    while (ch.state() != channel::ChannelState::kEnded &&
           ch.state() != channel::ChannelState::kError)
      ch.Tick(at, mdt);
    if (ch.state() == channel::ChannelState::kError) state.SkipWithError(ch.error().c_str());
    lines += ch.block_search().block_count;
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
  Search(state, {{text, nc::Dialect::kIsg}, {"%sub_a\nG01 Z1 F1000\nM17\n", nc::Dialect::kIsg}});
}

BENCHMARK(BM_SearchToEndStraightMtc200)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SearchToEndExpressionsIsg)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SearchToEndLoopsIsg)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
