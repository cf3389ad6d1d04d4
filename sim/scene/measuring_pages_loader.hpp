#pragma once
// The scene's `measuring_pages:` (docs/scene-format.md): TASTWERKZEUGPAGE and EICHWERTEPAGE of
// fast measurement as the operator enters them before the program runs (3.1: "the user must
// enter all the elements in this page"), and, where the scene does not, the stylus pages from
// the model's `probe:` (the styluses it has).

#include "control/axes/tool_table.hpp"
#include "control/measure/measuring_pages.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::sim {

class YamlNode;

/// TASTWERKZEUGPAGE 1.. from the model's styluses in their order: T number, contact, pin and
/// the sphere radii (mm).
void PresetStylusPages(const MachineModel& m, control::measure::MeasuringPages& pages);

/// Reads `measuring_pages:` into `pages`; a `stylus:` list replaces every stylus page. A stylus
/// must be in `tools` (3.1: it is handled like a tool). Throws ModelError with the YAML path.
void LoadMeasuringPages(const YamlNode& node, const control::axes::ToolTable& tools,
                        control::measure::MeasuringPages& pages);

}  // namespace vmt::sim
