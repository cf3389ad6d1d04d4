#pragma once
// The faults a timeline injects between the machine and the control (`fault:` steps), as two
// filters of the tick: on the way in a stuck sensor reads its stuck level and a faulted drive
// reports itself not ready; on the way out a stuck valve stays where it is whatever the PLC
// commands and a faulted drive's power stage is off, so its axis coasts.

#include "control/drive_bus.hpp"
#include "sim/scene/steps/timeline_play.hpp"

namespace vmt::sim {

class FaultFilter {
 public:
  /// The machine's telegram `raw` as the control sees it: `raw` itself while no fault was
  /// ever injected, else a filtered copy valid until the next call.
  const control::AmplifierTelegram& In(const control::AmplifierTelegram& raw,
                                       const InjectedFaults& f);
  /// The control's commands as the machine gets them.
  static void Out(const InjectedFaults& f, control::MasterTelegram& mdt);
  /// The last filtered copy: empty until a fault was injected.
  const control::AmplifierTelegram& filtered() const { return filtered_; }

 private:
  control::AmplifierTelegram filtered_;
};

}  // namespace vmt::sim
