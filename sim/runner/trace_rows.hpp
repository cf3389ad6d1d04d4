#pragma once
// The trace's rows (trace.csv, and the digest that pins a scene's behaviour): per drive its
// command, position and velocity (rpm for spindles and rotary axes, the parameter set where it
// has several), each clutch's state, and the NC's state and line. Fixed formatting, so that
// the bytes, and so the digest, depend only on the simulation.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "control/channel/channel.hpp"
#include "control/drive_bus.hpp"
#include "sim/backend/dog_clutch.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::sim {

/// The header row; `nc`: the run has an NC channel.
std::string TraceHeader(const MachineModel& m, bool nc);
/// The row at time `t`; `channel` null without one.
std::string TraceRow(double t, const MachineModel& m, const control::AmplifierTelegram& at,
                     const control::MasterTelegram& mdt, const std::vector<ClutchState>& clutches,
                     const control::channel::Channel* channel);

/// A run's rows, each as TraceRow writes it. Most of a row stands still from one row to the
/// next (the axes at rest, the spindle off, the clutch, the NC's state): a field whose value
/// has the bits it had in the row before is copied as written then, not formatted again.
class TraceRowWriter {
 public:
  /// The row, valid until the next: written into a buffer the writer keeps.
  std::string_view Row(double t, const MachineModel& m, const control::AmplifierTelegram& at,
                       const control::MasterTelegram& mdt, const std::vector<ClutchState>& clutches,
                       const control::channel::Channel* channel);

  /// One field as last written: its value's bits and its text (at most 31 characters).
  struct Field {
    uint64_t bits = 0;
    uint8_t size = 0;  ///< 0: not written yet
    char text[32] = {};
  };

 private:
  std::vector<Field> last_;
  std::string buffer_;
};

}  // namespace vmt::sim
