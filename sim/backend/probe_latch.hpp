#pragma once
// The probe evaluation of one digital drive (fast-measurement manual 7.3, "Probe Function in the
// DDS"): two probe inputs, E4 (PIN4, probe 1) and E5 (PIN5, probe 2), sampled every 250 us
// drive tick; on an edge the drive stores its actual position value of that tick.
//
// The rules, as 7.3 gives them:
// - S-0-0170 'Probe cycle command' = 3 activates the function; from then on S-0-0401/0402 show
//   the inputs' levels. Any other value switches it off: levels, flags and values read 0 and
//   the inputs are disarmed (a command that is cancelled ends what it started).
// - The 0-1 transition of S-0-0405 / S-0-0406 (enable) arms its input, and only while the
//   function is active: an enable already set when S-0-0170 becomes 3 needs 0 then 1.
// - After arming, only the first positive (0-1) and the first negative (1-0) edge that
//   S-0-0169 selects are latched: S-0-0409..0412 set, S-0-0130..0133 take the actual position
//   value acquired for the sample that saw the edge (ProbeInputSample::acquired_position, else
//   the tick's). Later edges change nothing.
// - Clearing the enable clears its input's flags and measured values; a new measurement needs
//   the enable 0 and back to 1.
// - An edge is a change between two samples: a change and its return within one tick is not
//   seen (the drive samples, it does not interrupt). The enable of this tick's setpoint is valid
//   from the tick's start, so an edge sampled in the tick that arms is latched.
// - The positive measured value belongs to the 0-1 edge (the SERCOS names; the manual's "1-0"
//   sentence contradicts them, docs/fast-measurement.md).

#include <array>
#include <optional>

#include "control/drive_bus.hpp"

namespace vmt::sim {

/// One probe input as the drive samples it at a tick.
struct ProbeInputSample {
  bool level = false;  ///< the input's level at this tick
  /// Where the axis was (mm | deg, unquantised) at the instant of the input's last change since
  /// the previous tick: vmt's truth beside the measured value. Read only when the level differs
  /// from the previous tick's.
  double exact_position = 0;
  /// The drive's actual position value acquired for a change in this tick (mm | deg, quantised
  /// as DriveFeedback::position): 7.3 puts the position measurement up to about 170 us from the
  /// edge (ProbeWiring). None: the tick's actual position value.
  std::optional<double> acquired_position;
};

class ProbeLatch {
 public:
  /// One 250 us tick: the master's probe parameters and enables of this tick, PIN4 and PIN5 as
  /// sampled now, and the drive's actual position value of this tick (DriveFeedback::position,
  /// mm | deg). Returns false when status() is the same as before the tick: the function was
  /// off and stays off (most ticks of a run), so whoever shows it need not copy it again.
  bool Step(const control::ProbeControl& control, const std::array<ProbeInputSample, 2>& pins,
            double actual_position);

  /// S-0-0401/0402, S-0-0409..0412, S-0-0130..0133 after the last Step.
  const control::ProbeStatus& status() const { return status_; }

 private:
  struct Input {
    bool level_before = false;   ///< the previous tick's sample
    bool enable_before = false;  ///< the previous tick's enable
    bool armed = false;          ///< enable 0-1 seen while active, not cleared since
  };

  std::array<Input, 2> inputs_;
  control::ProbeStatus status_;
  bool off_ = true;  ///< the function was off in the last tick: nothing armed, status_ all clear
};

}  // namespace vmt::sim
