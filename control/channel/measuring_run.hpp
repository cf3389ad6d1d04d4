#pragma once
// A fast-measurement instruction in work (SETTING ... RESTORE): its block, call, plan and the
// step the channel has got to, the contact, and the reverse vectors it has reached.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "control/measure/measuring_cycle.hpp"
#include "control/measure/measuring_messages.hpp"
#include "control/measure/measuring_pages.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

struct MeasuringRun {
  nc::PreparedBlock block;  ///< the instruction's block (block_ holds the generated moves)
  measure::InstructionCall call;
  measure::MeasuringContext context;
  measure::MeasuringPlan plan;
  size_t step = 0;
  bool moving = false;            ///< the move of step `step - 1` is in work
  bool measuring_move = false;    ///< ... and it is the measuring path
  std::optional<double> contact;  ///< the sphere centre when the probe switched
  bool reversal = false;          ///< the reverse vectors, before `.HOME` runs
  /// The recorded reverse vectors this instruction's stylus has reached: the plan records its
  /// way in before it moves (measure::ReverseVectors), the reversal may only retrace it.
  size_t reached = 0;
  const measure::MeasuringMessage* message = nullptr;  ///< issued when the steps are done
};

/// The channel's fast measurement (fast-measurement manual): the instruction in work, the
/// setting of SETTING( ), the stylus' way back, the machine data pages.
struct MeasuringData {
  std::optional<MeasuringRun> run;
  std::optional<measure::MeasuringSetting> setting;
  measure::ReverseVectors reverse_vectors;
  measure::MeasuringPages* pages = nullptr;  ///< null: MTD is an error
  std::vector<std::string> warnings;
  /// Bit n: SETTING axis n+1's drive has shown the probe free since event 29 was set.
  uint8_t probe_free_seen = 0;
};

}  // namespace vmt::control::channel
