#pragma once
// The NC status block: what a PLC or an HMI shows of the NC beside the PLC signals - each axis'
// actual position, velocity and following error, the mode, the program state, the source line
// in work and the active messages - as a block of input registers (Modbus function 04) behind
// the signal table's own. vmt serve fills it after every cycle; `vmt signals` lists every
// register of it. Read only; it changes nothing the NC does.
//
// Encoding: 16-bit registers; a 32-bit value takes two, most significant word first (as the
// table's DINTs). Positions and following errors in 0.0001 mm (linear axes) or 0.0001 deg
// (rotary axes and spindles), velocities in 0.001 mm/s or 0.001 deg/s, all DINT. A rotary
// axis' position is shown within the turn, 0 <= p < 360 deg (a spindle's count of turns would
// leave the DINT range within seconds); values beyond the DINT range stop at its limits.
//
// Layout from the block's first register B (NcStatusLayout::address):
//   B+0 layout version (1)   B+1 axis rows N   B+2 process number   B+3 message slots (8)
//   B+4..5 simulated time, ms (UDINT)   B+6 mode   B+7 program state   B+8..9 source line
//   B+10 active messages (all of them, also those beyond the slots)
//   B+12+2k, B+13+2k: slot k (0..7): message number, its source (0 empty, 1 NC, 2 PLC)
//   B+32+8i..: axis row i (the table's axes Axx in table order): +0..1 position, +2..3
//   velocity, +4..5 following error, +6 axis number, +7 flags (NcStatusFlag)
// Registers not named here (B+11, B+28..31) read 0.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "control/channel/channel_types.hpp"
#include "control/channel/operator_messages.hpp"
#include "control/drive_bus.hpp"
#include "control/gateway/signal_table.hpp"

namespace vmt::control::channel {
class Channel;
}

namespace vmt::control::gateway {

inline constexpr int kNcStatusVersion = 1;
inline constexpr int kNcStatusHeader = 32;  ///< registers before the first axis row
inline constexpr int kNcStatusAxisRow = 8;  ///< registers per axis row
inline constexpr int kNcStatusMessageSlots = 8;

/// Bits of an axis row's flags register.
enum NcStatusFlag : uint16_t {
  kNcStatusRotary = 1 << 0,      ///< units are deg, deg/s (else mm, mm/s)
  kNcStatusFed = 1 << 1,         ///< a drive answers for the axis (else the values are 0)
  kNcStatusInPosition = 1 << 2,  ///< the drive is within its in-position window
  kNcStatusStandstill = 1 << 3,  ///< the drive stands still
};

/// Codes of the mode register (channel::ChannelMode) and the program state register
/// (channel::ChannelState: 2 is a held program, feed hold or interrupted).
uint16_t NcStatusCode(channel::ChannelMode mode);
uint16_t NcStatusCode(channel::ChannelState state);

/// One axis row: an axis of the signal table.
struct NcStatusAxis {
  int number = 0;    ///< Axx
  std::string name;  ///< its designation: X, Z, C, S1
  bool rotary = false;
  bool spindle = false;  ///< spindle-capable: the main spindle's drive answers for it
};

/// One register or register pair of the block, for the register map (`vmt signals`).
struct NcStatusField {
  std::string name;  ///< "NC.MODE", "A01.NC_POS"
  SignalType type;
  int address;  ///< first input register, 0-based
  int count;    ///< registers
  std::string meaning;
  std::string unit;  ///< empty for codes and counts
};

struct NcStatusLayout {
  int address = 0;  ///< B, the first input register
  int process = 0;
  std::vector<NcStatusAxis> axes;
  int count() const { return kNcStatusHeader + kNcStatusAxisRow * static_cast<int>(axes.size()); }
  std::vector<NcStatusField> Fields() const;
};

/// The block of a machine's table: its axes (every Axx of the table, in table order; rotary
/// are those with the spindle's or the changeover's signals), its first process, and B: input
/// register 1000, or the first multiple of 1000 past the table's input registers where they
/// reach it. Throws std::invalid_argument if the block would pass register 65535.
NcStatusLayout NcStatusLayoutOf(const std::vector<Signal>& table);

/// What the block shows, in machine units (mm | deg, s).
struct NcStatus {
  double time_s = 0;
  channel::ChannelMode mode = channel::ChannelMode::kAutomatic;
  channel::ChannelState state = channel::ChannelState::kIdle;
  uint32_t line = 0;
  std::vector<channel::OperatorMessage> messages;
  struct Axis {
    bool fed = false;
    double position = 0, velocity = 0, following_error = 0;
    uint32_t drive_status = 0;
  };
  std::vector<Axis> axes;  ///< one per layout axis
};

/// The channel and its drives' feedback as the block shows them: an axis row takes the drive
/// of the channel axis with its number, else (a spindle-capable axis) the main spindle's.
NcStatus NcStatusOf(const NcStatusLayout& layout, const channel::Channel& channel,
                    const AmplifierTelegram& feedback, double time_s);

/// Encodes `status` into `words` (layout.count() registers).
void EncodeNcStatus(const NcStatusLayout& layout, const NcStatus& status,
                    std::span<uint16_t> words);

}  // namespace vmt::control::gateway
