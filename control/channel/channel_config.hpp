#pragma once
// What a channel is given and never changes while it runs: its axes and spindles, the machine
// data of its process, zero offsets, tool list and start-up modal state, the headstock, PathGuard's
// reaction and the tool storage axis. Built once from the machine and the scene (the scene loader
// does it), separate from the channel's changing state.

#include <optional>
#include <vector>

#include "control/axes/axis_parameters.hpp"
#include "control/axes/headstock_changeover.hpp"
#include "control/axes/tool_table.hpp"
#include "control/axes/zero_offsets.hpp"
#include "control/channel/further_spindles.hpp"
#include "control/nc/interpreter.hpp"
#include "control/path_guard.hpp"

namespace vmt::control::channel {

/// A channel axis is described by its axis parameters (control/axes).
using ChannelAxis = axes::AxisParameters;

struct ChannelConfig {
  std::vector<ChannelAxis> axes;
  axes::ProcessParameters process;
  int spindle_drive = -1;  ///< main spindle (S, M3/M4/M5/M19); -1 if none
  /// The main spindle's axis parameters: its designation (S1), jogging speed and jogging
  /// spindle position (AxxC.M3/M4/M19), encoder limits and reference at power-on. Its `drive`
  /// and `number` are not read (spindle_drive is). An empty name shows as "S1".
  axes::AxisParameters spindle;
  /// The channel's further spindles (Sj, j >= 2: lathe-c1's driven tool S2), which the channel
  /// commands from Sj= / Mj= words (further_spindles.hpp).
  std::vector<ChannelSpindle> spindles;
  int ticks_per_cycle = 4;  ///< NC cycle 1 ms at the 250 us drive tick
  double tick_s = 250e-6;
  /// The zero offset table and the tool list at power-on; the running channel writes its own
  /// copies (ChannelData).
  axes::ZeroOffsetTable zero_offsets;
  axes::ToolTable tools;
  nc::ModalState initial;  ///< modal state at program start
  /// M, H, Q and T functions wait for the PLC's acknowledgement (AcknowledgeAux) before the
  /// block goes on; off, they count as acknowledged at once.
  bool aux_handshake = false;
  double handwheel_per_count = 0.01;  ///< mm | deg per handwheel count
  /// A spindle with a rotary axis mode (C-axis manual): the blocks and jog keys that need the
  /// other mode wait for the changeover. Absent: the spindle is only a spindle.
  std::optional<axes::HeadstockConfig> headstock;
  int rotary_axis = -1;  ///< the channel axis of the headstock's rotary axis mode (C)
  /// What a contact PathGuard finds ahead of a move does: stop it before it happens with an NC
  /// error (kMsgCollision), only record it, or no checks at all.
  GuardReaction path_guard = GuardReaction::kStop;
  /// Continuous jogs are checked ahead every this many NC cycles, far enough to brake in time.
  int path_guard_every = 8;
  /// The drive of the tool storage axis (a turret the PLC indexes), -1 if none: with Bxx.045 its
  /// position at the interruption is part of the state to restore (REPOS manual 6.2, 7.3).
  int tool_storage_drive = -1;
  /// An NC-controlled tool storage axis (REPOS manual 3.4, 6.2): the channel commands
  /// tool_storage_drive itself, jogs it with PxxC.MGPOS / MGNEG in manual mode and returns it
  /// with MTP. False: the PLC positions it and jogs it with those signals (lathe-c1's turret).
  bool tool_storage_nc = false;
  /// The tool storage axis' parameters: jogging speed (Cxx.020), acceleration, rotary without
  /// travel limits for an endless one (its adjust symbol then measures the short way round).
  axes::AxisParameters tool_storage;
  /// The tool storage axis' stations, evenly spaced over a turn: tool Tn is station n, at
  /// (n - 1) * 360 / stations deg (lathe-c1's model: joint angle (k - 1) * 30 deg puts station
  /// k at the work). With tool_storage_nc, a T word indexes the turret to its station (REPOS
  /// manual 4.2: asynchronously to the other axes); 0: T words do not index it.
  int tool_storage_stations = 0;
  /// A JogOfPath channel (jog_of_path.hpp): its axis output is suspended from the start, until
  /// the block search channel's axes are handed to it.
  bool output_suspended_at_start = false;
  /// Every programmed move is an approach move, checked by PathGuard before it starts as the
  /// REPOS subroutine's are: the JogOfPath channel's manual return to the contour.
  bool approach_program = false;
};

}  // namespace vmt::control::channel
