#pragma once
// What the timeline's steps act on while it plays: the drives' setpoints and profiles, the
// valves, the faults injected, the NC channel and the gateway signals. The timeline player
// (sim/runner/timeline_player.hpp) owns it; each step kind (step_kind.hpp) changes its part.

#include <cstdint>
#include <string>
#include <vector>

#include "control/drive_bus.hpp"
#include "control/gateway/signal_image.hpp"
#include "sim/scene/scene.hpp"

namespace vmt::sim {

struct ProgramEvent {
  double t_s;
  std::string kind;  ///< step | step_done | timeout
  std::string text;
};

/// A point-to-point profile: trapezoidal velocity, acceleration-limited.
struct TrapezoidProfile {
  double start = 0, end = 0, speed = 0, accel = 0, t0_s = 0;
  double Duration() const;
  double At(double t_s) const;
};

/// Faults the timeline has injected and not cleared (TimelineStep::Fault); the runner applies
/// them between the machine and the control.
struct InjectedFaults {
  std::vector<int8_t> sensor;    ///< per I/O point: -1 none, else the level it is stuck at
  std::vector<int8_t> valve;     ///< per I/O point: -1 none, else the level it stays at
  std::vector<bool> drive;       ///< per drive: power stage off, not ready
  int64_t plc_missed_scans = 0;  ///< scans the PLC is yet to miss (set by an overrun fault)
  /// client_gone steps so far: from the first on the PLC's link is gone for good (embedded: it
  /// misses every scan; vmt serve drops its Modbus clients once per step).
  int plc_client_gone = 0;
  bool any = false;
};

/// The state the timeline's steps write, kept between ticks.
struct TimelinePlay {
  const MachineModel* model = nullptr;
  control::channel::Channel* channel = nullptr;   ///< may be null: NC steps do nothing
  control::gateway::SignalImage* image = nullptr;  ///< may be null: signal steps do nothing
  std::vector<control::DriveSetpoint> setpoints;
  std::vector<TrapezoidProfile> profiles;
  std::vector<uint8_t> profiling;  ///< per drive: its setpoint follows profiles[drive]
  std::vector<uint8_t> outputs;
  InjectedFaults faults;
  std::vector<std::string> failures;  ///< steps that did not complete, as messages
};

/// The tick a step plays in: its time, when the step began (equal to t_s in its first tick),
/// the machine's feedback of the last tick, and where its events go.
struct StepTick {
  double t_s;
  double since_s;
  const control::AmplifierTelegram& at;
  const std::vector<ClutchState>& clutches;
  std::vector<ProgramEvent>& events;
};

/// Evaluates a condition on the machine's feedback (and the channel and the gateway signals,
/// if there are).
bool Holds(const Condition& c, const control::AmplifierTelegram& at,
           const std::vector<ClutchState>& clutches, const control::channel::Channel* channel,
           const control::gateway::SignalImage* image);

}  // namespace vmt::sim
