#pragma once
// The NC channel's changes as a run's events: the headstock's mode, target and pre-selections,
// PathGuard's checks, the measuring warnings, the JogOfPath channel, the REPOS screen, block
// search, the message list and the NC's state. The watch keeps what it reported last and hands
// each change to the recorder; it also keeps every message of the run for summary.json.

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "control/channel/channel.hpp"
#include "sim/model/machine_model.hpp"
#include "sim/runner/run_recorder.hpp"

namespace vmt::sim {

class ChannelEventWatch {
 public:
  explicit ChannelEventWatch(const MachineModel& model) : m_(&model) {}

  /// This tick's changes at `t`; `nc_cycle`: an NC cycle began (the REPOS screen, block search
  /// and the messages are read once a cycle). `jog_of_path` null without one.
  void Watch(double t, bool nc_cycle, const control::AmplifierTelegram& at,
             control::channel::Channel& channel, control::channel::Channel* jog_of_path,
             RunRecorder& recorder);
  /// Every message of the run, with when it came and, once gone, when it went.
  const nlohmann::ordered_json& messages_seen() const { return messages_seen_; }

 private:
  void WatchHeadstock(double t, const control::channel::Channel& channel, RunRecorder& recorder);
  void WatchJogOfPath(double t, control::channel::Channel& jog_of_path, RunRecorder& recorder);
  void WatchMessages(double t, const control::channel::Channel& channel, RunRecorder& recorder);

  const MachineModel* m_;
  control::axes::HeadstockMode headstock_mode_ = control::axes::HeadstockMode::kNone;
  control::axes::HeadstockMode headstock_target_ = control::axes::HeadstockMode::kNone;
  bool rotmod_ = false, spmod_ = false;  ///< the pre-selections the PLC was last shown
  control::channel::ChannelState jog_of_path_state_ = control::channel::ChannelState::kIdle;
  std::string repos_key_;       ///< the REPOS screen last emitted (ReposEventKey)
  std::string repos_key_next_;  ///< this cycle's, in storage kept
  control::channel::BlockSearchState block_search_state_ =
      control::channel::BlockSearchState::kInactive;
  size_t block_search_warnings_ = 0;  ///< warnings of the block search already emitted
  control::channel::ChannelState nc_state_ = control::channel::ChannelState::kIdle;
  std::vector<control::channel::OperatorMessage> messages_;  ///< the list as last emitted
  nlohmann::ordered_json messages_seen_ = nlohmann::ordered_json::array();
};

}  // namespace vmt::sim
