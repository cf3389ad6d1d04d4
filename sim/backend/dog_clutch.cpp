#include "sim/backend/dog_clutch.hpp"

#include <cmath>
#include <numbers>

namespace vmt::sim {

const char* ToString(ClutchState state) {
  switch (state) {
    case ClutchState::kReleased:
      return "released";
    case ClutchState::kEngaging:
      return "engaging";
    case ClutchState::kBlocked:
      return "blocked";
    case ClutchState::kEngaged:
      return "engaged";
    case ClutchState::kReleasing:
      return "releasing";
  }
  return "?";
}

double DogClutchLogic::PhaseError(const DogClutch& k, double q_motor, double q_load) {
  const double pitch = 2 * std::numbers::pi / k.teeth;
  const double relative = q_load - q_motor / k.ratio;
  return relative - pitch * std::round(relative / pitch);
}

double DogClutchLogic::MeshOffset(const DogClutch& k, double q_motor, double q_load) {
  const double pitch = 2 * std::numbers::pi / k.teeth;
  return pitch * std::round((q_load - q_motor / k.ratio) / pitch);
}

bool DogClutchLogic::Step(const DogClutch& k, bool valve_engage, bool valve_release,
                          double phase_error, double slip_rad_s, double dt_s) {
  const ClutchState before = state;
  // A valve pair that is both on or both off holds the dogs where they are.
  const bool engage = valve_engage && !valve_release;
  const bool release = valve_release && !valve_engage;
  const bool meshes = std::abs(phase_error) <= k.phase_tolerance_rad &&
                      std::abs(slip_rad_s) <= k.max_relative_speed_rad_s;
  switch (state) {
    case ClutchState::kReleased:
      if (engage) state = ClutchState::kEngaging, stroke_left_s = k.engage_time_s;
      break;
    case ClutchState::kEngaging:
      if (release) {
        state = ClutchState::kReleasing, stroke_left_s = k.release_time_s;
        break;
      }
      stroke_left_s -= dt_s;
      if (stroke_left_s <= 0) state = meshes ? ClutchState::kEngaged : ClutchState::kBlocked;
      break;
    case ClutchState::kBlocked:
      // The dogs stay pressed on each other; they drop in as soon as the teeth line up slowly
      // enough (that is what "hunting" the drive at low speed is for).
      if (release)
        state = ClutchState::kReleasing, stroke_left_s = k.release_time_s;
      else if (meshes)
        state = ClutchState::kEngaged;
      break;
    case ClutchState::kEngaged:
      if (release) state = ClutchState::kReleasing, stroke_left_s = k.release_time_s;
      break;
    case ClutchState::kReleasing:
      if (engage) {
        state = ClutchState::kEngaging, stroke_left_s = k.engage_time_s;
        break;
      }
      stroke_left_s -= dt_s;
      if (stroke_left_s <= 0) state = ClutchState::kReleased;
      break;
  }
  const bool ratchets =
      state == ClutchState::kBlocked && std::abs(slip_rad_s) > k.max_relative_speed_rad_s;
  if (ratchets && !ratcheting) {
    ++clashes;
    clash_slip_rad_s = slip_rad_s;
  }
  ratcheting = ratchets;
  return state != before;
}

}  // namespace vmt::sim
