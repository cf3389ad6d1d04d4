#pragma once
// A scene (format v1, docs/scene-format.md): a machine model, a workpiece, the initial state, a
// drive-level timeline of operator/test actions, expectations and snapshots. Scenes are the
// demos, the tests and the benchmark inputs at once.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "control/channel/channel_config.hpp"
#include "control/channel/channel_types.hpp"
#include "control/gateway/signal_table.hpp"
#include "control/measure/measuring_pages.hpp"
#include "control/nc/interpreter.hpp"
#include "control/nc/program.hpp"
#include "sim/backend/machine_backend.hpp"
#include "sim/model/machine_model.hpp"
#include "sim/model/revolved_part.hpp"

namespace vmt::sim {

/// The longest scene (a day): every time in a scene lies in 0..kMaxSceneSeconds.
inline constexpr double kMaxSceneSeconds = 86400;
/// Fastest spindle (rpm) and feed (mm/min | deg/min) a scene step may command: far above any
/// lathe's, the drives' own limits apply below them.
inline constexpr double kMaxRpm = 1e5;
inline constexpr double kMaxFeed = 1e7;

enum class BackendKind { kPhysics, kKinematic };
inline const char* ToString(BackendKind k) {
  return k == BackendKind::kPhysics ? "physics" : "kinematic";
}

/// The part in the chuck with its true dimensions (a stock cylinder, a stepped shaft, a face
/// groove), in its link's frame: what PathGuard checks against, the probe touches and the
/// pictures show.
struct Workpiece {
  bool present = false;
  RevolvedPart part{"workpiece", "spindle", {}};
  render::Rgba colour{0.78f, 0.79f, 0.80f, 1.0f};
};

/// The NC channel of a scene: its programs (main first) and the drives it commands.
struct NcSetup {
  bool present = false;
  std::vector<std::shared_ptr<const control::nc::ParseResult>> programs;
  /// The machine's NC data with the scene's choices applied (axes, spindle, zero offsets, tool
  /// list).
  NcMachineData data;
  std::vector<int> axis_drives;  ///< channel axes' drives, in channel order
  double override = 1.0;
  control::nc::ModalState initial;  ///< `initial:` G codes of the scene (e.g. G54)
  /// The channel as it runs: built from the machine and the choices above once they are read
  /// (ChannelConfigOf); a run starts its channel from it.
  control::channel::ChannelConfig channel;
  bool aux_handshake = false;       ///< M/H/Q/T wait for the PLC's acknowledgement
  /// `tool_storage_nc: yes`: the model's tool storage axis is NC-controlled (REPOS manual 3.4,
  /// 4.2): the channel commands its drive, PxxC.MGPOS / MGNEG jog it, MTP returns it.
  bool tool_storage_nc = false;
  /// `jog_of_path: FILE`: a JogOfPath channel on the channel's feed axes runs this program, the
  /// manual return to the contour during block search (twincat-cnc-block-search-de.md 4.2.1).
  std::shared_ptr<const control::nc::ParseResult> jog_of_path;
  /// The gateway's signals for this machine (vmt signals MODEL); the runner's signal image.
  std::shared_ptr<const std::vector<control::gateway::Signal>> signals;
  /// The machine data pages of fast measurement as the run starts with them: `measuring_pages:`
  /// presets, else the stylus pages of the model's `probe:`.
  control::measure::MeasuringPages measuring_pages;
  /// Gateway signals the PLC or the operator writes, set once at t = 0 before anything runs:
  /// the block search CNC objects of `block_search:` (twincat-cnc-block-search-de.md 5, e.g.
  /// mc_cmd_bs_type_w) and `vmt run --set NAME=VALUE`. STRING signals keep `text`.
  struct SignalPreset {
    int id = -1;
    double number = 0;
    std::string text;
  };
  std::vector<SignalPreset> presets;
};

/// Adds the preset NAME=VALUE (a full gateway signal name; true/false for BOOL, a number, or the
/// text of a STRING) to `nc`: "" or what is wrong with it.
std::string AddSignalPreset(NcSetup& nc, const std::string& name, const std::string& value);

/// The embedded PLC program (plc_programs.hpp) and its scan time.
struct PlcSetup {
  bool present = false;
  std::string program;
  /// The program's constant wiring of block inputs (fast-measurement 7.2 typical application:
  /// TRUE --- ENABLE, 1 --- ACHS_NR_1): gateway signals the PLC writes, set once at t = 0.
  std::vector<std::pair<int, double>> constants;
  double period_s = 0.004;  ///< DESIGN.md: 4 ms, 16 drive ticks
};

/// What a wait_until step or an expectation looks at.
struct Condition {
  enum class Kind {
    kInput,
    kInPosition,
    kAtSpeed,
    kStandstill,
    kClutch,
    kNc,
    kSignal
  } kind = Kind::kInput;
  int index = -1;           ///< I/O point, drive, clutch or gateway signal
  double signal_value = 1;  ///< kSignal: the value wanted (BOOL as 0/1)
  bool value = true;        ///< input level or status bit wanted
  ClutchState clutch = ClutchState::kEngaged;
  control::channel::ChannelState nc = control::channel::ChannelState::kEnded;
};

struct TimelineStep {
  enum class Kind {
    kMove,
    kSpeed,
    kOrient,
    kOff,
    kOutput,
    kWait,
    kWaitUntil,
    kNcStart,
    kNcStop,
    kNcReset,
    kNcOverride,
    kNcSingleBlock,
    kNcOptionalStop,
    kNcMode,
    kNcJogIncrement,
    kNcJogMode,
    kNcMdi,
    kNcSelect,  ///< program selection: `code` indexes NcSetup::programs
    kNcReverse,
    kNcZeroOffset,  ///< operator edit: zero offset G`code` of `axis` := target (REPOS 2.5)
    kNcToolLength,  ///< operator edit: length of tool `code` edge `edge` along `axis` := target
    kJog,
    kHandwheel,
    kSignal,
    kFault,
  } kind;
  double not_before_s = 0;  ///< `at:`; 0 = as soon as the previous step is done
  int drive = -1;
  int io = -1;
  double target = 0;      ///< move: position (mm|deg); speed: deg/s or mm/s; orient: deg
  double feed = 0;        ///< move: mm/s | deg/s
  int parameter_set = 0;  ///< move, speed, orient: the drive parameter set the setpoint names
  bool level = false;     ///< output value
  int code = 0;           ///< kNcMode: ChannelMode; kNcJogMode: JOGM code; kHandwheel: counts;
                          ///< kNcSelect: program index
  int signal = -1;        ///< kSignal: gateway signal the (default) PLC writes; value in `target`
  int axis = -1;          ///< kJog, kNcZeroOffset, kNcToolLength: channel axis index
  int edge = 0;           ///< kNcToolLength: D
  int direction = 0;      ///< kJog: +1 | -1
  int fictive = -1;  ///< kJog, kHandwheel of a fictive axis of G31: 0 X1, 1 Y1 (axis stays -1)
  bool jog_to = false;    ///< kJog to the axis position `target`: an increment, one tap
  double wait_s = 0;
  Condition until;
  double timeout_s = 10;
  std::string text;  ///< "timeline[3]: move Z to 250" for events and messages
  std::string mdi;   ///< kNcMdi: the blocks
  /// kFault: what fails. A sensor or valve sticks at `level` (io), a drive loses its power
  /// stage (drive), the PLC misses `code` scans (its watchdog trips after two), the PLC's
  /// Modbus client is gone for good (embedded: every scan from then on is missed; vmt serve:
  /// every client is disconnected), or a fault is cleared again (io or drive).
  enum class Fault {
    kSensorStuck,
    kValveStuck,
    kDrive,
    kPlcOverrun,
    kPlcClientGone,
    kClear
  } fault{};
};

struct Expectation {
  enum class Quantity {
    kPosition,
    kVelocity,
    kRpm,
    kFollowingError,
    kParameterSet,  ///< the drive's current parameter set (S-0-0254)
    kInput,
    kClutch,
    kNc,
    kSignal,
    kDriveTrip  ///< `{drive:, trip:}`: the drive's amplifier has tripped by then
  } quantity;
  double at_s = -1;  ///< -1: at the end of the run
  int index = -1;    ///< drive, I/O point, clutch or gateway signal
  double value = 0;
  double tolerance = 0;
  ClutchState clutch = ClutchState::kEngaged;
  control::channel::ChannelState nc = control::channel::ChannelState::kEnded;
  /// kDriveTrip: the fault bits it means (control::drive_status kOverload | kOverspeed |
  /// kParameterSetError; any of them). A trip no such expectation covers fails the run.
  uint32_t trip = 0;
  std::string text;  ///< "expect[2]: Z position 250 +- 0.01 at 3 s"
};

/// What an event snapshot waits for (snapshots `on:`): a collision (a PathGuard check that
/// found a contact, or a stylus beyond its over-travel), a drive's probe latch, the NC entering
/// its error state.
enum class SnapshotEvent { kNone, kCollision, kProbeLatch, kError };
const char* ToString(SnapshotEvent e);

/// A rectangle of a snapshot in pixels, from its top left corner.
struct SnapshotMaskRect {
  int x = 0, y = 0, width = 0, height = 0;
};

/// A picture at a time (`at:`), or at the first `limit` occurrences of an event (`on:`).
struct SnapshotSpec {
  double at_s = 0;                          ///< time snapshots
  SnapshotEvent on = SnapshotEvent::kNone;  ///< event snapshots (at_s unused)
  int limit = 1;                            ///< event snapshots: occurrences pictured
  std::string camera;
  int width = 640, height = 480;
  std::string file;  ///< time snapshots: relative to the output folder; event ones name theirs
  /// Comparison with a golden picture (vmt golden): pixels left out of it (`mask:`), and the
  /// tolerance where it is not the project's (`allowed_fraction:`, `tolerance_levels:`).
  std::vector<SnapshotMaskRect> mask;
  std::optional<double> allowed_fraction;
  std::optional<int> tolerance_levels;
  int series = -1;  ///< index into Scene::snapshot_series, -1: not part of a series
};

/// `snapshots: - {every:, from:, to:}`: time snapshots at even steps and a contact sheet of
/// them all, a grid in time order (render/contact_sheet.hpp).
struct SnapshotSeries {
  std::string sheet;          ///< the contact sheet's file, relative to the output folder
  std::vector<size_t> shots;  ///< indexes into Scene::snapshots, in time order
};

struct Scene {
  std::string file;
  std::string name;
  std::shared_ptr<const MachineModel> model;
  BackendKind backend = BackendKind::kPhysics;
  double duration_s = 1;
  double trace_period_s = 0.001;
  Workpiece workpiece;
  InitialState initial;
  NcSetup nc;
  PlcSetup plc;
  std::vector<TimelineStep> timeline;
  std::vector<Expectation> expectations;
  std::vector<SnapshotSpec> snapshots;
  std::vector<SnapshotSeries> snapshot_series;
  std::vector<NamedCamera> cameras;  ///< the model's, then the scene's (same name replaces)
  /// `probe: {sampling_phase: seeded, seed: N}`: the drives' probe sampling phase (off: fixed).
  ProbeSamplingPhase probe_sampling;

  const NamedCamera* Camera(const std::string& name) const;
};

/// Loads a scene and its model. Throws ModelError naming the file and the YAML path.
Scene LoadScene(const std::string& path);

}  // namespace vmt::sim
