#pragma once
// The run's control stage: what a real machine's control cabinet holds. The NC channel (and the
// JogOfPath channel of block search 4.2.1), the gateway of signals between NC and PLC, the
// embedded PLC with its watchdog, the field bus that carries the machine's sensors and valves
// through the signal image, and the SERCOS side of the PLC's probe block. The runner hands it
// the machine's telegram and the master telegram in the order of a tick; the timeline writes
// the drives no channel writes (WritesDrive) between the stage's reading and its ticking.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "control/channel/channel.hpp"
#include "control/drive_bus.hpp"
#include "control/gateway/channel_gateway.hpp"
#include "control/gateway/signal_image.hpp"
#include "control/measure/measuring_pages.hpp"
#include "control/plc/plc_runtime.hpp"
#include "sim/runner/field_bus.hpp"
#include "sim/runner/probe_glue.hpp"
#include "sim/scene/scene.hpp"
#include "sim/scene/steps/timeline_play.hpp"

namespace vmt::sim {

class ControlStage {
 public:
  /// The channels where the scene has `nc:` (asking `guard` before their approach moves; null:
  /// no PathGuard), the gateway where it has signals, its embedded PLC unless `external_plc`
  /// (vmt serve's client takes its place), the field bus where a PLC is there to read it. A
  /// scene with a separate C servo and no PLC of its own gets the changeover PLC of C-axis
  /// manual 4.4; a timeline that switches that PLC's valves is refused (std::runtime_error).
  ControlStage(const Scene& scene, bool external_plc, control::PathGuard* guard);
  ControlStage(const ControlStage&) = delete;  // the channel points at measuring_pages_
  ControlStage& operator=(const ControlStage&) = delete;

  /// Start of a tick: the probe block's drives report their status.
  void ReadStatus(const control::AmplifierTelegram& at);
  /// The PLC's scan when `tick` starts its cycle, or its missed scan under `faults`. Returns
  /// the NC's message when the watchdog stops the PLC now (StopPlc has been done), else "".
  std::string ScanPlc(int64_t tick, InjectedFaults& faults);
  /// The PLC is gone (watchdog, lost client): its outputs drop, the channel stops with 505.
  void StopPlc(const std::string& nc_text);
  /// The valves' signals out to the machine's outputs.
  void WriteOutputs(control::MasterTelegram& mdt);
  /// Whether the field bus brings the machine's sensors into the image before `tick`: before
  /// each PLC cycle (the first too), where a PLC is there to read them.
  bool ReadsInputsAt(int64_t tick) const {
    return field_bus_.connected() && tick % plc_every_ == 0;
  }
  void ReadInputs(const control::AmplifierTelegram& at) { field_bus_.ReadInputs(at, *image_); }

  bool NcCycle(int64_t tick) const { return tick % channel_->ticks_per_cycle() == 0; }
  /// The NC cycle's inputs to the channels: the headstock's acknowledgement where no PLC gives
  /// it, the gateway's controls, the JogOfPath channel's hand-over of the feed axes.
  void ReadControls(bool nc_cycle);
  /// Whether a channel writes drive `d`'s setpoint this tick (the timeline writes the others).
  bool WritesDrive(size_t d) const {
    return channel_drive_[d] &&
           (channel_->WritesDrive(d) || (jog_of_path_ && jog_of_path_->WritesDrive(d)));
  }
  /// Whether a channel may ever write drive `d`.
  bool MayWriteDrive(size_t d) const { return channel_drive_[d] != 0; }
  /// The channels' tick (the one holding the feed axes last), the probe block's setpoints,
  /// and on an NC cycle the gateway's status out.
  void Tick(bool nc_cycle, const control::AmplifierTelegram& at, control::MasterTelegram& mdt);

  control::channel::Channel* channel() { return channel_.get(); }
  const control::channel::Channel* channel() const { return channel_.get(); }
  /// Null without `nc: jog_of_path:`.
  control::channel::Channel* jog_of_path() { return jog_of_path_.get(); }
  /// Null without the scene's signals.
  control::gateway::SignalImage* image() { return image_.get(); }
  const control::gateway::SignalImage* image() const { return image_.get(); }
  /// Null without an embedded PLC.
  const control::plc::PlcRuntime* plc() const { return plc_.get(); }
  /// Null without the scene's signals.
  ProbeGlue* probe_glue() { return probe_glue_.get(); }
  /// The machine data pages of fast measurement: the channel's MTD(...) and the probe
  /// block's MTD_RD read and write the same ones.
  const control::measure::MeasuringPages& measuring_pages() const { return measuring_pages_; }
  /// Drive ticks per PLC cycle.
  int64_t plc_every() const { return plc_every_; }

  /// What the stage's tick changes (channels, signal image, gateway, PLC, probe block, machine
  /// data pages), kept to go back to (a run's in-memory snapshot).
  struct Saved {
    control::measure::MeasuringPages measuring_pages;
    std::optional<control::channel::ChannelData> channel, jog_of_path;
    std::optional<control::gateway::SignalImage> image;
    std::optional<control::gateway::ChannelGateway> gateway;
    std::optional<control::plc::PlcRuntime::Saved> plc;
    std::optional<ProbeGlue> probe_glue;
    int64_t plc_overdue;
    bool default_headstock_plc;
  };
  Saved Save() const;
  void Restore(const Saved& saved);

 private:
  void MakeChannels(const Scene& scene, control::PathGuard* guard);
  void MakeGateway(const Scene& scene);
  void MakePlc(const Scene& scene, bool external_plc);
  void StartHeadstockPlc(const Scene& scene);
  void AcknowledgeHeadstock();

  const MachineModel& m_;
  control::measure::MeasuringPages measuring_pages_;
  std::unique_ptr<control::channel::Channel> channel_;
  std::unique_ptr<control::channel::Channel> jog_of_path_;
  std::unique_ptr<control::gateway::SignalImage> image_;
  std::unique_ptr<control::gateway::ChannelGateway> gateway_;
  std::unique_ptr<control::plc::PlcRuntime> plc_;
  FieldBus field_bus_;
  std::unique_ptr<ProbeGlue> probe_glue_;
  int64_t plc_every_ = 16;
  int64_t plc_overdue_ = 0;  ///< scans in a row the PLC has missed
  /// Per drive: a channel may write it (its own, or the one it lends).
  std::vector<uint8_t> channel_drive_;
  /// Without a PLC the stage acknowledges the headstock changeover at once, as a PLC does
  /// when no mechanical changeover is needed (C-axis manual 4.2), reports spindle mode at
  /// power-on and enables the drives (AxxC.READY); a timeline that writes ROTMOD_Q / SPMOD_Q
  /// itself turns this off.
  bool default_headstock_plc_ = false;
};

}  // namespace vmt::sim
