#pragma once
// The scene's `workpiece:` (docs/scene-format.md): a stock cylinder, or the sections of a part
// whose true dimensions a measuring scene knows, made oversize or undersize by `oversize:`.

#include "sim/scene/scene.hpp"

namespace vmt::sim {

class YamlNode;

/// Throws ModelError with the YAML path of the fault.
Workpiece LoadWorkpiece(const YamlNode& w, const MachineModel& m);

}  // namespace vmt::sim
