#pragma once
// What an NC channel changes as it runs, apart from what it was configured with: MuJoCo's split
// of mjModel and mjData for the channel. Channel (channel.hpp) is its ChannelConfig, the
// programs it was given, and this value; its member functions read and write the fields below
// as their own (Channel derives from ChannelData privately, so the fields keep the member
// names those functions use). ChannelData is a plain value: a copy taken at any NC cycle and
// handed back with Channel::Restore puts the channel where it was then.

#include <optional>
#include <string>
#include <vector>

#include "control/axes/tool_table.hpp"
#include "control/axes/zero_offsets.hpp"
#include "control/channel/aux_output.hpp"
#include "control/channel/axis_output.hpp"
#include "control/channel/backward_travel.hpp"
#include "control/channel/block_search_run.hpp"
#include "control/channel/block_search_simulation.hpp"
#include "control/channel/cax_track.hpp"
#include "control/channel/channel_config.hpp"
#include "control/channel/channel_types.hpp"
#include "control/channel/cycle_start.hpp"
#include "control/channel/enabling_signals.hpp"
#include "control/channel/fast_measurement.hpp"
#include "control/channel/further_spindle_control.hpp"
#include "control/channel/headstock_control.hpp"
#include "control/channel/jog_state.hpp"
#include "control/channel/look_ahead.hpp"
#include "control/channel/main_spindle_state.hpp"
#include "control/channel/operator_messages.hpp"
#include "control/channel/path_guard_client.hpp"
#include "control/channel/program_events.hpp"
#include "control/channel/program_frames.hpp"
#include "control/channel/program_in_work.hpp"
#include "control/channel/programmed_stop.hpp"
#include "control/channel/repositioning.hpp"
#include "control/channel/synchronous_block.hpp"
#include "control/channel/tool_storage_control.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

struct ChannelData {
  /// A channel at power-on: at rest, its axes and spindle homed as `config` says.
  explicit ChannelData(const ChannelConfig& config);

  // The channel's state, mode and messages.
  ChannelState state_ = ChannelState::kIdle;
  ChannelMode mode_ = ChannelMode::kAutomatic;
  std::string error_;
  int error_number_ = 0;
  PlcMessage plc_message_;
  EnablingSignals enable_;  ///< PxxC.ENABL, AxxC.ENABL
  double override_ = 1.0;
  bool single_block_ = false;
  PendingStart start_;

  // The program run.
  /// The program the channel runs: its interpreter, the block in work, look-ahead and tool
  /// radius compensation (program_in_work.hpp).
  ProgramInWork work_;
  ProgramEvents events_;            ///< BES / BEC / SE / RE: the gateway's, or the program's own
  ProgrammedStop programmed_stop_;  ///< M00 / M01
  ProgramFrames frames_;            ///< per axis: program -> axis translation, G92 shift, reference
  /// The zero offset table and the tool list as the program and repositioning have written
  /// them (TLD, OTD, repositioning's edits); ChannelConfig's are the ones at power-on.
  axes::ZeroOffsetTable zero_offsets_;
  axes::ToolTable tools_;
  AuxOutput aux_;  ///< M, H, Q, T waiting for the PLC, and their strobe
  bool reversing_ = false;
  bool inserted_piece_ = false;  ///< work_.block is a corner the compensation inserted before it
  MdiState mdi_;
  nc::ModalState last_modal_;
  LookAheadState look_;    ///< the block in work's speed targets and the speed carried on
  SynchronousBlock sync_;  ///< G33 / G63 / G64 in work
  CaxTrackState cax_;      ///< #CAX TRACK

  // The axes and drives.
  /// Positions commanded at the last two NC cycles and who holds the axes.
  AxisOutput out_;
  std::vector<double> drive_positions_;  ///< every drive's actual position, this NC cycle
  DriveWatch drives_;  ///< encoder positions and Control-Reset's trip acknowledgement
  JogData jog_;        ///< the jog keys, the handwheel, X1/Y1, the jog mode
  PathGuardClient guard_;

  // The spindles and the headstock.
  MainSpindleState sp_;  ///< the main spindle: command, override, keys, reference, feedback
  FurtherSpindleControl further_;  ///< spindles j >= 2
  HeadstockControl headstock_;     ///< none without a headstock

  // The tool storage axis.
  ToolStorageControl tool_storage_;
  /// MRY: the block waits until the program's traverse (T, MTP) has ended and the axis stands
  /// at its place.
  bool tool_storage_wait_ = false;

  // Repositioning, backward travel, block search, fast measurement.
  Repositioning repos_;
  /// The interrupted program while the REPOS subroutine runs in its place (in work_).
  ProgramInWork parked_;
  BackwardTravel backward_;
  BlockSearchSimulation search_;  ///< the skipped blocks and the search's run
  BlockSearchData bs_;
  FastMeasurement measuring_;
};

}  // namespace vmt::control::channel
