// Block search type 5 over NC program files, timed in its phases (wall and CPU seconds): read
// as vmt check reads, parse, search to the program end. bench/linuxcnc_compare.sh runs it on the
// files it gives LinuxCNC's rs274, so that both sides read the same moves from a file. Usage:
// search_program MAIN [SUBPROGRAM...]; the dialect is detected per file as vmt check does. Prints
// one JSON object; exit 1 on a parse or search error, 2 on a file that cannot be read.

#include <malloc.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/mapped_file.hpp"
#include "control/nc/parser.hpp"
#include "type5_search.hpp"

namespace {

// Wall and CPU seconds of a phase: the CPU time (user + system, so page faults included) is the
// one that other processes' load on a shared machine moves least.
struct Stopwatch {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  double cpu = CpuS();

  static double CpuS() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           double(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6;
  }
  double WallS() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
  }
  double CpuSince() const { return CpuS() - cpu; }
};

}  // namespace

int main(int argc, char** argv) {
  namespace nc = vmt::control::nc;
  // As vmt does: keep freed memory in the process (fresh pages are expensive on these VMs).
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  if (argc < 2) {
    std::fprintf(stderr, "usage: search_program MAIN [SUBPROGRAM...]\n");
    return 2;
  }
  Stopwatch watch;
  std::vector<vmt::common::MappedFile> texts;
  size_t source_lines = 0;
  for (int i = 1; i < argc; ++i) {
    std::optional<vmt::common::MappedFile> read = vmt::common::MappedFile::Read(argv[i]);
    if (!read) {
      std::fprintf(stderr, "%s:0:0: error: cannot open file\n", argv[i]);
      return 2;
    }
    texts.push_back(std::move(*read));
    for (char c : texts.back().text()) source_lines += c == '\n';
  }
  const double read_s = watch.WallS(), read_cpu_s = watch.CpuSince();

  watch = Stopwatch();
  std::vector<nc::ParseResult> parsed;
  size_t blocks = 0;
  for (size_t i = 0; i < texts.size(); ++i) {
    const std::string file = argv[i + 1];
    parsed.push_back(nc::ParseProgram(texts[i], file, nc::DetectDialect(texts[i], file)));
    for (const nc::Diagnostic& d : parsed.back().errors)
      std::fprintf(stderr, "%s\n", nc::Format(d, parsed.back().program.files).c_str());
    if (!parsed.back().ok()) return 1;
    blocks += parsed.back().program.blocks.size();
  }
  const double parse_s = watch.WallS(), parse_cpu_s = watch.CpuSince();

  std::vector<const nc::Program*> programs;
  for (const nc::ParseResult& r : parsed) programs.push_back(&r.program);
  watch = Stopwatch();
  const vmt::bench::Type5Result r = vmt::bench::RunType5Search(programs);
  const double search_s = watch.WallS(), search_cpu_s = watch.CpuSince();
  if (!r.error.empty()) {
    std::fprintf(stderr, "%s: error: block search: %s\n", argv[1], r.error.c_str());
    return 1;
  }
  std::printf(
      "{\"source_lines\": %zu, \"blocks\": %zu, \"decoder_lines\": %llu, \"read_s\": %.6f, "
      "\"read_cpu_s\": %.6f, \"parse_s\": %.6f, \"parse_cpu_s\": %.6f, \"search_s\": %.6f, "
      "\"search_cpu_s\": %.6f}\n",
      source_lines, blocks, static_cast<unsigned long long>(r.decoder_lines), read_s, read_cpu_s,
      parse_s, parse_cpu_s, search_s, search_cpu_s);
  return 0;
}
