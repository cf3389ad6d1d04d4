// Writes a generated benchmark program to stdout, so that tools outside the benchmarks (vmt
// check, search_program, LinuxCNC's rs274) read the very text nc_decode_bench and
// block_search_bench time. Usage: generate_program straight|loops|loops-sub|expressions
// [--dialect vmt|rs274ngc] [--blocks N]. vmt's dialect is the program's own (straight: MTC200,
// the others: ISG); rs274ngc has straight and loops (with their subprogram inside).

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>
#include <utility>

#include "generated_programs.hpp"

namespace {

int Usage() {
  std::fprintf(stderr,
               "usage: generate_program straight|loops|loops-sub|expressions "
               "[--dialect vmt|rs274ngc] [--blocks N]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace vmt::bench;
  std::string program, dialect = "vmt";
  int blocks = kBlocks;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--dialect" && i + 1 < argc) {
      dialect = argv[++i];
    } else if (a == "--blocks" && i + 1 < argc) {
      char* end = nullptr;
      const long n = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || n < 10 || n > 100000000) return Usage();
      blocks = int(n);
    } else if (program.empty() && a[0] != '-') {
      program = a;
    } else {
      return Usage();
    }
  }
  const std::map<std::pair<std::string, std::string>, std::function<std::string()>> generators = {
      {{"vmt", "straight"}, [&] { return StraightMtc200(blocks); }},
      {{"vmt", "loops"}, [&] { return LoopsIsg(blocks); }},
      {{"vmt", "loops-sub"}, [] { return LoopsIsgSubprogram(); }},
      {{"vmt", "expressions"}, [&] { return ExpressionsIsg(blocks); }},
      {{"rs274ngc", "straight"}, [&] { return StraightRs274ngc(blocks); }},
      {{"rs274ngc", "loops"}, [&] { return LoopsRs274ngc(blocks); }}};
  const auto generator = generators.find({dialect, program});
  if (generator == generators.end()) return Usage();
  const std::string text = generator->second();
  return std::fwrite(text.data(), 1, text.size(), stdout) == text.size() ? 0 : 1;
}
