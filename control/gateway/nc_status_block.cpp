#include "control/gateway/nc_status_block.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/demand.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::gateway {
namespace {

constexpr int kFirstAddress = 1000;  // and the step past a table that reaches it
constexpr int kMessageOffset = 12;
// Offsets in an axis row.
constexpr int kPosition = 0, kVelocity = 2, kFollowingError = 4, kNumber = 6, kFlags = 7;

void Put32(std::span<uint16_t> words, int at, uint32_t v) {
  words[at] = static_cast<uint16_t>(v >> 16);
  words[at + 1] = static_cast<uint16_t>(v & 0xffff);
}

// `value` in units of `step`, rounded, held within the DINT range.
int32_t Count(double value, double step) {
  const double n = std::round(value / step);
  if (!(n > std::numeric_limits<int32_t>::min())) return std::numeric_limits<int32_t>::min();
  if (n >= std::numeric_limits<int32_t>::max()) return std::numeric_limits<int32_t>::max();
  return static_cast<int32_t>(n);
}

}  // namespace

uint16_t NcStatusCode(channel::ChannelMode mode) {
  switch (mode) {
    case channel::ChannelMode::kAutomatic:
      return 0;
    case channel::ChannelMode::kManual:
      return 1;
    case channel::ChannelMode::kMdi:
      return 2;
  }
  return 0xffff;
}

uint16_t NcStatusCode(channel::ChannelState state) {
  switch (state) {
    case channel::ChannelState::kIdle:
      return 0;
    case channel::ChannelState::kRunning:
      return 1;
    case channel::ChannelState::kHold:
      return 2;
    case channel::ChannelState::kEnded:
      return 3;
    case channel::ChannelState::kError:
      return 4;
  }
  return 0xffff;
}

std::vector<NcStatusField> NcStatusLayout::Fields() const {
  const int b = address;
  std::vector<NcStatusField> f = {
      {"NC.VERSION", SignalType::kUint, b + 0, 1, "layout version of the NC status block (1)", ""},
      {"NC.AXES", SignalType::kUint, b + 1, 1, "number of axis rows (8 registers each, from +32)",
       ""},
      {"NC.PROCESS", SignalType::kUint, b + 2, 1, "process (channel) the block shows", ""},
      {"NC.MSG_SLOTS", SignalType::kUint, b + 3, 1, "number of message slots (8)", ""},
      {"NC.TIME_MS", SignalType::kUdint, b + 4, 2,
       "simulated time of the last refresh (after every PLC cycle)", "ms"},
      {"NC.MODE", SignalType::kUint, b + 6, 1, "operating mode: 0 automatic, 1 manual, 2 MDI", ""},
      {"NC.STATE", SignalType::kUint, b + 7, 1,
       "program state: 0 idle, 1 running, 2 held (feed hold, interrupted), 3 ended, 4 error", ""},
      {"NC.LINE", SignalType::kUdint, b + 8, 2,
       "source line of the block in work in its program, 0 when none", ""},
      {"NC.MSG_COUNT", SignalType::kUint, b + 10, 1,
       "active messages (error in force, PLC message), also those beyond the slots", ""},
  };
  for (int k = 0; k < kNcStatusMessageSlots; ++k) {
    const std::string slot = "NC.MSG" + std::to_string(k + 1);
    const int at = b + kMessageOffset + 2 * k;
    f.push_back({slot, SignalType::kUint, at, 1,
                 "number of active message " + std::to_string(k + 1) + ", 0: slot empty", ""});
    f.push_back({slot + "_SOURCE", SignalType::kUint, at + 1, 1,
                 "source of active message " + std::to_string(k + 1) + ": 0 empty, 1 NC, 2 PLC",
                 ""});
  }
  for (size_t i = 0; i < axes.size(); ++i) {
    const NcStatusAxis& a = axes[i];
    const std::string prefix = InstanceName("Axx", a.number) + ".NC_";
    const std::string who = "axis " + a.name + ": ";
    const int row = b + kNcStatusHeader + kNcStatusAxisRow * static_cast<int>(i);
    const char* position = a.rotary ? "0.0001 deg" : "0.0001 mm";
    f.push_back({prefix + "POS", SignalType::kDint, row + kPosition, 2,
                 who + (a.rotary ? "actual position, machine coordinates, within the turn 0..360"
                                 : "actual position, machine coordinates"),
                 position});
    f.push_back({prefix + "VEL", SignalType::kDint, row + kVelocity, 2, who + "actual velocity",
                 a.rotary ? "0.001 deg/s" : "0.001 mm/s"});
    f.push_back({prefix + "FE", SignalType::kDint, row + kFollowingError, 2,
                 who + "following error (command - actual)", position});
    f.push_back({prefix + "AXIS", SignalType::kUint, row + kNumber, 1, who + "axis number", ""});
    f.push_back({prefix + "FLAGS", SignalType::kWord, row + kFlags, 1,
                 who + "bit 0 rotary (deg), 1 a drive answers, 2 in position, 3 standstill", ""});
  }
  return f;
}

