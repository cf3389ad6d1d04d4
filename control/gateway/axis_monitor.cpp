#include "control/gateway/axis_monitor.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "control/channel/channel.hpp"

namespace vmt::control::gateway {
namespace {

std::string AxisPrefix(int number) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "A%02d", number);
  return buf;
}

}  // namespace

AxisMonitor::AxisMonitor(SignalImage& image, const std::vector<int>& axis_numbers,
                         int spindle_number)
    : image_(&image) {
  auto add = [&](int number, int channel_axis) {
    const std::string a = AxisPrefix(number);
    Axis axis;
    axis.channel_axis = channel_axis;
    axis.name = a;
    axis.otrvl = image.Find(a + "C.OTRVL");
    axis.mtas = image.Find(a + "C.MTAS");
    axis.strbp = image.Find(a + "C.STRBP");
    axis.strbpos = image.Find(a + "S.STRBPOS");
    for (int k = 0; k < 8; ++k) axis.wp[k] = image.Find(a + "S.WP" + std::to_string(k));
    if (axis.otrvl >= 0) axis.last_otrvl = image.Bool(axis.otrvl);
    if (axis.mtas >= 0) axis.last_mtas = image.Bool(axis.mtas);
    if (axis.strbp >= 0) axis.last_strbp = image.Bool(axis.strbp);
    axes_.push_back(axis);
  };
  bool spindle_is_axis = false;
  for (size_t i = 0; i < axis_numbers.size(); ++i) {
    add(axis_numbers[i], static_cast<int>(i));
    spindle_is_axis = spindle_is_axis || axis_numbers[i] == spindle_number;
  }
  if (spindle_number > 0 && !spindle_is_axis) add(spindle_number, -1);
}

void AxisMonitor::ReadControls(channel::Channel& ch) {
  const SignalImage& im = *image_;
  for (Axis& a : axes_) {
    const channel::ChannelConfig& c = ch.config();
    if (a.channel_axis < 0 && c.spindle_drive < 0) continue;
    // Built only for a message: the switches are read every NC cycle.
    const auto name = [&] {
      return a.channel_axis >= 0 ? "axis " + c.axes[a.channel_axis].name
                                 : "spindle " + (c.spindle.name.empty() ? "S1" : c.spindle.name);
    };
    // C-axis manual 4.2 only asks that the switches be 1 on a digital spindle and gives no
    // reaction to a 0. vmt's reading: a switch that opens is a fault of the axis, as on the
    // machine a tripped limit switch or a hot motor takes the drive's power: immediate stop
    // and an error message; Control-Reset clears it, and the operator jogs off the switch.
    const auto opened = [&](int id, bool& last) {
      if (id < 0) return false;
      const bool now = im.Bool(id), fell = last && !now;
      last = now;
      return fell;
    };
    if (opened(a.otrvl, a.last_otrvl))
      ch.SafetyStop(name() + " (" + a.name + "): safety limit switch open (AxxC.OTRVL)",
                    channel::kMsgSafetyLimitSwitch);
    if (opened(a.mtas, a.last_mtas))
      ch.SafetyStop(name() + " (" + a.name + "): thermal protection switch open (AxxC.MTAS)",
                    channel::kMsgThermalSwitch);
  }
}

void AxisMonitor::WriteStatus(const channel::Channel& ch, const AmplifierTelegram& at) {
  SignalImage& im = *image_;
  const channel::ChannelConfig& c = ch.config();
  for (Axis& a : axes_) {
    const bool spindle = a.channel_axis < 0;
    const axes::AxisParameters& p = spindle ? c.spindle : c.axes[a.channel_axis];
    const int drive = spindle ? c.spindle_drive : p.drive;
    if (drive < 0 || drive >= static_cast<int>(at.feedback.size())) continue;
    const bool rotary = spindle || p.rotary;
    // Machine coordinates: a rotary axis' and a spindle's within one turn, as its waypoints.
    double position = at.feedback[drive].position;
    if (rotary) position -= 360 * std::floor(position / 360);
    // 4.2: "The NC saves the current position" on the strobe. The manual names no place to
    // read it from; vmt shows it in AxxS.STRBPOS: the actual position of the NC cycle in
    // which the PLC's rising edge arrived.
    if (a.strbp >= 0) {
      const bool now = im.Bool(a.strbp);
      if (now && !a.last_strbp && a.strbpos >= 0) im.SetReal(a.strbpos, position);
      a.last_strbp = now;
    }
    // 4.2: the waypoint signals are valid only after homing, and the NC updates them in main
    // spindle mode and rotary axis mode alike. The manual gives their parameters (Cxx.025..032,
    // 2.2) but not the comparison; vmt's reading: WPn is 1 while the actual position lies at
    // or beyond waypoint n (for a rotary axis within the turn, 0 <= position < 360).
    const bool homed = spindle ? ch.spindle_homed() : ch.homed(a.channel_axis);
    for (int k = 0; k < 8; ++k) {
      if (a.wp[k] < 0) continue;
      const double w = p.waypoints[k];
      const bool passed = homed && !std::isnan(w) && position >= w;
      if (im.Bool(a.wp[k]) != passed) im.SetBool(a.wp[k], passed);
    }
  }
}

}  // namespace vmt::control::gateway
