#pragma once
// The contact sheets of a run's snapshot series (scene `snapshots: - {every: ...}`): one PNG
// grid per series, beside its pictures, each picture captioned with its time.

#include <string>
#include <vector>

#include "sim/scene/scene.hpp"

namespace vmt::sim {

/// Writes out_dir/<series.sheet> for each of the scene's series from the pictures of it that
/// the run wrote (`written`: the paths of this run's snapshots; a series cut short by the end
/// of the run shows the pictures it has, none: no sheet). Returns the sheets' paths. Throws
/// std::runtime_error when a picture cannot be read or the sheet written.
std::vector<std::string> WriteContactSheets(const Scene& scene, const std::string& out_dir,
                                            const std::vector<std::string>& written);

}  // namespace vmt::sim
