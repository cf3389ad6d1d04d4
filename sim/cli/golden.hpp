#pragma once
// vmt golden check|update: image regression for scenes. Each scene runs as `vmt run` runs it
// (or an earlier run's output folder is taken as it is), and every snapshot the run wrote (its
// `snapshot` events) is compared with GOLDEN/<scene>/<file> at the project's tolerance
// (render/image_compare.hpp) or the snapshot's own (mask:, allowed_fraction:,
// tolerance_levels:). `update` writes the baselines; `check` fails on a picture that differs,
// a baseline that is missing (unless --create-missing) and a baseline no snapshot wrote.
// Results go to the console, optionally JUnit XML and JSON; a failing picture leaves a page
// with golden, actual and difference side by side (sim/cli/golden_report.hpp).

#include <functional>
#include <utility>
#include <vector>

namespace CLI {
class App;
}

namespace vmt::sim {

/// Registers `vmt golden` and its `check` and `update` subcommands: each with what it does once
/// the command line is parsed (its exit code: 0 all pass, 1 a failure, 2 bad input).
std::vector<std::pair<CLI::App*, std::function<int()>>> AddGoldenCommands(CLI::App& app);

}  // namespace vmt::sim
