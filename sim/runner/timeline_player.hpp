#pragma once
// The timeline player: plays a scene's timeline of operator and test actions in time, one step
// after the other (steps/: each kind's effect), a step that waits holding the ones after it. It
// writes the valves and the setpoints of the drives no channel owns, and hands the NC steps to
// the channel and the signal steps to the gateway's image.

#include <string>
#include <vector>

#include "control/drive_bus.hpp"
#include "control/gateway/signal_image.hpp"
#include "sim/scene/scene.hpp"
#include "sim/scene/steps/timeline_play.hpp"

namespace vmt::sim {

class TimelinePlayer {
 public:
  /// `feedback` gives the state at t = 0: servos hold their position, spindles stand at 0.
  /// A servo whose position encoder sits beyond a dog clutch (the C servo on the spindle's
  /// encoder, through clutch K) is held only while the clutch is engaged; released, its
  /// controller enable is off and its command follows the encoder (follow-up mode, C-axis
  /// manual 4.3), as the PLC of spindle mode keeps it -- held, it would chase a spindle it
  /// cannot reach until its amplifier trips on overload. A step that commands the drive ends
  /// this default, and so does LeaveEnableToChannel.
  /// `channel` (may be null) receives the timeline's NC steps.
  /// `image` (may be null): the gateway signals the timeline's `signal:` steps write, as the
  /// default PLC passing panel keys to the NC would.
  TimelinePlayer(const Scene& scene, const control::AmplifierTelegram& feedback,
               control::channel::Channel* channel = nullptr,
               control::gateway::SignalImage* image = nullptr);

  /// One drive tick at time t: advances the timeline on the feedback of the last tick and fills
  /// the MDT's outputs. Events are appended to `events`.
  void Tick(double t_s, const control::AmplifierTelegram& at,
            const std::vector<ClutchState>& clutches, control::MasterTelegram& mdt,
            std::vector<ProgramEvent>& events);
  /// The setpoints of the drives no channel writes this tick (`written_elsewhere`): where the
  /// timeline's steps command them, else where they stood at t = 0.
  template <typename WrittenElsewhere>
  void WriteSetpoints(control::MasterTelegram& mdt, WrittenElsewhere written_elsewhere) const {
    mdt.setpoints.resize(play_.setpoints.size());
    for (size_t d = 0; d < play_.setpoints.size(); ++d)
      if (!written_elsewhere(d)) mdt.setpoints[d] = play_.setpoints[d];
  }

  /// A channel may write drive d (its axis, or the rotary axis of its headstock): the
  /// channel's headstock switches its controller enable, the timeline holds it until then.
  void LeaveEnableToChannel(size_t d) { Release(d); }

  bool finished() const { return next_ >= scene_->timeline.size(); }
  InjectedFaults& faults() { return play_.faults; }
  /// Steps that did not complete (wait_until timeouts), as messages.
  const std::vector<std::string>& failures() const { return play_.failures; }

 private:
  const Scene* scene_;
  TimelinePlay play_;
  size_t next_ = 0;
  /// Per drive: the clutch between its motor and its encoder (-1: none), and whether the
  /// drive still has its default setpoint (no step has commanded it).
  std::vector<int> encoder_clutch_;
  std::vector<uint8_t> held_;
  int held_count_ = 0;        ///< drives held: without them a tick needs no comparison of setpoints
  double step_since_s_ = -1;  ///< when the current blocking step began
  /// The setpoints before a step played, to tell which drives it commanded (kept, so that the
  /// step a run waits on does not allocate every tick).
  std::vector<control::DriveSetpoint> setpoints_before_;
  std::vector<uint8_t> profiling_before_;

  void Release(size_t d) {
    held_count_ -= held_[d];
    held_[d] = 0;
  }
};

}  // namespace vmt::sim
