#pragma once
// Main spindle mode <-> rotary axis mode of one headstock (C-axis manual): either a main spindle
// drive with rotary axis capability that switches between speed and position control and its
// drive parameter set (section 2), or a main spindle plus a separate servo drive engaged by a
// machine mechanism such as a dog clutch (section 3). The NC side of figures 4-1 / 4-2:
//  (1) activate: a block or a manual command needs the other mode (Request);
//  (2) internal changeover: the drives decelerate to standstill in speed control, the drive
//      parameter set of the new mode is activated;
//  (3) external changeover: ROTMOD or SPMOD to the PLC until it acknowledges with ROTMOD_Q or
//      SPMOD_Q; meanwhile the PLC's AXD motion functions (idents 65012..65015: hunting,
//      positioning, speed specification) run, and only then (4.2 note);
//  (4) deactivate, (5) position / speed control changeover (the position command value is
//      updated to the actual position), (6) the axis designation shown switches (S1 <-> C).
// The PLC's acknowledgement is a level held as long as the mode is selected (4.1): removing it
// in that mode is a process error. Controller enables are the PLC's (AxxC.READY, 4.3): a drive
// without it is in follow-up mode (its command tracks its actual position, no error).

#include <array>
#include <cstdint>
#include <string>
#include <utility>

#include "control/drive_bus.hpp"

namespace vmt::control::axes {

enum class HeadstockMode : uint8_t { kNone, kSpindle, kRotary };
const char* ToString(HeadstockMode mode);

enum class ChangeoverPhase : uint8_t {
  kNone,      ///< no changeover in progress
  kInternal,  ///< (2) decelerating, speed control, parameter set
  kExternal,  ///< (3) waiting for the PLC's acknowledgement; AXD motion functions run
};

/// Idents of the AXD data channel (2.2, 3.2), per drive: index 0..3 = 65012..65015.
inline constexpr int kAxdFunction = 0;  ///< 65012: bits 0..2 requests, 8..10 acknowledgements
inline constexpr int kAxdSpeed = 1;     ///< 65013: speed for the speed specification, 0.0001 rpm
inline constexpr int kAxdAccel = 2;     ///< 65014: acceleration for it, rad/s^2
inline constexpr int kAxdAngle = 3;     ///< 65015: angle for the positioning, 0.0001 deg
namespace axd {
inline constexpr int64_t kHunting = 1 << 0;
inline constexpr int64_t kPositioning = 1 << 1;
inline constexpr int64_t kSpeedSpec = 1 << 2;
inline constexpr int64_t kHuntingAck = 1 << 8;
inline constexpr int64_t kPositioningAck = 1 << 9;
inline constexpr int64_t kSpeedSpecAck = 1 << 10;
inline constexpr double kMaxSpeedRpm = 1000;  ///< 65013 "is limited to 1000 rpm"
}  // namespace axd

/// The headstock as the axis parameters describe it (drive indices on the DriveBus).
struct HeadstockConfig {
  int spindle_drive = -1;  ///< speed control, M3/M4/M5/M19
  /// Position control in rotary axis mode: a separate servo (section 3), or the spindle drive
  /// itself (section 2).
  int rotary_drive = -1;
  /// Section 2: the drive parameter set of rotary axis mode ("Parameter set in drive used for
  /// rotary mode", 0: no switch).
  uint8_t rotary_parameter_set = 0;
  /// Hunting (65012 bit 0): the drive oscillates at this speed (deg/s), reversing every
  /// hunting_half_period_s, so that dogs find their gaps without a net rotation.
  double hunting_speed = 6;
  double hunting_half_period_s = 0.25;
  /// Positioning (65012 bit 1) runs at this speed (deg/s) and is acknowledged within this
  /// window (deg).
  double positioning_speed = 36;
  double positioning_window = 0.1;
  /// An external changeover without the PLC's acknowledgement for this long (s) is reported
  /// (Stalled()): most often a clutch whose dogs meet tooth on tooth and no AXD motion function
  /// turns the drive to let them mesh.
  double stall_message_s = 5;

  bool separate_servo() const { return rotary_drive != spindle_drive; }
};

/// What the PLC gives the NC for the headstock, each NC cycle.
struct HeadstockPlc {
  bool rotmod_q = false, spmod_q = false;           ///< Axx.ROTMOD_Q / SPMOD_Q of the spindle
  bool spindle_ready = true, rotary_ready = true;   ///< AxxC.READY of the two drives (enables)
  std::array<int64_t, 4> spindle_axd{}, rotary_axd{};  ///< 65012..65015 of the two drives
  bool stop = false;  ///< immediate stop in force (PxxS.STOP): motion functions halt
};

class HeadstockChangeover {
 public:
  explicit HeadstockChangeover(const HeadstockConfig& config) : config_(config) {}

