// Rows per second and MB/s of the trace writer (RunRecorder::Trace: the digest and trace.csv
// through common::OutputFile), against the way rows were written before it: the same digest and
// a std::ofstream `<<` per row. The rows are a real trace's (scenes/jog.yaml, 2 s of the run,
// on the kinematic backend), written over and over; the files go to $TMPDIR (default /tmp).

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "sim/runner/run_recorder.hpp"
#include "sim/runner/runner.hpp"
#include "sim/scene/scene.hpp"

namespace {

using namespace vmt;

constexpr size_t kRows = 200000;  // per iteration: a 50 s run at the 250 us tick

std::string Folder(const std::string& name) {
  const char* tmp = std::getenv("TMPDIR");
  const std::string dir = std::string(tmp && *tmp ? tmp : "/tmp") + "/vmt-trace-bench/" + name;
  std::filesystem::create_directories(dir);
  return dir;
}

// The rows of a short real run, each with its line break, as TraceRow makes them.
const std::vector<std::string>& Rows() {
  static const std::vector<std::string> rows = [] {
    sim::Scene scene = sim::LoadScene(std::string(VMT_SOURCE_DIR) + "/scenes/jog.yaml");
    sim::RunOptions options;
    options.backend = sim::BackendKind::kKinematic;
    options.until_s = 2;
    options.snapshots = false;
    options.out_dir = Folder("source");
    sim::RunScene(scene, options);
    std::ifstream in(options.out_dir + "/trace.csv", std::ios::binary);
    std::vector<std::string> out;
    for (std::string line; std::getline(in, line);) out.push_back(line + "\n");
    out.erase(out.begin());  // the header
    return out;
  }();
  return rows;
}

void Count(benchmark::State& state, size_t bytes) {
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kRows));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * bytes));
  state.counters["row_bytes"] = static_cast<double>(bytes) / kRows;
}

size_t BytesOf(const std::vector<std::string>& rows) {
  size_t bytes = 0;
  for (size_t i = 0; i < kRows; ++i) bytes += rows[i % rows.size()].size();
  return bytes;
}

// The runner's trace writer as a run uses it: Open, a row per tick, Close (the rename).
void BM_TraceRunRecorder(benchmark::State& state) {
  const std::vector<std::string>& rows = Rows();
  const std::string dir = Folder("recorder");
  for (auto _ : state) {
    sim::RunRecorder recorder;
    recorder.Open(dir);
    for (size_t i = 0; i < kRows; ++i) recorder.Trace(rows[i % rows.size()]);
    recorder.Close();
    benchmark::DoNotOptimize(recorder.DigestHex());
  }
  Count(state, BytesOf(rows));
}

// The writer before common::OutputFile: the digest, and `<<` into a std::ofstream per row.
void BM_TraceOfstream(benchmark::State& state) {
  const std::vector<std::string>& rows = Rows();
  const std::string dir = Folder("ofstream");
  for (auto _ : state) {
    sim::Fnv1a64 digest;
    std::ofstream file(dir + "/trace.csv", std::ios::binary);
    for (size_t i = 0; i < kRows; ++i) {
      const std::string& row = rows[i % rows.size()];
      digest.Add(row);
      file << row;
    }
    file.flush();
    benchmark::DoNotOptimize(digest.Hex());
  }
  Count(state, BytesOf(rows));
}

// The digest alone, what both writers share: the part of a row's cost that is not writing.
void BM_TraceDigestOnly(benchmark::State& state) {
  const std::vector<std::string>& rows = Rows();
  for (auto _ : state) {
    sim::Fnv1a64 digest;
    for (size_t i = 0; i < kRows; ++i) digest.Add(rows[i % rows.size()]);
    benchmark::DoNotOptimize(digest.Hex());
  }
  Count(state, BytesOf(rows));
}

BENCHMARK(BM_TraceRunRecorder)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TraceOfstream)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TraceDigestOnly)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
