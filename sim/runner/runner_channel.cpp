// The NC channel's part of a scene run's tick: the gateway's controls in, PathGuard's view of
// the stock, the channel's cycle, the gateway's status out, and the events of what changed.
#include <algorithm>

#include "control/channel/jog_of_path.hpp"
#include "control/plc/plc_message_texts.hpp"
#include "sim/runner/channel_events.hpp"
#include "sim/runner/runner_state.hpp"

namespace vmt::sim {

// Each NC cycle, before the channel may ask PathGuard: cut the stock where the tools stand and
// note whether the spindle turns (the chuck is then checked as it sweeps).
void SceneRun::State::FollowSpindle(double t) {
  const std::vector<double> q = backend->JointPositions();
  if (cutter && cutter->Cut(q, t)) guard_parts_stale = true;
  const int joint = path_guard->sweep().joint;
  if (joint < 0) return;
  const double cycle_s = channel->ticks_per_cycle() * kDriveTickS;
  path_guard->SetSpindleTurning(std::abs(q[joint] - spindle_angle) >= kTurningSpeedRadS * cycle_s);
  spindle_angle = q[joint];
}

void SceneRun::State::StepChannel(double t, const control::AmplifierTelegram& at) {
  const bool nc_cycle = tick % channel->ticks_per_cycle() == 0;
  if (gateway && nc_cycle && default_headstock_plc) AcknowledgeHeadstock();
  if (gateway && nc_cycle) gateway->ReadControls(*channel);
  if (jog_of_path && gateway && nc_cycle) gateway->ReadJogOfPath(*jog_of_path);
  if (jog_of_path && nc_cycle) control::channel::HandOverAxes(*channel, *jog_of_path);
  if (path_guard && nc_cycle) FollowSpindle(t);
  // The channel holding the axes writes their setpoints last; the other holds them where the
  // holder commanded them, which also covers the cycle in which both have let them go.
  const bool jog_of_path_holds = jog_of_path && !jog_of_path->output_suspended();
  if (jog_of_path && !jog_of_path_holds) jog_of_path->Tick(at, mdt);
  channel->Tick(at, mdt);
  if (jog_of_path_holds) jog_of_path->Tick(at, mdt);
  if (probe_glue) probe_glue->WriteSetpoints(mdt);
  if (gateway && nc_cycle) gateway->WriteStatus(*channel, at);
  if (jog_of_path && gateway && nc_cycle) gateway->WriteJogOfPath(*jog_of_path);
  if (const auto* hs = channel->headstock(); hs && hs->target() != headstock_target) {
    // The operator's display: the axis designation of the mode (S1 <-> C, 2.3 position
    // indication) once the changeover is complete.
    headstock_target = hs->target();
    recorder.Event({{"t", t},
                {"event", "headstock"},
                {"mode", ToString(hs->mode())},
                {"target", ToString(hs->target())}});
  }
  if (const auto* hs = channel->headstock();
      hs && (hs->rotmod() != rotmod || hs->spmod() != spmod)) {
    // The pre-selections ROTMOD / SPMOD (4.1) as the PLC sees them: the end of the internal
    // changeover, with the drives at standstill (4.2), starts the external one.
    rotmod = hs->rotmod();
    spmod = hs->spmod();
    recorder.Event({{"t", t}, {"event", "headstock"}, {"rotmod", rotmod}, {"spmod", spmod}});
  }
  if (const auto* hs = channel->headstock(); hs && hs->mode() != headstock_mode) {
    headstock_mode = hs->mode();
    // The status indication switches with it: speeds in spindle mode, lines in rotary mode.
    recorder.Event({{"t", t},
                {"event", "headstock"},
                {"mode", ToString(headstock_mode)},
                {"axis", channel->HeadstockAxisName()},
                {"speeds", channel->spindle_status().speeds_shown ? "shown" : "lines"}});
  }
  for (const control::channel::GuardRecord& r : channel->TakeGuardRecords())
    recorder.Event(GuardEvent(t, r, m));
  for (const std::string& w : channel->TakeMeasuringWarnings())
    recorder.Event({{"t", t}, {"event", "measuring"}, {"warning", w}});
  if (jog_of_path) {
    for (const control::channel::GuardRecord& r : jog_of_path->TakeGuardRecords()) {
      nlohmann::ordered_json e = GuardEvent(t, r, m);
      e["channel"] = "jog_of_path";
      recorder.Event(e);
    }
    if (jog_of_path->state() != jog_of_path_state) {
      jog_of_path_state = jog_of_path->state();
      nlohmann::ordered_json e = {{"t", t},
                                  {"event", "nc"},
                                  {"channel", "jog_of_path"},
                                  {"state", ToString(jog_of_path_state)}};
      if (!jog_of_path->error().empty()) e["error"] = jog_of_path->error();
      recorder.Event(e);
    }
  }
  if (nc_cycle) {
    // The REPOS screen (repositioning manual 2.2) when its function, status or an adjust
    // symbol changes.
    const control::channel::ReposStatus rs = channel->repos_status(&at);
    std::string key = ReposEventKey(rs);
    if (key != repos_key) {
      if (!repos_key.empty() || rs.allowed) recorder.Event(ReposEvent(t, rs));
      repos_key = std::move(key);
    }
  }
  if (nc_cycle) {
    // Block search: its state as the PLC sees it change, and each warning once.
    const control::channel::BlockSearchStatus& bs = channel->block_search();
    if (bs.state != block_search_state) {
      block_search_state = bs.state;
      recorder.Event(BlockSearchEvent(t, *channel));
    }
    if (bs.warnings.size() < block_search_warnings) block_search_warnings = 0;  // a new run
    for (; block_search_warnings < bs.warnings.size(); ++block_search_warnings)
      recorder.Event(BlockSearchEvent(t, *channel, bs.warnings[block_search_warnings]));
  }
  if (nc_cycle) NoteMessages(t);
  if (channel->state() != nc_state) {
    nc_state = channel->state();
    nlohmann::ordered_json e = {{"t", t}, {"event", "nc"}, {"state", ToString(nc_state)}};
    if (!channel->error().empty()) e["error"] = channel->error();
    recorder.Event(e);
  }
}

// The NC's message list (the error in force, the PLC's MSG_WR): each message once as it
// appears and once as it goes, so that the operator's log shows what the PLC reported.
void SceneRun::State::NoteMessages(double t) {
  using control::channel::OperatorMessage;
  std::vector<OperatorMessage> now = channel->messages();
  const auto same = [](const OperatorMessage& a, const OperatorMessage& b) {
    return a.source == b.source && a.number == b.number && a.parameter == b.parameter &&
           a.text == b.text;
  };
  const auto contains = [&](const std::vector<OperatorMessage>& list, const OperatorMessage& m) {
    return std::any_of(list.begin(), list.end(), [&](const auto& x) { return same(x, m); });
  };
  for (const OperatorMessage& m : messages) {
    if (contains(now, m)) continue;
    recorder.Event({{"t", t},
                {"event", "message"},
                {"source", ToString(m.source)},
                {"number", m.number},
                {"state", "cleared"}});
    for (auto& seen : messages_seen)
      if (seen["source"] == ToString(m.source) && seen["number"] == m.number &&
          !seen.contains("cleared_t"))
        seen["cleared_t"] = t;
  }
  for (const OperatorMessage& m : now) {
    if (contains(messages, m)) continue;
    nlohmann::ordered_json e = {{"t", t},
                                {"event", "message"},
                                {"source", ToString(m.source)},
                                {"number", m.number}};
    if (m.source == OperatorMessage::Source::kPlc) e["parameter"] = m.parameter;
    e["text"] = m.source == OperatorMessage::Source::kPlc
                    ? control::plc::PlcMessageText(m.number, m.parameter)
                    : m.text;
    recorder.Event(e);
    nlohmann::ordered_json seen = e;
    seen.erase("event");
    messages_seen.push_back(seen);
  }
  messages = std::move(now);
}

}  // namespace vmt::sim
