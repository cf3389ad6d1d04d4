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
};

struct ChannelConfig {
  std::vector<ChannelAxis> axes;
  int spindle_drive = -1;   ///< main spindle (S, M3/M4/M5/M19); -1 if none
  int ticks_per_cycle = 4;  ///< NC cycle 1 ms at the 250 us drive tick
  double tick_s = 250e-6;
};

enum class ChannelState { kIdle, kRunning, kHold, kEnded, kError };
const char* ToString(ChannelState s);

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
  DriveSetpoint spindle_;
};

}  // namespace vmt::control::channel
