#pragma once
// `vmt study sbatch` (a study as a Slurm array job of shards and a merge job after it) and
// `vmt study status` (which cases a study folder, its shards or a Slurm study still lacks).

#include <functional>
#include <utility>
#include <vector>

namespace CLI {
class App;
}

namespace vmt::sim {

/// Registers both under `study`: each with what it does once the command line is parsed (its
/// exit code; status: 0 complete, 1 cases missing, 2 bad input).
std::vector<std::pair<CLI::App*, std::function<int()>>> AddStudySlurmCommands(CLI::App& study);

}  // namespace vmt::sim
