#include "control/plc/plc_programs.hpp"

#include "control/plc/programs/c_axis_changeover.hpp"
#include "control/plc/programs/machine_panel.hpp"
#include "control/plc/programs/probe_block.hpp"
#include "control/plc/programs/repos_machine_keys.hpp"

namespace vmt::control::plc {
namespace {

struct Entry {
  std::string_view name;
  PlcProgram (*make)(const gateway::SignalImage&, const measure::MeasuringPages*);
};

template <typename Program>
PlcProgram Make(const gateway::SignalImage& image, const measure::MeasuringPages*) {
  return Program(image);
}

PlcProgram MakeProbeBlock(const gateway::SignalImage& image,
                          const measure::MeasuringPages* measuring_pages) {
  ProbeBlockProgram program(image);
  program.measuring_pages = measuring_pages;
  return program;
}

PlcProgram MakeNcTurretPanel(const gateway::SignalImage& image, const measure::MeasuringPages*) {
  return MachinePanel(image, true);
}

PlcProgram MakeWrongChangeover(const gateway::SignalImage& image, const measure::MeasuringPages*) {
  CAxisChangeoverConfig config;
  config.acknowledge_before_clutch = true;
  return CAxisChangeover(image, config);
}

constexpr Entry kPrograms[] = {
    {"repos_machine_keys", &Make<ReposMachineKeys>},
    {"c_axis_changeover", &Make<CAxisChangeover>},
    {"c_axis_changeover_wrong", &MakeWrongChangeover},
    {"probe_block", &MakeProbeBlock},
    {"machine_panel", &Make<MachinePanel>},
    {"machine_panel_nc_turret", &MakeNcTurretPanel},
};

}  // namespace

std::vector<std::string> PlcProgramNames() {
  std::vector<std::string> names;
  for (const Entry& e : kPrograms) names.emplace_back(e.name);
  return names;
}

std::optional<PlcProgram> MakePlcProgram(std::string_view name, const gateway::SignalImage& image,
                                         const measure::MeasuringPages* measuring_pages) {
  for (const Entry& e : kPrograms)
    if (name == e.name) return e.make(image, measuring_pages);
  return std::nullopt;
}

}  // namespace vmt::control::plc
