#pragma once
// The PLC programs vmt ships, chosen by name in a scene (`plc: {program: NAME}`). Each is the
// PLC program of a manual, written against the runtime (plc_runtime.hpp) with the manual's
// signal and marker names; programs resolve their signals once, when they are made.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "control/gateway/signal_image.hpp"
#include "control/measure/measuring_pages.hpp"
#include "control/plc/plc_runtime.hpp"

namespace vmt::control::plc {

/// The names of the shipped programs, for error messages and `--help`.
std::vector<std::string> PlcProgramNames();

/// The program called `name`, wired to the signals of `image`'s table. nullopt if no program
/// has that name; throws std::invalid_argument naming the signal if the machine lacks one the
/// program needs. `measuring_pages`: the NC's machine data pages, which probe_block reads
/// (MTD_RD); not owned, null: none.
std::optional<PlcProgram> MakePlcProgram(std::string_view name, const gateway::SignalImage& image,
                                         const measure::MeasuringPages* measuring_pages = nullptr);

}  // namespace vmt::control::plc
