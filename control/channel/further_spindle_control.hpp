#pragma once
// The channel's function for its further spindles (further_spindles.hpp): their Sj= / Mj= words
// in a program, their return by G77 Sj=0 (REPOS manual 4.2), their part in PxxS.CREST (7.3: all
// spindles) and on the REPOS screen (2.2), and their command to the drives. It owns their
// state; the channel hands it the block, the states at the interruption and the drives'
// feedback, and turns an error it reports into the channel's error state.

#include <string>
#include <vector>

#include "control/channel/further_spindles.hpp"
#include "control/drive_bus.hpp"
#include "control/nc/interpreter.hpp"
#include "control/nc/program.hpp"

namespace vmt::control::channel {

class FurtherSpindleControl {
 public:
  explicit FurtherSpindleControl(std::vector<ChannelSpindle> spindles);

  /// Sj= / Mj= of `b` (read from `program`) take effect. An error ("file:line:col: error: S3=100:
  /// the channel has no spindle S3", at the word) for a spindle the channel lacks or a function
  /// it cannot give one; empty on success.
  std::string TakeWords(const nc::Program& program, const nc::PreparedBlock& b);
  /// The Sj= / Mj= words of a G77 block `b`: an error for a spindle the channel lacks or an Mj=
  /// (G77 restores the direction itself); empty if they can be restored.
  std::string CheckRepos(const nc::Program& program, const nc::PreparedBlock& b) const;
  /// G77 Sj=0 in `b`: each named spindle takes its state of `before` (the interruption's); the
  /// block waits (restoring()) while one still ramps to it.
  void Restore(const nc::PreparedBlock& b, const std::vector<FurtherSpindleState>& before,
               const AmplifierTelegram& at);
  /// While restoring: goes on until no restored spindle ramps any more. True while it waits.
  bool UpdateRestoring(const AmplifierTelegram& at);
  bool restoring() const { return restoring_; }
  void StopRestoring() { restoring_ = false; }
  /// Every spindle stopped (M5, no speed): the start and Control-Reset.
  void Reset();

  /// Spindle `k` has the command of `before` and (with `at`) runs at it.
  bool Restored(size_t k, const std::vector<FurtherSpindleState>& before,
                const AmplifierTelegram* at) const;
  bool AllRestored(const std::vector<FurtherSpindleState>& before,
                   const AmplifierTelegram& at) const;
  /// Their lines of the REPOS screen against the states of `before`.
  std::vector<ReposFurtherSpindleStatus> ReposStatus(const std::vector<FurtherSpindleState>& before,
                                                     const AmplifierTelegram* at) const;

  const std::vector<FurtherSpindleState>& states() const { return states_; }
  void WriteSetpoints(MasterTelegram& mdt) const;

 private:
  /// A spindle with a command still short of its speed.
  bool Ramping(const AmplifierTelegram& at) const;

  std::vector<ChannelSpindle> spindles_;     ///< the channel's, in config order
  std::vector<FurtherSpindleState> states_;  ///< per spindle
  bool restoring_ = false;                   ///< a G77 Sj=0 (j >= 2) block waits for their speed
};

}  // namespace vmt::control::channel
