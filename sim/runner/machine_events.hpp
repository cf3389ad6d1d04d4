#pragma once
// The machine's changes as a run's events: every gateway signal that changes (either
// direction, as the PLC engineer traces it), clutch states and clashes, the machine's inputs,
// the drives' trips and parameter sets, and the probe latches as the drives fill them. The
// watch keeps what it saw last and hands each change to the recorder.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "control/drive_bus.hpp"
#include "control/gateway/signal_image.hpp"
#include "sim/backend/machine_backend.hpp"
#include "sim/model/machine_model.hpp"
#include "sim/runner/run_recorder.hpp"

namespace vmt::sim {

/// A drive's amplifier tripping (SERCOS status kOverload | kOverspeed | kParameterSetError):
/// when, which drive, and the fault bits that came with it.
struct DriveTrip {
  double t_s = 0;
  int drive = -1;
  uint32_t faults = 0;
};
/// "overload", "overspeed", "parameter_set_error", joined by " and ".
std::string TripCauses(uint32_t faults);

class MachineEventWatch {
 public:
  explicit MachineEventWatch(const MachineModel& model) : m_(&model) {}

  /// Only the signals `wanted` accepts (by name) make events from now on (RunOptions::
  /// signal_events); the clutches, inputs and drives are watched as ever.
  void SetSignalEvents(std::function<bool(const std::string&)> wanted) {
    signal_events_ = std::move(wanted);
    wanted_.clear();
  }

  /// This tick's changes at time `t`: `at` as the control sees it, `clutches` the backend's
  /// states; `image` null without a gateway.
  void Watch(double t, const control::AmplifierTelegram& at,
             const std::vector<ClutchState>& clutches, const MachineBackend& backend,
             const control::gateway::SignalImage* image, RunRecorder& recorder);
  /// Every trip of the run so far, in time order (a fault bit that comes while others stand is
  /// a trip of its own).
  const std::vector<DriveTrip>& trips() const { return trips_; }

 private:
  void WatchSignals(double t, const control::gateway::SignalImage& image, RunRecorder& recorder);
  void WatchClutches(double t, const std::vector<ClutchState>& clutches,
                     const MachineBackend& backend, RunRecorder& recorder);
  void WatchDrives(double t, const control::AmplifierTelegram& at, RunRecorder& recorder);

  const MachineModel* m_;
  std::function<bool(const std::string&)> signal_events_;
  std::vector<bool> wanted_;  ///< per signal of the image: signal_events_ accepts it
  std::vector<double> last_signals_;
  std::vector<int64_t> last_cells_;  ///< the image's cells when last_signals_ was taken
  uint64_t last_changes_ = 0;        ///< the image's change count then
  std::vector<ClutchState> last_clutches_;
  std::vector<int> last_clashes_;  ///< clashes of each clutch reported so far
  std::vector<uint8_t> last_inputs_;
  std::vector<uint32_t> last_faults_;  ///< per drive: its fault bits at the last tick
  std::vector<uint8_t> last_sets_;     ///< per drive: its current parameter set at the last tick
  std::vector<uint8_t> last_latches_;  ///< per drive: its probe latched flags at the last tick
  std::vector<DriveTrip> trips_;
};

}  // namespace vmt::sim
