#pragma once
// The axis signals of the C-axis manual's table (4.2) that the NC derives from an axis' drive
// and switches alone, for the channel axes and the main spindle alike: the waypoints AxxS.WP0..7,
// the position strobe AxxC.STRBP with the position it saves (AxxS.STRBPOS), and the safety
// limit switch AxxC.OTRVL and thermal protection switch AxxC.MTAS, whose opening stops the
// channel. ChannelGateway serves it every NC cycle.

#include <array>
#include <vector>

#include "control/channel/channel_types.hpp"
#include "control/drive_bus.hpp"
#include "control/gateway/signal_image.hpp"

namespace vmt::control::gateway {

class AxisMonitor {
 public:
  /// `axis_numbers`: Axx of each channel axis; `spindle_number`: Axx of the main spindle, -1
  /// if none. A spindle with rotary axis capability shares its number with the rotary axis
  /// (C-axis manual 2.2): one set of signals, served as that channel axis.
  AxisMonitor(SignalImage& image, const std::vector<int>& axis_numbers, int spindle_number);

  /// PLC -> NC: an OTRVL or MTAS that goes from 1 to 0 stops the channel (Channel::SafetyStop).
  void ReadControls(channel::Channel& ch);
  /// NC -> PLC: waypoints; a rising STRBP saves the actual position into AxxS.STRBPOS.
  void WriteStatus(const channel::Channel& ch, const AmplifierTelegram& at);

 private:
  struct Axis {
    int channel_axis = -1;  ///< index in the channel's axes; -1: the main spindle
    std::string name;       ///< Axx, for the messages
    int otrvl = -1, mtas = -1, strbp = -1, strbpos = -1;
    std::array<int, 8> wp{-1, -1, -1, -1, -1, -1, -1, -1};
    // Switches act when they change (from 1 to 0), as the enabling signals do: BOOL signals
    // start 0, and a PLC that never writes them leaves the axis in operation.
    bool last_otrvl = false, last_mtas = false, last_strbp = false;
  };
  SignalImage* image_;
  std::vector<Axis> axes_;
};

}  // namespace vmt::control::gateway
