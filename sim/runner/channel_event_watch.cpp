#include "sim/runner/channel_event_watch.hpp"

#include <algorithm>
#include <utility>

#include "control/plc/plc_message_texts.hpp"
#include "sim/runner/channel_events.hpp"

namespace vmt::sim {

void ChannelEventWatch::Watch(double t, bool nc_cycle, const control::AmplifierTelegram& at,
                              control::channel::Channel& channel,
                              control::channel::Channel* jog_of_path, RunRecorder& recorder) {
  WatchHeadstock(t, channel, recorder);
  for (const control::channel::GuardRecord& r : channel.TakeGuardRecords())
    recorder.Event(GuardEvent(t, r, *m_));
  for (const std::string& w : channel.TakeMeasuringWarnings())
    recorder.Event({{"t", t}, {"event", "measuring"}, {"warning", w}});
  if (jog_of_path) WatchJogOfPath(t, *jog_of_path, recorder);
  if (nc_cycle) {
    // The REPOS screen (repositioning manual 2.2) when its function, status or an adjust
    // symbol changes. The screen's parts that no key holds are read only for the event.
    ReposEventKey(channel.repos_status(&at, false), repos_key_next_);
    if (repos_key_next_ != repos_key_) {
      const control::channel::ReposStatus rs = channel.repos_status(&at);
      if (!repos_key_.empty() || rs.allowed) recorder.Event(ReposEvent(t, rs));
      repos_key_.swap(repos_key_next_);
    }
    // Block search: its state as the PLC sees it change, and each warning once.
    const control::channel::BlockSearchStatus& bs = channel.block_search();
    if (bs.state != block_search_state_) {
      block_search_state_ = bs.state;
      recorder.Event(BlockSearchEvent(t, channel));
    }
    if (bs.warnings.size() < block_search_warnings_) block_search_warnings_ = 0;  // a new run
    for (; block_search_warnings_ < bs.warnings.size(); ++block_search_warnings_)
      recorder.Event(BlockSearchEvent(t, channel, bs.warnings[block_search_warnings_]));
    WatchMessages(t, channel, recorder);
  }
  if (channel.state() != nc_state_) {
    nc_state_ = channel.state();
    nlohmann::ordered_json e = {{"t", t}, {"event", "nc"}, {"state", ToString(nc_state_)}};
    if (!channel.error().empty()) e["error"] = channel.error();
    recorder.Event(e);
  }
}

void ChannelEventWatch::WatchHeadstock(double t, const control::channel::Channel& channel,
                                       RunRecorder& recorder) {
  const control::axes::HeadstockChangeover* hs = channel.headstock();
  if (!hs) return;
  if (hs->target() != headstock_target_) {
    // The operator's display: the axis designation of the mode (S1 <-> C, 2.3 position
    // indication) once the changeover is complete.
    headstock_target_ = hs->target();
    recorder.Event({{"t", t},
                    {"event", "headstock"},
                    {"mode", ToString(hs->mode())},
                    {"target", ToString(hs->target())}});
  }
  if (hs->rotmod() != rotmod_ || hs->spmod() != spmod_) {
    // The pre-selections ROTMOD / SPMOD (4.1) as the PLC sees them: the end of the internal
    // changeover, with the drives at standstill (4.2), starts the external one.
    rotmod_ = hs->rotmod();
    spmod_ = hs->spmod();
    recorder.Event({{"t", t}, {"event", "headstock"}, {"rotmod", rotmod_}, {"spmod", spmod_}});
  }
  if (hs->mode() != headstock_mode_) {
    headstock_mode_ = hs->mode();
    // The status indication switches with it: speeds in spindle mode, lines in rotary mode.
    recorder.Event({{"t", t},
                    {"event", "headstock"},
                    {"mode", ToString(headstock_mode_)},
                    {"axis", channel.HeadstockAxisName()},
                    {"speeds", channel.spindle_status().speeds_shown ? "shown" : "lines"}});
  }
}

void ChannelEventWatch::WatchJogOfPath(double t, control::channel::Channel& jog_of_path,
                                       RunRecorder& recorder) {
  for (const control::channel::GuardRecord& r : jog_of_path.TakeGuardRecords()) {
    nlohmann::ordered_json e = GuardEvent(t, r, *m_);
    e["channel"] = "jog_of_path";
    recorder.Event(e);
  }
  if (jog_of_path.state() != jog_of_path_state_) {
    jog_of_path_state_ = jog_of_path.state();
    nlohmann::ordered_json e = {{"t", t},
                                {"event", "nc"},
                                {"channel", "jog_of_path"},
                                {"state", ToString(jog_of_path_state_)}};
    if (!jog_of_path.error().empty()) e["error"] = jog_of_path.error();
    recorder.Event(e);
  }
}

// The NC's message list (the error in force, the PLC's MSG_WR): each message once as it appears
// and once as it goes, so that the operator's log shows what the PLC reported.
void ChannelEventWatch::WatchMessages(double t, const control::channel::Channel& channel,
                                      RunRecorder& recorder) {
  using control::channel::OperatorMessage;
  std::vector<OperatorMessage> now = channel.messages();
  const auto same = [](const OperatorMessage& a, const OperatorMessage& b) {
    return a.source == b.source && a.number == b.number && a.parameter == b.parameter &&
           a.text == b.text;
  };
  const auto contains = [&](const std::vector<OperatorMessage>& list, const OperatorMessage& m) {
    return std::any_of(list.begin(), list.end(), [&](const auto& x) { return same(x, m); });
  };
  for (const OperatorMessage& m : messages_) {
    if (contains(now, m)) continue;
    recorder.Event({{"t", t},
                    {"event", "message"},
                    {"source", ToString(m.source)},
                    {"number", m.number},
                    {"state", "cleared"}});
    for (auto& seen : messages_seen_)
      if (seen["source"] == ToString(m.source) && seen["number"] == m.number &&
          !seen.contains("cleared_t"))
        seen["cleared_t"] = t;
  }
  for (const OperatorMessage& m : now) {
    if (contains(messages_, m)) continue;
    nlohmann::ordered_json e = {
        {"t", t}, {"event", "message"}, {"source", ToString(m.source)}, {"number", m.number}};
    if (m.source == OperatorMessage::Source::kPlc) e["parameter"] = m.parameter;
    e["text"] = m.source == OperatorMessage::Source::kPlc
                    ? control::plc::PlcMessageText(m.number, m.parameter)
                    : m.text;
    recorder.Event(e);
    nlohmann::ordered_json seen = e;
    seen.erase("event");
    messages_seen_.push_back(seen);
  }
  messages_ = std::move(now);
}

}  // namespace vmt::sim