  /// Power-on and Control-Reset (2.3): the mode is the one the PLC acknowledges, neither if it
  /// acknowledges none (or both); a changeover in progress is abandoned.
  void TakeModeFromPlc(const HeadstockPlc& plc);
  /// (1): start a changeover to `target` unless the headstock is in that mode or changing to
  /// it. A request for the other mode during a changeover turns it round.
  void Request(HeadstockMode target);
  /// Reverse (2.3): the changeover is abandoned and the original mode restored (a changeover
  /// back is started if the internal changeover had already begun).
  void Abandon();

  /// One NC cycle. `at` is the drives' feedback. Returns false with error() set on a process
  /// error (an acknowledgement removed in its mode).
  bool Cycle(const HeadstockPlc& plc, const AmplifierTelegram& at, double dt_s);

  /// Setpoints of the two drives, for every cycle: during a changeover the sequence's, else
  /// `spindle` (the channel's M3/M4/M5/M19 command) for the spindle drive in spindle mode and
  /// `rotary` (the interpolated rotary axis) for the rotary drive in rotary mode; a drive
  /// without its enable is off, the other drive holds still.
  void WriteSetpoints(const DriveSetpoint& spindle, const DriveSetpoint& rotary,
                      MasterTelegram& mdt) const;

  HeadstockMode mode() const { return mode_; }
  /// The mode the changeover in progress goes to (mode() when none is).
  HeadstockMode target() const { return phase_ == ChangeoverPhase::kNone ? mode_ : target_; }
  ChangeoverPhase phase() const { return phase_; }
  bool busy() const { return phase_ != ChangeoverPhase::kNone; }
  /// ROTMOD / SPMOD (4.1): the pre-selection, from the external changeover on for as long as
  /// the mode is selected.
  bool rotmod() const { return Preselected(HeadstockMode::kRotary); }
  bool spmod() const { return Preselected(HeadstockMode::kSpindle); }
  /// 65012 as the drives answer it: the request bits with their acknowledgement bits set.
  int64_t SpindleFunctionWord() const { return spindle_fn_.word; }
  int64_t RotaryFunctionWord() const { return rotary_fn_.word; }
  /// True once after the changeover reached rotary axis mode: the channel takes the rotary
  /// axis' actual position as its command value (5).
  bool TakeOverRotary() { return std::exchange(take_over_rotary_, false); }
  const std::string& error() const { return error_; }
  /// Empty, or why the external changeover has waited stall_message_s for the PLC: the mode
  /// it waits for, and what the AXD idents the PLC wrote leave undone (no motion function
  /// requested, a speed specification with speed or acceleration 0).
  std::string Stalled() const;
  const HeadstockConfig& config() const { return config_; }

 private:
  /// An AXD motion function running on one drive.
  struct Function {
    int64_t word = 0;          ///< 65012 with acknowledgement bits
    /// What it commands this cycle. Until a function runs: speed control at zero, so that a
    /// changeover decelerates its drives from the first cycle on (4.2/4.3 internal changeover:
    /// the drive is braked, never let go; a drive without enable coasts, and the kinematic
    /// backend, having no inertia, would stop it dead).
    DriveSetpoint setpoint{DriveMode::kVelocity, 0, 0};
    double speed = 0;          ///< deg/s, ramped speed of the speed specification
    double hunting_s = 0;      ///< time into the hunting oscillation
    bool active = false;       ///< a function commands the drive
  };
  void RunFunction(Function& f, const std::array<int64_t, 4>& axd, const DriveFeedback& fb,
                   bool stop, double dt_s) const;
  void Enter(HeadstockMode target);
  /// The drive parameter set of a mode (section 2): the rotary one in rotary axis mode, else 0.
  uint8_t SetOf(HeadstockMode m) const {
    return m == HeadstockMode::kRotary ? config_.rotary_parameter_set : 0;
  }
  bool Preselected(HeadstockMode m) const {
    return (phase_ == ChangeoverPhase::kExternal && target_ == m) ||
           (phase_ == ChangeoverPhase::kNone && mode_ == m);
  }

  HeadstockConfig config_;
  HeadstockMode mode_ = HeadstockMode::kNone;
  HeadstockMode target_ = HeadstockMode::kNone;
  HeadstockMode before_ = HeadstockMode::kNone;  ///< the mode the changeover started from
  ChangeoverPhase phase_ = ChangeoverPhase::kNone;
  Function spindle_fn_, rotary_fn_;
  bool spindle_ready_ = true, rotary_ready_ = true;
  bool take_over_rotary_ = false;
  /// Section 2: the parameter set the one drive runs with. It changes only at standstill (the
  /// end of the internal changeover, 4.2): the rotary set's velocity limit is far below the
  /// spindle's speed, and a drive switched while turning faster trips (overspeed).
  uint8_t parameter_set_ = 0;
  std::string error_;
  double external_s_ = 0;                                ///< time in the external changeover
  std::array<int64_t, 4> spindle_axd_{}, rotary_axd_{};  ///< what the PLC wrote last
};

}  // namespace vmt::control::axes
