#pragma once
// Repositioning and NC-block restart (REPOS manual): what the channel keeps of an interrupted
// program, the targets it returns the axes and the spindle to, and the REPOS screen's data.
// The rules of one axis or key (the adjustment window 6.1, the zone a feed axis may be jogged
// in 3.2, the spindle keys that restore a spindle 3.3), and Repositioning, the function's state
// with what it reads of the channel (ReposView): the targets, PxxS.CREST, the screen. The
// program's side, the REPOS subroutine in the interrupted program's place, is the channel's
// (channel_repositioning.cpp).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "control/axes/axis_parameters.hpp"
#include "control/axes/headstock_changeover.hpp"
#include "control/axes/tool_table.hpp"
#include "control/axes/zero_offsets.hpp"
#include "control/channel/further_spindles.hpp"
#include "control/channel/main_spindle_state.hpp"
#include "control/drive_bus.hpp"
#include "control/nc/coordinate_transformation.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

struct ChannelConfig;
class FurtherSpindleControl;

/// The function the PLC asks for with PxxC.REPOS / PxxC.RESTA (7.1).
enum class ReposFunction : uint8_t {
  kNone,
  kRepositioning,  ///< back to the interruption point
  kRestart,        ///< back to the start of the interrupted block
};
const char* ToString(ReposFunction f);

/// The program's state when it was interrupted (2.1), taken when the channel enters manual mode
/// from the interruption. Positions are the axes' (machine coordinates); a zero offset or tool
/// edit moves them by the change of the translation (2.5), see Repositioning::Target.
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

/// The M function a spindle command runs under: 3, 4, 5 or 19 (positioned).
int SpindleMOf(const DriveSetpoint& command);

/// 7.3: a rotary axis positioned in rotary axis mode before the interruption has its state back
/// only in that mode: in spindle mode (a spindle key selected it, C-axis manual 4.2) it is no
/// positioned axis, whatever angle the spindle stands at. `headstock` null: none.
bool OutOfItsMode(const axes::HeadstockChangeover* headstock, int rotary_axis, size_t axis);

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

/// Repositioning's state: the interruption, what the PLC asks for and what the NC does.
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

/// What repositioning reads of the channel for one call; the channel builds it, nothing of it
/// is kept.
struct ReposView {
  const ChannelConfig& config;
  const axes::ZeroOffsetTable& zero_offsets;   ///< the channel's, as the program wrote them
  const axes::ToolTable& tools;                ///< the same
  const std::vector<double>& shift;            ///< G92's part of the translation, per axis
  const std::vector<double>& commanded;        ///< the channel axes' commands
  const axes::HeadstockChangeover* headstock;  ///< null: none
  const MainSpindleState& spindle;
  const FurtherSpindleControl& further;
  /// The tool storage axis' drive position this NC cycle; null: the channel has none.
  const double* tool_storage = nullptr;
};

/// Repositioning and NC-block restart: it keeps the interrupted program's place, takes the
/// PLC's call, checks on the NC cycle whether the state before the interruption is restored
/// and makes the REPOS screen. The program run tells it when the REPOS subroutine and its
/// closing move run (StartRun, StartClosing).
class Repositioning {
 public:
  /// The program is left, interrupted (2.1): its state, and where the axes are commanded now.
  void Interrupt(Interruption interruption, const std::vector<double>& commanded);
  /// The interruption point is `point` after all (backward travel left from there).
  void MoveInterruptionPoint(const std::vector<double>& point);
  /// PxxC.REPOS / PxxC.RESTA (7.1), levels given every NC cycle; both at once ask for neither.
  void Request(bool repositioning, bool restart);
  /// The REPOS subroutine starts (`subroutine`), or without one the closing move (4.1).
  void StartRun(bool subroutine);
  /// Stopped during the REPOS subroutine and manual mode entered: the next start runs it again.
  void Rerun() { data_.rerun = true; }
  /// The subroutine has returned: the closing move to the exact target runs.
  void StartClosing() { data_.closing = true; }
  /// The interruption is over: the program continues, or Control-Reset.
  void Clear();

  /// The interruption; null when there is none.
  const Interruption* interruption() const {
    return data_.interruption ? &*data_.interruption : nullptr;
  }
  ReposFunction function() const { return data_.function; }
  bool called() const { return data_.function != ReposFunction::kNone; }
  bool conditions_restored() const { return data_.crest; }  ///< PxxS.CREST, last NC cycle
  bool run() const { return data_.run; }          ///< the REPOS subroutine or closing move runs
  bool closing() const { return data_.closing; }  ///< the closing move runs
  bool finish() const { return data_.finish; }    ///< no subroutine: close and continue
  bool rerun() const { return data_.rerun; }
  /// Where each axis stood when the function was called.
  const std::vector<double>& start() const { return data_.start; }

  /// The NC cycle (7.1, 7.3): whether an axis has left the contour, the function the NC
  /// performs, PxxS.CREST. `interrupted`: the program holds or the subroutine runs; `motion`:
  /// in manual mode a jog still moves or its key is held, which keeps a withdrawn function
  /// until it has ended (7.1 instruction).
  void Cycle(const ReposView& v, const AmplifierTelegram& at, bool interrupted, bool motion);
  /// Per channel axis the function's target (machine coordinates); NaN: no target.
  std::vector<double> Target(const ReposView& v) const;
  /// G31 was active at the interruption: the channel axes X and C, whose window (6.1) and
  /// screen values (5.2) go by the fictive point.
  bool Fictive(const ReposView& v, int& x, int& c) const;
  /// The fictive point of axis positions `position` in the interrupted block's frame.
  nc::FictivePoint FictiveOf(const ReposView& v, const std::vector<double>& position, int x,
                             int c) const;
  /// The main spindle counts (7.3): a spindle in spindle mode before the interruption.
  bool SpindleRelevant(const ReposView& v) const;
  /// The main spindle has its command before the interruption and runs at it (or stands in
  /// position).
  bool SpindleRestored(const ReposView& v, const AmplifierTelegram& at) const;
  /// 6.2: the tool storage axis is back (only with Bxx.045 = yes).
  bool ToolStorageRestored(const ReposView& v) const;
  /// The REPOS screen (2.2) but for PxxS.REPOS, the feed override and the program's file,
  /// which are the channel's; `whole` as Channel::repos_status.
  ReposStatus Status(const ReposView& v, const AmplifierTelegram* at, bool whole) const;

 private:
  ReposData data_;
};

}  // namespace vmt::control::channel
