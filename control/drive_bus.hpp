#pragma once
// DriveBus: the cyclic telegram between the control kernel and the machine, as SERCOS carries
// it. Every drive cycle (250 us) the master writes one MDT (master data telegram: a setpoint per
// drive plus the digital outputs) and reads one AT (amplifier telegram: feedback per drive plus
// the digital inputs). The control kernel knows the machine only through this and PathGuard.
//
// Units at this interface are machine units: linear axes mm, mm/s, N; rotary axes and spindles
// degrees, deg/s, N m. Positions and velocities are load-side (spindle, not motor).

#include <cstdint>
#include <string>
#include <vector>

namespace vmt::control {

/// What a drive's controller follows this cycle.
enum class DriveMode : uint8_t {
  kOff,       ///< no controller enable: the motor is torque-free, the axis coasts
  kPosition,  ///< value = position command (mm | deg), cyclically updated by the master
  kVelocity,  ///< value = velocity command (mm/s | deg/s); spindles ramp at their acceleration
  kTorque,    ///< value = torque command (N | N m), limited by the drive's torque limit
};

/// Linear axes move in mm, rotary axes and spindles in degrees.
enum class AxisKind : uint8_t { kLinear, kRotary };

/// The drive's probe function (fast-measurement manual 7.3), as the master sets it. QMFB1Axx
/// writes S-0-0169 and S-0-0170 over the service channel (AXD_WR, 7.2) and switches the enable
/// through the real-time control bit it allocates (S-0-0303: AxxC.QDDS). The defaults leave the
/// function off.
struct ProbeControl {
  /// S-0-0170 Probe cycle command: 3 activates the function (7.3: "must be set to 3"); from
  /// then on the inputs' levels show in S-0-0401/0402. Any other value switches it off.
  uint8_t probe_cycle_command = 0;
  /// S-0-0169 Probe control parameter: which edges latch, bits probe_control::k* (the SERCOS
  /// layout of IDN 169; the manual's figure 7-30 is missing).
  uint16_t probe_control_parameter = 0;
  bool probe1_enable = false;  ///< S-0-0405 Probe-1 enable: its 0-1 transition arms probe 1
  bool probe2_enable = false;  ///< S-0-0406 Probe-2 enable
};

/// Bits of ProbeControl::probe_control_parameter (S-0-0169), as SERCOS lays out IDN 169.
namespace probe_control {
inline constexpr uint16_t kProbe1Positive = 1u << 0;  ///< probe 1: latch the 0-1 edge
inline constexpr uint16_t kProbe1Negative = 1u << 1;  ///< probe 1: latch the 1-0 edge
inline constexpr uint16_t kProbe2Positive = 1u << 2;  ///< probe 2: latch the 0-1 edge
inline constexpr uint16_t kProbe2Negative = 1u << 3;  ///< probe 2: latch the 1-0 edge
/// S-0-0170's value that activates the probe function.
inline constexpr uint8_t kProbeCycleActive = 3;
}  // namespace probe_control

struct DriveSetpoint {
  DriveMode mode = DriveMode::kOff;
  double value = 0;
  /// Drive parameter set (SERCOS S-0-0217, 0..7); selects gains and limits from the machine
  /// YAML (drive key parameter_sets; set 0 is the drive's own keys). A switch acts in the cycle
  /// that names the new set; only at standstill is it bumpless. A set the drive does not have
  /// trips it (kParameterSetError). In a set of type servo, position mode follows `value` as
  /// an absolute (not wrapped) position; in a spindle set it orients to `value` modulo 360 (M19).
  uint8_t parameter_set = 0;
  /// Position mode: velocity feed-forward added to the position loop's output, mm/s | deg/s
  /// (the control's low-lag interpolation, MTC200 G06: the following error falls to ~0).
  double velocity_feedforward = 0;
  /// Position mode of a spindle set: follow `value` as the NC's cyclic, interpolated absolute
  /// position command (not wrapped), like a servo, instead of orienting to it (M19). Rigid
  /// tapping (G64) interpolates the spindle this way; a servo set ignores the flag.
  bool interpolated = false;
  /// The probe function's parameters and enables (7.3); default off.
  ProbeControl probe{};
};

/// Status bits of DriveFeedback::status.
namespace drive_status {
inline constexpr uint32_t kReady = 1u << 0;        ///< powered, no fault
inline constexpr uint32_t kEnabled = 1u << 1;      ///< controller enable active
inline constexpr uint32_t kInPosition = 1u << 2;   ///< |command - actual| < in-position window
inline constexpr uint32_t kStandstill = 1u << 3;   ///< |velocity| < standstill window
inline constexpr uint32_t kAtSpeed = 1u << 4;      ///< velocity mode: actual == command (ramp done)
inline constexpr uint32_t kTorqueLimit = 1u << 5;  ///< output saturated at the torque limit
inline constexpr uint32_t kFollowingError = 1u << 6;  ///< following error above its limit
// Drive faults. Each trips the drive: power stage off (the axis coasts), kReady and kEnabled
// clear. A fault latches until a setpoint with mode kOff (controller enable removed: the drive's
// fault reset) arrives once its cause is gone.
inline constexpr uint32_t kOverload = 1u << 7;   ///< net time at the torque limit > overload_time
inline constexpr uint32_t kOverspeed = 1u << 8;  ///< |velocity| > 1.2 x the velocity limit
inline constexpr uint32_t kParameterSetError = 1u << 9;  ///< setpoint names a set it does not have
// Threshold status bits of a drive (SERCOS status parameters; the C-axis manual's spindle
// signals AxxS.MD_MDX, P_PX, LOAD90, 4.2). Each stays 0 on a drive that has no threshold set.
/// |Md| >= Mdx: the torque at or above the drive's torque threshold (S-0-0333, Mdx S-0-0126).
inline constexpr uint32_t kTorqueThreshold = 1u << 10;
/// |P| >= Px: the mechanical power |torque x velocity| at or above the drive's power threshold
/// (S-0-0337, Px S-0-0158).
inline constexpr uint32_t kPowerThreshold = 1u << 11;
/// 90 % load: |torque| at or above 90 % of the active parameter set's torque limit.
inline constexpr uint32_t kLoad90 = 1u << 12;
}  // namespace drive_status

/// One edge's latch of a probe input: S-0-0409..0412 and S-0-0130..0133.
struct ProbeEdgeLatch {
  bool latched = false;  ///< 'Probe-n positive/negative latched'
  /// 'Measured value n positive/negative', mm | deg: the drive's actual position value (as
  /// DriveFeedback::position) of the 250 us tick whose sample saw the edge.
  double measured_value = 0;
  /// Not a SERCOS parameter but vmt's truth: where the axis was (unquantised, same scaling as
  /// the measured value) at the instant the input changed. measured_value - exact_position is
  /// the drive's sampling error, up to the feed x 250 us plus half an encoder increment.
  double exact_position = 0;
};

/// One probe input of the drive (PIN4 = probe 1, PIN5 = probe 2).
struct ProbeInputStatus {
  bool level = false;         ///< S-0-0401 'Probe-1' / S-0-0402 'Probe-2', while S-0-0170 = 3
  ProbeEdgeLatch positive{};  ///< 0-1 edge: S-0-0409 / S-0-0130 (probe 1), S-0-0411 / S-0-0132
  ProbeEdgeLatch negative{};  ///< 1-0 edge: S-0-0410 / S-0-0131 (probe 1), S-0-0412 / S-0-0133
};

/// The drive's probe function as the master reads it (7.3); all clear while it is off.
struct ProbeStatus {
  ProbeInputStatus probe1{};  ///< input E4 (PIN4)
  ProbeInputStatus probe2{};  ///< input E5 (PIN5)
};

struct DriveFeedback {
  /// Encoder-quantised actual position (rotary: not wrapped): the position loop's encoder,
  /// which is a load-side (external) one on a drive that has it.
  double position = 0;
  /// The velocity loop's, i.e. the motor's, in load units (ratio applied), also on a drive with
  /// a load-side encoder: with the load uncoupled it shows the motor turning.
  double velocity = 0;
  double torque = 0;           ///< motor torque referred to the load
  double following_error = 0;  ///< position mode: command - actual
  uint32_t status = 0;
  /// The parameter set the drive works with (SERCOS S-0-0254, current parameter set): the one
  /// the setpoint last selected (S-0-0217) among the sets it has.
  uint8_t parameter_set = 0;
  /// The probe function's states, latched flags and measured values (7.3).
  ProbeStatus probe{};
};

/// One drive on the bus, as the machine YAML declares it.
struct DriveInfo {
  std::string name;  ///< the axis name of the manuals: X, Z, C, S1, S2, T, W
  AxisKind kind = AxisKind::kLinear;
};

/// One digital signal of the machine's I/O map (valves out, switches in).
struct IoInfo {
  std::string name;  ///< e.g. QROTMODE (out), IROTMODE (in), as in the C-axis manual's PLC program
  bool is_output = false;
  /// An operator's key (machine key table, repositioning manual 8.1): an input of the PLC that
  /// the operator presses, not the machine; the backends leave it alone.
  bool key = false;
  /// A selector (a key with positions): a multi-position switch of the operator panel, e.g. the
  /// feed override switch, whose position (an integer, one of these) the PLC reads.
  std::vector<int> positions;
  int initial = 0;  ///< a selector's position at the start
  bool selector() const { return !positions.empty(); }
  /// What the operator can set it to: a selector one of its positions, a key 0 or 1.
  bool PositionOk(double value) const {
    if (!selector()) return value == 0 || value == 1;
    for (const int p : positions)
      if (value == p) return true;
    return false;
  }
  /// "0/50/100" (a selector's positions, for messages).
  std::string PositionList() const {
    std::string s;
    for (const int p : positions) s += (s.empty() ? "" : "/") + std::to_string(p);
    return s;
  }
};

/// Master data telegram: written by the control every drive cycle.
struct MasterTelegram {
  std::vector<DriveSetpoint> setpoints;  ///< one per drive, in DriveBus::Drives() order
  std::vector<uint8_t> outputs;          ///< one per I/O point (inputs' entries are ignored)
};

/// Amplifier telegram: read by the control every drive cycle.
struct AmplifierTelegram {
  std::vector<DriveFeedback> feedback;  ///< one per drive
  std::vector<uint8_t> inputs;          ///< one per I/O point (outputs read back as written)
};

class DriveBus {
 public:
  virtual ~DriveBus() = default;
  virtual const std::vector<DriveInfo>& Drives() const = 0;
  virtual const std::vector<IoInfo>& Io() const = 0;
  /// Takes effect for the next drive cycle.
  virtual void Write(const MasterTelegram& mdt) = 0;
  /// The feedback of the last completed drive cycle.
  virtual const AmplifierTelegram& Read() const = 0;
};

/// Index of a drive or I/O point by name, or -1.
template <typename Info>
int IndexOf(const std::vector<Info>& infos, const std::string& name) {
  for (size_t i = 0; i < infos.size(); ++i)
    if (infos[i].name == name) return static_cast<int>(i);
  return -1;
}

}  // namespace vmt::control
