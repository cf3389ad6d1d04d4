#pragma once
// SIGINT and SIGTERM ask a run to stop at its next tick, as vmt serve stops: the files are
// completed as far as the run went, summary.json says it stopped and when, and the command
// exits 3 (docs/cli.md). Killed outright instead, a run would leave no summary and a cut trace.

#include <csignal>
#include <string>

namespace vmt::sim {

inline constexpr int kStoppedEarly = 3;

inline volatile std::sig_atomic_t g_stop_signal = 0;

/// From here on SIGINT and SIGTERM only note that they came.
inline void CatchStopSignals() {
  const auto note = [](int signal) { g_stop_signal = signal; };
  std::signal(SIGINT, note);
  std::signal(SIGTERM, note);
}

/// "SIGINT" or "SIGTERM" once one came, else "".
inline std::string StopSignalName() {
  if (g_stop_signal == SIGINT) return "SIGINT";
  if (g_stop_signal == SIGTERM) return "SIGTERM";
  return "";
}

}  // namespace vmt::sim
