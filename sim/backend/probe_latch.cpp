#include "sim/backend/probe_latch.hpp"

namespace vmt::sim {
namespace {

namespace pc = control::probe_control;

// S-0-0169 bits of probe n (0: probe 1, 1: probe 2), SERCOS IDN 169 layout.
constexpr std::array<uint16_t, 2> kPositiveBit = {pc::kProbe1Positive, pc::kProbe2Positive};
constexpr std::array<uint16_t, 2> kNegativeBit = {pc::kProbe1Negative, pc::kProbe2Negative};

void Latch(control::ProbeEdgeLatch& latch, double actual_position, double exact_position) {
  latch.latched = true;
  latch.measured_value = actual_position;
  latch.exact_position = exact_position;
}

}  // namespace

bool ProbeLatch::Step(const control::ProbeControl& control,
                      const std::array<ProbeInputSample, 2>& pins, double actual_position) {
  const bool active = control.probe_cycle_command == pc::kProbeCycleActive;
  const std::array<bool, 2> enables = {control.probe1_enable, control.probe2_enable};
  if (!active && off_) {
    // Still off: what the rules below would do, minus the clearing already done -- the samples
    // and enables are remembered for the edges and the arming after the function comes on.
    for (size_t n = 0; n < 2; ++n) {
      inputs_[n].level_before = pins[n].level;
      inputs_[n].enable_before = enables[n];
    }
    return false;
  }
  off_ = !active;
  std::array<control::ProbeInputStatus*, 2> shown = {&status_.probe1, &status_.probe2};

  for (size_t n = 0; n < 2; ++n) {
    Input& in = inputs_[n];
    control::ProbeInputStatus& out = *shown[n];
    const bool level = pins[n].level;
    const bool rising = level && !in.level_before;
    const bool falling = !level && in.level_before;
    const bool enable = active && enables[n];
    // An inactive function or a cleared enable clears its input; 0-1 of the enable arms it.
    if (!enable) {
      in.armed = false;
      out.positive = {};
      out.negative = {};
    } else if (!in.enable_before) {
      in.armed = true;
    }
    if (in.armed) {
      if (rising && (control.probe_control_parameter & kPositiveBit[n]) && !out.positive.latched)
        Latch(out.positive, pins[n].acquired_position.value_or(actual_position),
              pins[n].exact_position);
      if (falling && (control.probe_control_parameter & kNegativeBit[n]) && !out.negative.latched)
        Latch(out.negative, pins[n].acquired_position.value_or(actual_position),
              pins[n].exact_position);
    }
    out.level = active && level;
    in.level_before = level;
    // The enable as the master sent it, active or not: one set before S-0-0170 = 3 made no
    // transition the function saw, so it arms only after 0 and back to 1.
    in.enable_before = enables[n];
  }
  return true;
}

}  // namespace vmt::sim
