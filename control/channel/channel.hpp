#pragma once
// One NC channel in automatic mode: it runs a program through the interpreter, interpolates
// each prepared block on the NC cycle (G00 with every axis at its rapid limit, ending together;
// G01/G02/G03 at path feed, acceleration-limited; feed override; feed hold on the path),
// fine-interpolates to the drive tick, and commands the spindle. It writes setpoints for its own
// drives into the master telegram and leaves the others alone.

#include <algorithm>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "control/channel/path_profile.hpp"
#include "control/drive_bus.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

struct ChannelAxis {
  std::string name;         ///< program address: X, Z, C
  int drive = -1;           ///< DriveBus index
  double rapid_per_s = 0;   ///< mm/s | deg/s
  double acceleration = 0;  ///< mm/s^2 | deg/s^2
  bool rotary = false;
  double jog_per_s = 0;  ///< jog velocity; 0: a tenth of the rapid
};

struct ChannelConfig {
  std::vector<ChannelAxis> axes;
  int spindle_drive = -1;   ///< main spindle (S, M3/M4/M5/M19); -1 if none
  int ticks_per_cycle = 4;  ///< NC cycle 1 ms at the 250 us drive tick
  double tick_s = 250e-6;
};

enum class ChannelState { kIdle, kRunning, kHold, kEnded, kError };
const char* ToString(ChannelState s);

/// Operating modes. Automatic runs the program (single block makes it semi-automatic); manual
/// moves the axes with the jog keys, continuously or by increments.
enum class ChannelMode { kAutomatic, kManual };
const char* ToString(ChannelMode m);

class Channel {
 public:
  /// `programs`: the main program first, then the subprograms it may call; they must outlive
  /// the channel.
  Channel(ChannelConfig config, std::vector<const nc::Program*> programs);

  void Start();  ///< cycle start: run, or resume after a hold
  void Stop();   ///< feed hold: brake on the path
  void Reset();  ///< Control-Reset: stop, back to the program start
  void SetFeedOverride(double fraction) { override_ = std::clamp(fraction, 0.0, 2.0); }
  /// Single block (semi-automatic): after each block the channel holds until the next start.
  void SetSingleBlock(bool on) { single_block_ = on; }
  /// Changes the mode; refused (false) while a program runs. An interrupted program (hold)
  /// stays interrupted: the axes may be jogged away and the program continued later.
  bool SetMode(ChannelMode mode);
  ChannelMode mode() const { return mode_; }
  /// Jog increment in mm | deg; 0 jogs continuously while the key is held.
  void SetJogIncrement(double increment) { jog_increment_ = std::abs(increment); }
  /// Jog key of a channel axis: +1 positive, -1 negative, 0 released. Manual mode only; an
  /// increment, once started, is completed.
  void Jog(size_t axis, int direction);
  /// Direction the axis is commanded to move this NC cycle: +1, -1 or 0 (MVPOS / MVNEG).
  int AxisMotion(size_t axis) const;
  void SetEventSource(std::function<bool(int)> source) { events_ = std::move(source); }

  /// One drive tick: reads the feedback, interpolates on the NC cycle, writes setpoints.
  void Tick(const AmplifierTelegram& at, MasterTelegram& mdt);

  ChannelState state() const { return state_; }
  /// "file:line:column: error: text" of the error that stopped the program.
  const std::string& error() const { return error_; }
  /// Commanded position of a channel axis (program coordinates, mm | deg).
  double position(size_t axis) const { return commanded_[axis]; }
  /// Source line of the block in work, 0 when none.
  uint32_t line() const;

 private:
  bool NextBlock(const AmplifierTelegram& at);
  void Interpolate(double dt);
  void Fail(const std::string& message);

  ChannelConfig config_;
  std::vector<const nc::Program*> programs_;
  std::unique_ptr<nc::Interpreter> interpreter_;
  std::function<bool(int)> events_;
  ChannelState state_ = ChannelState::kIdle;
  std::string error_;
  double override_ = 1.0;
  bool single_block_ = false;

  // The block in work.
  bool active_ = false;
  nc::PreparedBlock block_;
  std::vector<double> start_, end_;
  double arc_centre_[2] = {0, 0}, arc_radius_ = 0, arc_start_angle_ = 0, arc_sweep_ = 0;
  int arc_axes_[2] = {-1, -1};  ///< channel axes of the arc plane, -1 when not an arc
  PathProfile profile_;
  double dwell_left_s_ = 0;

  // Positions: commanded at the last two NC cycles, for fine interpolation.
  std::vector<double> commanded_, previous_;
  int tick_in_cycle_ = 0;
  bool holding_positions_ = false;  ///< once started, the channel owns its axes' setpoints
  bool start_pending_ = false;
  bool take_over_pending_ = false;  ///< own the axes' setpoints from the next tick on
  void Jogging(double dt);

  ChannelMode mode_ = ChannelMode::kAutomatic;
  double jog_increment_ = 0;
  struct JogAxis {
    int key = 0;            ///< key held: +1, -1, 0
    double velocity = 0;    ///< continuous jog
    PathProfile increment;  ///< incremental jog in progress when rate or u < 1
    double from = 0, to = 0;
    bool stepping = false;
  };
  std::vector<JogAxis> jog_;
  std::vector<double> interruption_point_;  ///< commanded position when manual was entered
  DriveSetpoint spindle_;
};

}  // namespace vmt::control::channel
