#pragma once
// The channel's function for fast measurement (mtc200-fast-measurement.md): a block with a
// measuring instruction runs the plan measure::PlanInstruction makes of it, step by step, as the
// real control runs the NC blocks it generates for the instruction: events to and from the PLC's
// measuring block (6.2), Q functions with their acknowledgement (6.1), G00 and G94 G01 moves of
// the stylus' sphere centre, and on the measuring path the drive's latch (7.3) stops the move and
// gives the measured value. It owns the instruction in work, SETTING's setting, the reverse
// vectors and the machine data pages; the channel hands it, per call, the block in work, where
// the axes are commanded, the program's events and auxiliary output, the drives' feedback,
// PathGuard's check and a way to fail (MeasuringLink).

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "control/channel/aux_output.hpp"
#include "control/channel/channel_config.hpp"
#include "control/channel/channel_types.hpp"
#include "control/channel/measuring_run.hpp"
#include "control/channel/program_events.hpp"
#include "control/channel/program_in_work.hpp"
#include "control/drive_bus.hpp"
#include "control/measure/measuring_cycle.hpp"
#include "control/measure/measuring_pages.hpp"
#include "control/nc/interpreter.hpp"
#include "control/nc/program.hpp"

namespace vmt::control::channel {

/// An error the channel takes over: `text` at block `block` of program `program`
/// ("file:line:col: error: text"), or, with `block` < 0, `text` as it is. `hold`: fault
/// category 2 (Q9998), the program holds with the message and a new start continues it;
/// otherwise the channel goes to its error state.
struct MeasuringError {
  std::string text;
  int number = 0;
  uint32_t program = 0;
  int32_t block = -1;
  bool hold = false;
};

/// What the channel hands the fast measurement for one call.
struct MeasuringLink {
  ProgramInWork& work;  ///< the block in work, its motion and profile, the interpreter
  const std::vector<double>& commanded;    ///< where the axes are commanded (machine coordinates)
  const std::vector<double>& translation;  ///< program -> axis of the block in work
  const ChannelState& state;
  ProgramEvents& events;  ///< SE / RE go out here, the PLC's events come in
  AuxOutput& aux;         ///< Q functions to the PLC
  std::function<const nc::Program&(uint32_t index)> program_of;
  /// Program -> axis translation of `modal` with the tables as they are now.
  std::function<std::vector<double>(const nc::ModalState& modal)> translation_of;
  /// `modal`'s offsets and tool length take effect for block `block` of program `program`
  /// (`translation` follows): false if that failed the channel (an edge not in the tool list).
  std::function<bool(const nc::ModalState& modal, uint32_t program, int32_t block)> take_offsets;
  /// Plans work.block, a block the instruction generated, from where the axes are commanded
  /// (their reference, their travel): false if that failed the channel.
  std::function<bool()> plan_motion;
  /// PathGuard's check of work.motion before it starts (only up to `end`, per channel axis,
  /// when given; `measuring_path`: the ruby may touch the part): false if it stopped the move.
  std::function<bool(const std::string& move, const std::vector<double>* end, bool measuring_path)>
      guard;
  std::function<void(const MeasuringError& error)> fail;
};

class FastMeasurement {
 public:
  /// The channel's axes (their names and drives), its tool list and its PLC handshake.
  explicit FastMeasurement(const ChannelConfig& config);

  /// The machine data pages (MTD, the measuring instructions); null: none. They must outlive
  /// the channel.
  void SetPages(measure::MeasuringPages* pages) { data_.pages = pages; }
  measure::MeasuringPages* pages() const { return data_.pages; }
  const std::optional<measure::MeasuringSetting>& setting() const { return data_.setting; }
  const measure::ReverseVectors& reverse_vectors() const { return data_.reverse_vectors; }
  std::vector<std::string> TakeWarnings() { return std::exchange(data_.warnings, {}); }
  /// An instruction is in work (its steps, or its move).
  bool in_work() const { return data_.run.has_value(); }

  /// The program ended: SETTING and the reverse vectors hold for one run of it.
  void ForgetProgram() {
    data_.setting.reset();
    data_.reverse_vectors = {};
  }
  /// Control-Reset: the instruction in work is dropped as well.
  void Reset() {
    data_.run.reset();
    ForgetProgram();
  }

  /// The block in work's measuring instruction: check it, plan it, start its steps. False
  /// after c.fail.
  bool Start(const MeasuringLink& c);
  /// Advances the steps while no move is in work; true when the instruction is done.
  bool Cycle(const MeasuringLink& c);
  /// While a measuring move runs: the probe's contact (the drives' latch in `at`) stops it.
  void WatchMove(const MeasuringLink& c, const AmplifierTelegram& at);
  /// While event 29 (collision monitoring) is set in a program that has run SETTING and not
  /// `reversing`: a probe displaced outside the measuring path stops the axes, outputs Q9999
  /// and fails (6.1).
  void WatchCollision(const MeasuringLink& c, const AmplifierTelegram& at, bool reversing);
  /// Reverse: the stylus travels its reverse vectors back (4.4) before `.HOME` runs; its steps
  /// start from `block`, the block in work.
  void StartReversal(const nc::PreparedBlock& block);
  /// Block search: the measuring instruction of `b` before the continue position, the
  /// search's axes at `position` (machine coordinates). The state-only instructions run, the
  /// others move `position` along their path without measuring and add a warning. False after
  /// c.fail.
  bool Simulate(const MeasuringLink& c, const nc::PreparedBlock& b, std::vector<double>& position,
                std::vector<std::string>& warnings);

 private:
  int SettingAxis(int n) const;  ///< channel axis of SETTING axis n (0..2), -1 if none
  /// Program -> axis translation with the stylus' sphere `sphere` as the tool edge.
  std::vector<double> StylusTranslation(const MeasuringLink& c, int sphere) const;
  measure::MeasuringContext ContextNow(const MeasuringLink& c) const;
  /// What `plan` leaves as state, in a run and in block search alike: SETTING's setting and its
  /// G codes (modal in the interpreter), RESTORE's @100..@112 and feed.
  void ApplyState(const MeasuringLink& c, const measure::MeasuringPlan& plan);
  bool StartMove(const MeasuringLink& c, const measure::MeasuringStep& step);
  /// After a move of the instruction: the reverse vectors reached, and a way back to a point
  /// already recorded (the escape) ends the record there.
  void TrackReverseVectors(const MeasuringLink& c);
  /// Ends the instruction: translation and the interpreter's position back to the program's.
  void End(const MeasuringLink& c);
  /// A measuring path has ended: TEST POINT NOT FOUND's Q9999, or the wait for event 7.
  void FinishMeasuringPath(MeasuringRun& run) const;

  std::vector<std::string> names_;  ///< the channel's axes
  std::vector<int> drives_;
  bool tool_list_;
  bool aux_handshake_;
  MeasuringData data_;
};

}  // namespace vmt::control::channel
