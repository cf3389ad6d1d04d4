#pragma once
// Invariants of vmt's own code. A broken one is a bug in vmt, never bad input (bad input is
// answered with an error naming its file and place): stop at once, saying where and why, rather
// than compute on from a broken state and report something wrong later.

#include <cstdarg>
#include <cstdio>
#include <cstdlib>

namespace vmt::common {

[[noreturn, gnu::cold, gnu::format(printf, 4, 5)]] inline void DemandFailed(
    const char* file, int line, const char* condition, const char* format, ...) {
  std::fprintf(stderr, "vmt: internal error at %s:%d (%s): ", file, line, condition);
  va_list args;
  va_start(args, format);
  std::vfprintf(stderr, format, args);
  va_end(args);
  std::fputc('\n', stderr);
  std::abort();
}

}  // namespace vmt::common

/// VMT_DEMAND(condition, printf-format, args...): aborts with the message when `condition` is
/// false. Kept in Release builds: the checks guard state that a wrong answer would hide.
#define VMT_DEMAND(condition, ...)                    \
  ((condition) ? static_cast<void>(0)                 \
               : ::vmt::common::DemandFailed(__FILE__, __LINE__, #condition, __VA_ARGS__))
