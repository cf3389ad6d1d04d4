#pragma once
// The `nc:` section of machine.yaml: the NC process of the machine, its axes with their axis
// parameters (Cxx.*), the process parameters (Bxx.*), the zero offset table and the tool list.
// A scene may replace the zero offsets and the tool list (a different job on the same machine).

#include <vector>

#include "control/axes/axis_parameters.hpp"
#include "control/axes/tool_table.hpp"
#include "control/axes/zero_offsets.hpp"
#include "control/path_guard.hpp"

namespace vmt::sim {

class YamlNode;
struct MachineModel;

struct NcMachineData {
  bool present = false;
  control::axes::ProcessParameters process;
  std::vector<control::axes::AxisParameters> axes;  ///< channel axes, in channel order
  int spindle_drive = -1;
  int spindle_number = -1;  ///< Axx of the spindle; -1: one past the highest axis number
  /// The main spindle's parameters (`spindle:` map): jog_per_s (deg/s) from `jogging_speed`
  /// (rpm), jog_spindle_position (deg), max_spindle_rpm (Cxx.049, default the drive's limit),
  /// the encoder's limit frequency. Its name, number and drive are not set here.
  control::axes::AxisParameters spindle;
  /// The spindle's rotary axis mode (C-axis manual): the channel axis that is its rotary axis
  /// (a separate servo, section 3, or on the spindle's own drive, section 2), -1 if none; and
  /// the drive parameter set of rotary axis mode (section 2, 0: no switch).
  int rotary_axis = -1;
  int rotary_parameter_set = 0;
  /// `changeover_message_s`: a headstock changeover the PLC has not acknowledged for this long
  /// is reported with its likely cause (HeadstockConfig::stall_message_s).
  double changeover_message_s = 5;
  control::axes::ZeroOffsetTable zero_offsets;
  control::axes::ToolTable tools;
  /// `path_guard: stop | warn | off`: what a contact PathGuard finds ahead of a move does.
  control::GuardReaction path_guard = control::GuardReaction::kStop;
  int tool_storage_drive = -1;  ///< the turret's drive (`tool_storage: T`), -1 if none
  /// The tool storage axis' parameters (`tool_storage: {name: T, Cxx.020: ...}`): an
  /// NC-controlled one's jogging speeds and parametric jogging distance (REPOS manual 3.4).
  control::axes::AxisParameters tool_storage;
  /// Its stations (`stations: 12`), evenly spaced over a turn: Tn is station n at
  /// (n - 1) * 360 / stations deg. 0: not given.
  int tool_storage_stations = 0;
};

/// Reads machine.yaml's `nc:`; the drives must be loaded. Throws ModelError (file, YAML path).
NcMachineData ReadNcMachineData(const MachineModel& m, const YamlNode& node);

/// `zero_offsets: {G54: {X: 0, Z: 200}, ...}` for the given channel axes.
control::axes::ZeroOffsetTable ReadZeroOffsets(
    const std::vector<control::axes::AxisParameters>& axes, const YamlNode& node);

/// `tools: [{T: 1, D: 1, X: 0, Z: 0, radius: 0.8, edge: 3}, ...]`; lengths in mm per axis.
control::axes::ToolTable ReadToolTable(const std::vector<control::axes::AxisParameters>& axes,
                                       const YamlNode& node);

}  // namespace vmt::sim
