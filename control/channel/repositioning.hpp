#pragma once
// Repositioning and NC-block restart (REPOS manual): what the channel keeps of an interrupted
// program, the targets it returns the axes and the spindle to, and the REPOS screen's data.
// Plain data and the rules that need no channel: the adjustment window (6.1), the zone a feed
// axis may be jogged in (3.2), the spindle keys that restore a spindle (3.3).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "control/axes/axis_parameters.hpp"
#include "control/axes/headstock_changeover.hpp"
#include "control/channel/further_spindles.hpp"
#include "control/drive_bus.hpp"
#include "control/nc/coordinate_transformation.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

/// The function the PLC asks for with PxxC.REPOS / PxxC.RESTA (7.1).
enum class ReposFunction : uint8_t {
  kNone,
  kRepositioning,  ///< back to the interruption point
  kRestart,        ///< back to the start of the interrupted block
};
const char* ToString(ReposFunction f);

/// The program's state when it was interrupted (2.1), taken when the channel enters manual mode
/// from the interruption. Positions are the axes' (machine coordinates); a zero offset or tool
/// edit moves them by the change of the translation (2.5), see ReposTarget.
struct Interruption {
  std::vector<double> point;        ///< per channel axis; NaN: the axis is on no contour
  std::vector<double> block_start;  ///< the interrupted block's start (the point between blocks)
  std::vector<double> translation;  ///< program -> axis at the interruption
  nc::ModalState modal;             ///< of the interrupted block: F, T, M and G state
  uint32_t program = 0;             ///< the interrupted program (index in the channel's list)
  uint32_t line = 0;                ///< its source line, 0 between blocks
  DriveSetpoint spindle;            ///< the main spindle's command (M3/M4 speed, M19 position)
  int spindle_m = 5;                ///< its M function: 3, 4, 5 or 19
  /// The further spindles' programmed speed and direction (ChannelConfig::spindles' order).
  std::vector<FurtherSpindleState> further_spindles;
  axes::HeadstockMode headstock_mode = axes::HeadstockMode::kNone;  ///< kNone: no headstock
  bool left_contour = false;  ///< an axis has been jogged away from `point` (2.1)
  double tool_storage = 0;    ///< the tool storage axis' position (deg), if there is one
};

/// 6.2: the tool storage axis counts as returned within this much of its former position (deg
/// or mm; the manual gives no window, a turret station is indexed far more exactly).
inline constexpr double kToolStorageWindow = 0.05;

/// 6.1: the axis is adjusted when its distance to go is within Cxx.086; a modulo rotary axis
/// (endless, 3.2) measures the distance the short way round.
double ReposDistanceToGo(const axes::AxisParameters& axis, double target, double actual);
bool WithinReposWindow(const axes::AxisParameters& axis, double target, double actual);

/// 6.1 instruction: under a coordinate transformation with fictive axes (G31) the NC uses the
/// adjustment window of the axis whose meaning is X: the fictive point (X1, Y1) is adjusted
/// when its distance to the target point is within X's Cxx.086.
bool WithinFictiveWindow(const axes::AxisParameters& x_axis, nc::FictivePoint target,
                         nc::FictivePoint actual);

/// 3.2: between the target and the position where the function was called the operator may jog
/// the axis back and forth, never past the target. The zone [low, high]; an endless rotary axis
/// has none (it may pass its target, 3.2 instruction).
struct ReposZone {
  bool limited = false;
  double low = 0, high = 0;
};
ReposZone ZoneOf(const axes::AxisParameters& axis, double target, double start);
/// 3.2 under G31, manual repositioning in Cartesian coordinates (5.2): a fictive axis may be
/// jogged between its target and where it stood when the function was called, never past it.
ReposZone FictiveZoneOf(double target, double start);

/// 3.3: the spindle keys that restore a spindle's state before the interruption: M03 by
/// AxxC.M3 or M4, M04 by M4 or M3, M05 by M5, M19 by M19.
bool KeyRestoresSpindle(int spindle_m_before, int key);

/// One feed axis on the REPOS screen (2.2).
struct ReposAxisStatus {
  std::string name;
  double final_value = 0;    ///< the target: interruption point or block start
  double command_value = 0;  ///< the axis' command now
  double distance_to_go = 0;
  bool relevant = false;  ///< takes part (Cxx.086 != 0, on a contour, in the process)
  bool adjust = false;    ///< the adjust symbol: relevant and outside its window
};

/// The main spindle on the REPOS screen (2.2).
struct ReposSpindleStatus {
  bool relevant = false;   ///< a spindle in spindle mode before the interruption (7.3)
  double actual_rpm = 0;   ///< the spindle's actual speed, signed
  double command_rpm = 0;  ///< its command before the override, signed; 0 for M19
  double override = 1;     ///< AxxC.SOVR
  int actual_m = 5;        ///< the M function it runs under now
  int command_m = 5;       ///< the one it had before the interruption
  bool adjust = false;
};

/// The REPOS screen's data (2.2) and the gateway's status (7.2, 7.3).
struct ReposStatus {
  bool allowed = false;  ///< PxxS.REPOS
  ReposFunction function = ReposFunction::kNone;
  bool conditions_restored = false;  ///< PxxS.CREST
  bool left_contour = false;
  bool subroutine_running = false;  ///< the REPOS subroutine runs (4.1)
  std::vector<ReposAxisStatus> axes;
  ReposSpindleStatus spindle;
  std::vector<ReposFurtherSpindleStatus> further_spindles;  ///< S2, S3 (7.3: all spindles)
  /// 2.2: the tool storage axis' adjust symbol after the T word (only with Bxx.045 = yes).
  bool tool_storage_relevant = false, tool_storage_adjust = false;
  double programmed_feed = 0;  ///< F of the interrupted block, mm/min | mm/rev
  double feed_override = 1;
  std::string program;  ///< the interrupted program's file
  uint32_t line = 0;
  int tool = 0, correction = 0;
  int spindle_m = 5, coolant = 9;
  std::vector<int> g_codes;  ///< the interrupted block's modal G functions
};

/// The channel's repositioning and NC-block restart: the interruption, what the PLC asks for
/// and what the NC does.
struct ReposData {
  std::optional<Interruption> interruption;
  ReposFunction request = ReposFunction::kNone;   ///< what the PLC asks for
  ReposFunction function = ReposFunction::kNone;  ///< what the NC does (7.1)
  std::vector<double> start;  ///< where each axis stood when the function was called
  bool crest = false;         ///< PxxS.CREST (7.3)
  bool run = false;           ///< the REPOS subroutine or the closing move runs (4.1)
  bool closing = false;       ///< the closing move to the exact target runs
  bool finish = false;        ///< no subroutine: close and continue
  /// Stopped during the REPOS subroutine and manual mode entered: the next start runs it again
  /// from `.REPOS` (the operator may have jogged; the interruption point stays the target).
  bool rerun = false;
};

}  // namespace vmt::control::channel
