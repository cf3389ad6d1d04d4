// The NC channel's part of a scene run's tick: the gateway's controls in, PathGuard's view of
// the stock, the channel's cycle, the gateway's status out, and the events of what changed.

#include "control/channel/jog_of_path.hpp"
#include "sim/runner/channel_events.hpp"
#include "sim/runner/runner_state.hpp"

namespace vmt::sim {

void SceneRun::State::StepChannel(double t, const control::AmplifierTelegram& at) {
  const bool nc_cycle = tick % channel->ticks_per_cycle() == 0;
  if (gateway && nc_cycle && default_headstock_plc) AcknowledgeHeadstock();
  if (gateway && nc_cycle) gateway->ReadControls(*channel);
  if (jog_of_path && gateway && nc_cycle) gateway->ReadJogOfPath(*jog_of_path);
  if (jog_of_path && nc_cycle) control::channel::HandOverAxes(*channel, *jog_of_path);
  if (path_guard && nc_cycle)
    path_guard->FollowSpindle(t, channel->ticks_per_cycle() * kDriveTickS);
  // Each drive has one writer: the timeline's steps for those no channel writes this tick.
  const control::channel::Channel* lent = jog_of_path.get();
  timeline->WriteSetpoints(mdt, [this, lent](size_t d) {
    return channel_drive[d] && (channel->WritesDrive(d) || (lent && lent->WritesDrive(d)));
  });
  // The channel holding the axes writes their setpoints last; the other holds them where the
  // holder commanded them, which also covers the cycle in which both have let them go.
  const bool jog_of_path_holds = jog_of_path && !jog_of_path->output_suspended();
  if (jog_of_path && !jog_of_path_holds) jog_of_path->Tick(at, mdt);
  channel->Tick(at, mdt);
  if (jog_of_path_holds) jog_of_path->Tick(at, mdt);
  if (probe_glue) probe_glue->WriteSetpoints(mdt);
  if (gateway && nc_cycle) gateway->WriteStatus(*channel, at);
  if (jog_of_path && gateway && nc_cycle) gateway->WriteJogOfPath(*jog_of_path);
  channel_events.Watch(t, nc_cycle, at, *channel, jog_of_path.get(), recorder);
}

}  // namespace vmt::sim
