#pragma once
// The headstock as the channel runs it (C-axis manual 2.3, 3.3, 4.1-4.3): the changeover
// sequencer (axes::HeadstockChangeover) with what the channel keeps beside it - the PLC's side,
// the mode a block waits for, who commanded the changeover, the mode the operator is shown and
// the rotary axis' translation while spindle mode hides it.

#include <optional>
#include <string>
#include <utility>

#include "control/axes/headstock_changeover.hpp"
#include "control/drive_bus.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

/// What the channel tells the headstock of its own state each NC cycle.
struct HeadstockCycleInput {
  bool hold = false;            ///< the program is interrupted (PxxS.STOP's hold)
  bool failed = false;          ///< an error is pending
  bool process_enabled = true;  ///< PxxC.ENABL
  bool running = false;         ///< the program runs: a block may be waiting for its mode
};

/// A channel's headstock, or none (a channel without one answers every query as for a plain
/// spindle). A value: copied with the channel.
class HeadstockControl {
 public:
  explicit HeadstockControl(const std::optional<axes::HeadstockConfig>& config) {
    if (config) changeover_.emplace(*config);
  }

  explicit operator bool() const { return changeover_.has_value(); }
  /// The sequencer, for its state (mode, phase, functions); null without a headstock.
  const axes::HeadstockChangeover* changeover() const {
    return changeover_ ? &*changeover_ : nullptr;
  }
  const axes::HeadstockChangeover* operator->() const { return &*changeover_; }
  /// In `mode` now (false without a headstock).
  bool In(axes::HeadstockMode mode) const { return changeover_ && changeover_->mode() == mode; }
  /// A headstock outside rotary axis mode: its rotary axis follows the spindle.
  bool RotaryAxisOff() const { return changeover_ && !In(axes::HeadstockMode::kRotary); }

  /// The PLC's side (ROTMOD_Q, SPMOD_Q, enables, AXD idents), given every NC cycle.
  void SetPlc(const axes::HeadstockPlc& plc) { plc_ = plc; }
  /// 2.3 / 3.3 Power-On State: at the first NC cycle, the mode the PLC presents.
  void PowerOn();
  /// AxxC.READY of the drive that positions the rotary axis: the servo's (section 3), or the
  /// one axis' (section 2, the spindle's signal).
  bool RotaryReady() const;
  /// One NC cycle of the changeover. Immediate stop (2.3, 3.3) halts the PLC's motion
  /// functions and leaves ROTMOD / SPMOD pending while the program is interrupted (unless a
  /// manual key commanded the changeover after that), an error is pending or the process
  /// enabling signal is missing. The text of the PLC's failed acknowledgement (the channel
  /// fails with it) unless an error is pending already.
  std::optional<std::string> Cycle(const HeadstockCycleInput& in, const AmplifierTelegram& at,
                                   double dt_s);
  /// After Cycle: whether the rotary axis' command follows its actual position this cycle
  /// (the NC does not position it; its command is then current when rotary axis mode begins).
  bool RotaryFollowsFeedback();

  /// The mode `b` needs (4.2), kNone if none; `rotary_axis` is the channel's rotary axis.
  static axes::HeadstockMode ModeNeeded(const nc::PreparedBlock& b, int rotary_axis);
  /// The rotary axis as a PlanBlockMotion follow-up bit while the NC does not position it
  /// (outside rotary axis mode), 0 otherwise.
  uint64_t FollowUpAxes(const nc::PreparedBlock& b, int rotary_axis) const;
  /// A block needs `mode`: the changeover starts and the block waits for it.
  void RequestForBlock(axes::HeadstockMode mode);
  /// A jog key turned the changeover round: the waiting block commands its own again.
  void RequestAgain() { changeover_->Request(waiting_for_); }
  /// The mode the block in work waits for, kNone if it waits for none.
  axes::HeadstockMode waiting_for() const { return waiting_for_; }
  bool waiting() const { return waiting_for_ != axes::HeadstockMode::kNone; }
  /// The block has its mode: the mode it waited for.
  axes::HeadstockMode EndWait() { return std::exchange(waiting_for_, axes::HeadstockMode::kNone); }
  /// A changeover commanded by a manual key (jog of the rotary axis, spindle keys); the keys
  /// abort one an immediate stop interrupted (2.3 / 3.3 Jogging Movements).
  void ManualChangeover(axes::HeadstockMode target, bool program_stopped);
  /// The interrupted block is given up: so is its changeover, the original mode restored.
  void Abandon();
  /// Control-Reset, or a headstock drive failing in a changeover (2.3 Errors): the mode is
  /// again the one the PLC acknowledges, as at power-on.
  void TakeModeFromPlc();
  /// Control-Reset: a changeover is no longer a manual key's.
  void ForgetManual() { manual_ = false; }
  void WriteSetpoints(const DriveSetpoint& spindle, const DriveSetpoint& rotary,
                      MasterTelegram& mdt) const {
    changeover_->WriteSetpoints(spindle, rotary, mdt);
  }

  /// 2.3 Zero Point Shifts: the rotary axis' offsets and G92 shift act in rotary axis mode only;
  /// meanwhile the channel keeps them here.
  bool RotaryOffsetsActive() const { return In(axes::HeadstockMode::kRotary); }
  void set_rotary_translation(double t) { rotary_translation_ = t; }
  double rotary_translation() const { return rotary_translation_; }
  /// The mode whose designation the operator is shown (the last completed changeover's).
  axes::HeadstockMode shown_mode() const { return shown_mode_; }

 private:
  std::optional<axes::HeadstockChangeover> changeover_;
  axes::HeadstockPlc plc_;  ///< ROTMOD_Q, SPMOD_Q, enables and AXD idents, as the gateway gave
  bool known_ = false;      ///< the power-on mode has been taken from the PLC
  axes::HeadstockMode waiting_for_ = axes::HeadstockMode::kNone;  ///< the block in work's need
  bool manual_ = false;  ///< the changeover in progress was commanded by a key
  axes::HeadstockMode shown_mode_ = axes::HeadstockMode::kSpindle;
  double rotary_translation_ = 0;
  bool rotary_ready_ = true;  ///< RotaryReady() as the last Cycle took it
};

}  // namespace vmt::control::channel