NcStatusLayout NcStatusLayoutOf(const std::vector<Signal>& table) {
  NcStatusLayout layout;
  int end = 0;
  bool process_found = false;
  for (const Signal& s : table) {
    if (s.modbus.area == ModbusAddress::kInputRegister)
      end = std::max(end, s.modbus.address + s.modbus.count);
    if (s.scope == Scope::kProcess && !process_found) {
      layout.process = s.instance;
      process_found = true;
    }
    if (s.scope != Scope::kAxis && s.scope != Scope::kSpindle && s.scope != Scope::kChangeover)
      continue;
    auto it = std::find_if(layout.axes.begin(), layout.axes.end(),
                           [&](const NcStatusAxis& a) { return a.number == s.instance; });
    if (it == layout.axes.end()) {
      layout.axes.push_back({s.instance, s.instance_name, false, false});
      it = layout.axes.end() - 1;
    }
    if (s.scope != Scope::kAxis) it->rotary = true;
    if (s.scope == Scope::kSpindle) it->spindle = true;
  }
  layout.address =
      std::max(kFirstAddress, (end + kFirstAddress - 1) / kFirstAddress * kFirstAddress);
  if (layout.address + layout.count() > 65536) {
    throw std::invalid_argument(
        "NC status block: input registers " + std::to_string(layout.address) + ".." +
        std::to_string(layout.address + layout.count() - 1) +
        " pass 65535 (the signal table ends at " + std::to_string(end) + ")");
  }
  return layout;
}

NcStatus NcStatusOf(const NcStatusLayout& layout, const channel::Channel& channel,
                    const AmplifierTelegram& feedback, double time_s) {
  NcStatus s;
  s.time_s = time_s;
  s.mode = channel.mode();
  s.state = channel.state();
  s.line = channel.line();
  s.messages = channel.messages();
  const channel::ChannelConfig& config = channel.config();
  for (const NcStatusAxis& a : layout.axes) {
    int drive = -1;
    for (const channel::ChannelAxis& ca : config.axes)
      if (ca.number == a.number) drive = ca.drive;
    if (drive < 0 && a.spindle) drive = config.spindle_drive;
    NcStatus::Axis row;
    if (drive >= 0 && static_cast<size_t>(drive) < feedback.feedback.size()) {
      const DriveFeedback& f = feedback.feedback[drive];
      row = {true, f.position, f.velocity, f.following_error, f.status};
    }
    s.axes.push_back(row);
  }
  return s;
}

void EncodeNcStatus(const NcStatusLayout& layout, const NcStatus& status,
                    std::span<uint16_t> words) {
  VMT_DEMAND(
      static_cast<int>(words.size()) == layout.count() && status.axes.size() == layout.axes.size(),
      "EncodeNcStatus: the words or the axes do not fit the layout");
  std::fill(words.begin(), words.end(), uint16_t{0});
  words[0] = kNcStatusVersion;
  words[1] = static_cast<uint16_t>(layout.axes.size());
  words[2] = static_cast<uint16_t>(layout.process);
  words[3] = kNcStatusMessageSlots;
  // Milliseconds modulo 2^32, as a PLC's TIME counts.
  Put32(words, 4,
        static_cast<uint32_t>(static_cast<uint64_t>(std::llround(status.time_s * 1000)) &
                              0xffffffffu));
  words[6] = NcStatusCode(status.mode);
  words[7] = NcStatusCode(status.state);
  Put32(words, 8, status.line);
  words[10] = static_cast<uint16_t>(std::min<size_t>(status.messages.size(), 0xffff));
  for (size_t k = 0; k < status.messages.size() && k < kNcStatusMessageSlots; ++k) {
    const channel::OperatorMessage& m = status.messages[k];
    words[kMessageOffset + 2 * k] = static_cast<uint16_t>(std::clamp(m.number, 0, 0xffff));
    words[kMessageOffset + 2 * k + 1] = m.source == channel::OperatorMessage::Source::kNc ? 1 : 2;
  }
  for (size_t i = 0; i < layout.axes.size(); ++i) {
    const NcStatusAxis& a = layout.axes[i];
    const NcStatus::Axis& v = status.axes[i];
    const int row = kNcStatusHeader + kNcStatusAxisRow * static_cast<int>(i);
    double position = v.position;
    if (a.rotary) {
      position = std::fmod(position, 360.0);
      if (position < 0) position += 360.0;
    }
    int32_t counts = Count(position, 1e-4);
    if (a.rotary && counts >= 3600000) counts = 0;  // rounded up to a full turn
    Put32(words, row + kPosition, static_cast<uint32_t>(counts));
    Put32(words, row + kVelocity, static_cast<uint32_t>(Count(v.velocity, 1e-3)));
    Put32(words, row + kFollowingError, static_cast<uint32_t>(Count(v.following_error, 1e-4)));
    words[row + kNumber] = static_cast<uint16_t>(a.number);
    uint16_t flags = a.rotary ? kNcStatusRotary : 0;
    if (v.fed) {
      flags |= kNcStatusFed;
      if (v.drive_status & drive_status::kInPosition) flags |= kNcStatusInPosition;
      if (v.drive_status & drive_status::kStandstill) flags |= kNcStatusStandstill;
    }
    words[row + kFlags] = flags;
  }
}

}  // namespace vmt::control::gateway
