#pragma once
// The dog clutch K between the C servo's gear and the spindle (C-axis manual 4.4). Shared by both
// backends: the stroke, the meshing condition and the end-position switches. The physics backend
// adds the rigid coupling when it meshes; the kinematic one ties the positions.

#include "sim/model/machine_model.hpp"

namespace vmt::sim {

enum class ClutchState {
  kReleased,   ///< open, ISPMODE (released switch) on
  kEngaging,   ///< valve QROTMODE on, dogs travelling
  kBlocked,    ///< dogs pressed tooth on tooth, or ratcheting: speed or phase wrong
  kEngaged,    ///< meshed, IROTMODE on: the motor drives the load through the gear
  kReleasing,  ///< valve QSPMODE on, dogs travelling back
};

const char* ToString(ClutchState state);

struct DogClutchLogic {
  ClutchState state = ClutchState::kReleased;
  double stroke_left_s = 0;
  /// Clashes so far: the dogs pushed in (blocked) while the halves turned against each other
  /// faster than max_relative_speed, so they ratchet over each other's teeth instead of meshing.
  /// One clash per spell of ratcheting.
  int clashes = 0;
  bool ratcheting = false;
  double clash_slip_rad_s = 0;  ///< load-side relative speed when the last clash began

  /// Relative tooth phase error (load side) in (-pitch/2, pitch/2] of load angle vs motor angle.
  static double PhaseError(const DogClutch& k, double q_motor, double q_load);
  /// Mesh offset so that q_load = q_motor / ratio + offset holds with whole teeth.
  static double MeshOffset(const DogClutch& k, double q_motor, double q_load);

  /// One tick. slip = load-side relative speed (rad/s). Returns true when the state changed.
  bool Step(const DogClutch& k, bool valve_engage, bool valve_release, double phase_error,
            double slip_rad_s, double dt_s);
  bool EngagedSwitch() const { return state == ClutchState::kEngaged; }
  bool ReleasedSwitch() const { return state == ClutchState::kReleased; }
};

}  // namespace vmt::sim
