#pragma once
// The probe switches of a machine and the drives' probe inputs they are wired to (machine.yaml
// drive key `probe_inputs:`), shared by both backends: one ProbeLatch per drive, stepped every
// drive tick, and the sub-tick instant of each switch change so that every latch wired to the
// switch knows where its axis really was at the contact.
//
// The switch is one contact for the PLC and the drives (fast-measurement manual 7.2: "The probe
// contact is connected to the controller and to the SPS input"): SetSwitch sets the I/O input
// the PLC reads as well. Whoever models the switch (the stylus) calls it with the instant of the
// change within the tick being stepped; a change of any other input wired to a drive (a cam
// switch, a clutch switch) has no sub-tick instant and counts at the tick's end.

#include <cstdint>
#include <vector>

#include "control/drive_bus.hpp"
#include "sim/backend/drive_controller.hpp"
#include "sim/backend/probe_latch.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::sim {

/// Fast-measurement manual 7.3: the drive scans its probe inputs every 250 us and generates the
/// actual position value it latches every 250 us, at most about 170 us away from the edge. vmt
/// acquires that value 80 us before the input sample that sees the edge: the edge lies up to
/// one period before the sample, so the position is taken between 170 us after and 80 us
/// before the edge.
inline constexpr double kProbeSamplePeriodS = 250e-6;
inline constexpr double kLatchMaxDelayS = 170e-6;
inline constexpr double kLatchPositionLeadS = kProbeSamplePeriodS - kLatchMaxDelayS;

/// Where within the drive's sampling period a contact falls. Off: the drive's 250 us clock runs
/// with the simulation's ticks, so a contact reached on the same path at the same feed falls at
/// the same point of the period and is latched with the same error (calibration cancels it).
/// Seeded: the drive's clock stands at a random phase to the contact, different for every
/// switch change, as on a real machine, where repeated measurements scatter by up to one
/// period times the feed. Deterministic for a given seed (scene `probe: sampling_phase:`).
struct ProbeSamplingPhase {
  bool seeded = false;
  uint64_t seed = 0;
};

class ProbeWiring {
 public:
  explicit ProbeWiring(const MachineModel& model);

  /// Every drive's unquantised actual position at t = 0 (ActualPositions): where the first
  /// tick's interpolation starts.
  void Start(const std::vector<double>& positions) { positions_before_ = positions; }

  /// The sampling-phase model; off until set. Restarts the seeded sequence.
  void SetSamplingPhase(const ProbeSamplingPhase& phase);

  /// Whether any drive has a probe input wired: without, Step has nothing to do.
  bool any() const { return any_; }
  /// The drives with a probe input wired, in drive order: the positions Step reads.
  const std::vector<int>& wired() const { return wired_; }

  /// The switch on I/O input `io_input` changes to `level` at `tick_fraction` (0..1, clamped)
  /// of the tick being stepped, i.e. at time_s() + tick_fraction x 250 us when called between
  /// ticks, or within a backend's Step before the drives sample. A level equal to the present
  /// one changes nothing; of several changes within one tick the last one's instant counts.
  /// Throws std::invalid_argument for an index that is not a machine input a device leaves
  /// alone (an output, an operator's key, a clutch, actuator or cam switch).
  void SetSwitch(int io_input, bool level, double tick_fraction);

  /// The switches' levels into the inputs the machine shows (after MachineInputs::Read).
  void ShowInputs(std::vector<uint8_t>& inputs) const;

  /// One drive tick, after the feedback of the tick is computed: each wired drive's latch
  /// samples its inputs (`inputs`: the machine's inputs of this tick) with the setpoints' probe
  /// control and writes DriveFeedback::probe. `positions`: per drive, the unquantised actual
  /// position of this tick (ActualPositions), for the exact position at a change; only the
  /// wired() drives' entries are read.
  void Step(const std::vector<control::DriveSetpoint>& setpoints,
            const std::vector<uint8_t>& inputs, const std::vector<double>& positions,
            std::vector<control::DriveFeedback>& feedback);

 private:
  struct Switch {
    bool level = false;
    bool changed = false;  ///< changed in the tick being stepped
    double fraction = 1;   ///< of the last change in that tick
    /// Seeded sampling phase: from the last change to the input sample that sees it, in
    /// periods, [0, 1).
    double sample_wait = 0;
  };

  /// The next number of the seeded sequence, uniform in [0, 1).
  double NextPhase();

  // Step and ShowInputs run every tick: they visit the few wired drives, set switches and
  // changes only, not every drive and I/O point of the machine.
  const MachineModel* model_;
  bool any_ = false;
  std::vector<int> wired_;         ///< the drives with a probe input wired, in drive order
  std::vector<uint8_t> settable_;  ///< per I/O point: SetSwitch may set it
  std::vector<uint8_t> set_;       ///< per I/O point: SetSwitch has set it
  std::vector<int> set_points_;    ///< the I/O points SetSwitch has set
  std::vector<Switch> switches_;   ///< per I/O point
  std::vector<int> changed_;       ///< the I/O points whose switch changed in this tick
  std::vector<ProbeLatch> latches_;
  std::vector<double> positions_before_;  ///< per drive, read and kept for wired drives only
  ProbeSamplingPhase phase_;
  uint64_t phase_state_ = 0;  ///< SplitMix64 state of the seeded sequence
};

/// Every drive's actual position, unquantised, in machine units (mm | deg) and the drive's own
/// scaling (within [0, modulo) for a modulo drive): what its encoder would read with infinite
/// resolution. `joint_position(j)` gives joint j's position in SI.
template <typename JointPosition>
void ActualPositions(const MachineModel& model, const JointPosition& joint_position,
                     std::vector<double>& positions);

/// The same for `drives` only (indices into model.drives); the other entries of `positions`
/// (one per drive) stay as they are. A backend steps the probe wiring with its wired() drives'.
template <typename JointPosition>
void ActualPositions(const MachineModel& model, const JointPosition& joint_position,
                     const std::vector<int>& drives, std::vector<double>& positions);

/// One drive's (see ActualPositions).
double ActualPosition(const DriveParams& p, double encoder_position_si);

template <typename JointPosition>
void ActualPositions(const MachineModel& model, const JointPosition& joint_position,
                     std::vector<double>& positions) {
  positions.resize(model.drives.size());
  for (size_t d = 0; d < model.drives.size(); ++d) {
    const DriveParams& p = model.drives[d];
    positions[d] = ActualPosition(p, EncoderPosition(p, joint_position));
  }
}

template <typename JointPosition>
void ActualPositions(const MachineModel& model, const JointPosition& joint_position,
                     const std::vector<int>& drives, std::vector<double>& positions) {
  positions.resize(model.drives.size());
  for (const int d : drives) {
    const DriveParams& p = model.drives[d];
    positions[d] = ActualPosition(p, EncoderPosition(p, joint_position));
  }
}

}  // namespace vmt::sim
