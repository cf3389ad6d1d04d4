#pragma once
// A fast-measurement instruction in work (SETTING ... RESTORE): its block, call, plan and the
// step the channel has got to, the contact, and the reverse vectors it has reached.

#include <cstddef>
#include <optional>

#include "control/measure/measuring_cycle.hpp"
#include "control/measure/measuring_messages.hpp"
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

}  // namespace vmt::control::channel
