// libFuzzer target for the NC front ends: any bytes, either dialect, must give a result and
// diagnostics -- never a crash, a sanitizer report, or a hang.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "control/nc/parser.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace vmt::control::nc;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  for (Dialect d : {Dialect::kMtc200, Dialect::kIsg}) {
    const ParseResult r = ParseProgram(text, "fuzz.nc", d);
    for (const Diagnostic& e : r.errors) (void)Format(e, r.program.files);
  }
  (void)DetectDialect(text, "fuzz.nc");
  return 0;
}
