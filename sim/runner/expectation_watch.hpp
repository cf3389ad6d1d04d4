#pragma once
// The scene's expectations (`expect:`) as a run goes: each is checked once, when its time comes
// (an untimed one at the run's last tick), and its result recorded as an event. At the run's end
// an expectation never reached fails, and so does a drive trip or an NC error the scene does not
// expect.

#include <limits>
#include <string>
#include <vector>

#include "control/channel/channel.hpp"
#include "control/drive_bus.hpp"
#include "control/gateway/signal_image.hpp"
#include "sim/model/machine_model.hpp"
#include "sim/runner/expectation_result.hpp"
#include "sim/runner/machine_events.hpp"
#include "sim/runner/run_recorder.hpp"
#include "sim/scene/scene.hpp"

namespace vmt::sim {

/// What an expectation reads at its tick.
struct ExpectationInputs {
  const control::AmplifierTelegram& at;
  const std::vector<ClutchState>& clutches;
  const control::channel::Channel* channel;  ///< null without NC
  const control::gateway::SignalImage* image;  ///< null without signals
  const std::vector<DriveTrip>& trips;  ///< the drive trips so far
};

class ExpectationWatch {
 public:
  ExpectationWatch(const std::vector<Expectation>& expectations, const MachineModel& m);

  /// Whether an expectation is due at `t` (or the run is at its last tick): before then the
  /// tick need not gather the inputs.
  bool Due(double t, bool last_tick) const {
    return last_tick || t >= next_s_ - 1e-9;
  }
  /// Checks those due at `t` and records each result as an event "expectation".
  void Check(double t, bool last_tick, const ExpectationInputs& in, RunRecorder& recorder);
  /// The results at the run's end (those never checked: "not reached"), in the scene's order.
  const std::vector<ExpectationResult>& Close();
  /// After Close: each expectation that did not hold, as a failure of the run.
  std::vector<std::string> NotHeld() const;
  /// The NC error (`channel_error`; empty: none) and each drive trip the scene does not expect,
  /// as failures of the run: a protection that takes a power stage off is a fault of the
  /// machine or of the program unless the scene means it (`expect: {drive:, trip:}`).
  std::vector<std::string> Unexpected(const std::vector<DriveTrip>& trips,
                                      const std::string& channel_error) const;

 private:
  const std::vector<Expectation>* expectations_;
  const MachineModel* m_;
  std::vector<bool> checked_;
  std::vector<ExpectationResult> results_;
  /// The earliest time an unchecked timed expectation is due.
  double next_s_ = -std::numeric_limits<double>::infinity();
};

}  // namespace vmt::sim
