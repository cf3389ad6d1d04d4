#pragma once
// The drive-level test program: until the NC kernel drives the machine, a scene's timeline
// commands the drives directly (move an axis along a trapezoidal profile, run a spindle, orient
// it, switch a controller enable off, set a valve, wait for a time or a signal).

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

class DriveProgram {
 public:
  /// `feedback` gives the state at t = 0: servos hold their position, spindles stand at 0.
  /// `channel` (may be null) receives the timeline's NC steps.
  /// `image` (may be null): the gateway signals the timeline's `signal:` steps write, as the
  /// default PLC passing panel keys to the NC would.
  DriveProgram(const Scene& scene, const control::AmplifierTelegram& feedback,
               control::channel::Channel* channel = nullptr,
               control::gateway::SignalImage* image = nullptr);

  /// One drive tick at time t: advances the timeline on the feedback of the last tick and fills
  /// the MDT to write. Events are appended to `events`.
  void Tick(double t_s, const control::AmplifierTelegram& at,
            const std::vector<ClutchState>& clutches, control::MasterTelegram& mdt,
            std::vector<ProgramEvent>& events);

  bool finished() const { return next_ >= scene_->timeline.size(); }
  InjectedFaults& faults() { return faults_; }
  /// Steps that did not complete (wait_until timeouts), as messages.
  const std::vector<std::string>& failures() const { return failures_; }

 private:
  bool Execute(const TimelineStep& step, double t_s, const control::AmplifierTelegram& at,
               const std::vector<ClutchState>& clutches, std::vector<ProgramEvent>& events);

  const Scene* scene_;
  control::channel::Channel* channel_;
  control::gateway::SignalImage* image_;
  std::vector<control::DriveSetpoint> setpoints_;
  std::vector<TrapezoidProfile> profiles_;
  std::vector<bool> profiling_;
  std::vector<uint8_t> outputs_;
  size_t next_ = 0;
  double step_since_s_ = -1;  ///< when the current blocking step began
  std::vector<std::string> failures_;
  InjectedFaults faults_;
};

/// Evaluates a condition on the machine's feedback (and the channel and the gateway signals,
/// if there are).
bool Holds(const Condition& c, const control::AmplifierTelegram& at,
           const std::vector<ClutchState>& clutches, const control::channel::Channel* channel,
           const control::gateway::SignalImage* image);

/// A signal's value as a number (BOOL 0/1; STRING 0).
double SignalNumber(const control::gateway::SignalImage& image, int id);
/// Writes a number into a signal of any numeric type (BOOL: != 0).
void SetSignalNumber(control::gateway::SignalImage& image, int id, double value);

}  // namespace vmt::sim
