#pragma once
// The parts of a scene file that act over time: timeline steps (each kind in steps/) and
// expectations, and the look-ups of names they share. LoadScene reads the rest; these throw
// ModelError with the YAML path like it.

#include <string>
#include <vector>

#include "sim/scene/scene.hpp"

namespace vmt::sim {

class YamlNode;

/// An axis by its drive's name, or by the name of an NC axis of the machine (C on a main
/// spindle with rotary axis capability is drive S1). Fails at `n` if there is none.
int RequireDrive(const MachineModel& m, const YamlNode& n);
/// A load-side position of a drive (mm | deg) must lie within its joint's travel.
void RequireWithinTravel(const MachineModel& m, int drive, double value, const YamlNode& where);
/// A number as a message shows it (shortest form).
std::string Fmt(double v);

/// A gateway signal by its name (`vmt signals MODEL`). Fails at `n` if there is none.
int RequireSignal(const NcSetup& nc, const YamlNode& n);
/// A signal value as written in a scene: true/false for BOOL, a number otherwise.
double SignalValue(const NcSetup& nc, int id, const YamlNode& n);

/// The index of an NC channel axis named by its drive or NC axis name.
int RequireChannelAxis(const MachineModel& m, const NcSetup& nc, const YamlNode& n);
/// The axis of a jog or handwheel step: a channel axis (`s.axis`, `s.drive`), or X1 / Y1, the
/// fictive axes of the G31 face transformation (`s.fictive`).
void RequireJogAxis(const MachineModel& m, const NcSetup& nc, const YamlNode& n,
                    TimelineStep& s);
/// An I/O point of the machine by its name.
int RequireIo(const MachineModel& m, const YamlNode& n);
ClutchState ParseClutchState(const YamlNode& n);
control::channel::ChannelState ParseNcState(const YamlNode& n);

/// Timeline step `i`; with `plc` the timeline may only press keys.
TimelineStep ReadStep(const MachineModel& m, const YamlNode& n, size_t i, const NcSetup& nc,
                      bool plc);
/// `press: KEY` or `press: {name: KEY, for: S}` (step `i`): key down, and up after `for`
/// seconds (0.1 s).
std::vector<TimelineStep> ReadPress(const MachineModel& m, const YamlNode& n, size_t i,
                                    const NcSetup& nc);
/// Expectation `i`.
Expectation ReadExpectation(const MachineModel& m, const YamlNode& n, size_t i, const NcSetup& nc);

}  // namespace vmt::sim
