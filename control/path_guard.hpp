#pragma once
// PathGuard (DESIGN.md): the machine geometry's answer to "may the axes move in a straight line
// from here to there without touching anything?". The control kernel asks it before approach
// moves start (jogging ahead, G77, the REPOS subroutine's moves, return to the contour, probe
// approach), before a turret indexes (a move of its drive alone) and before a spindle starts;
// the simulation answers from the model's collision geometry at the current poses.
// Like DriveBus it speaks machine units: positions per drive, mm | deg.

#include <string>
#include <vector>

namespace vmt::control {

struct PathCheck {
  bool clear = true;
  // The first contact on the way (clear == false):
  std::string part_a, part_b;    ///< the two parts that touch
  double point[3] = {0, 0, 0};   ///< where, machine frame, mm
  double distance = 0;           ///< along the path to it, mm (the linear drives' path)
  std::vector<double> position;  ///< every drive's position there
  // The smallest clearance on the way (up to the contact, 0 there), and between which parts.
  double min_clearance = 0;  ///< mm
  std::string closest_a, closest_b;
};

/// What a contact found ahead of a move does (the NC's PathGuard parameter): stop the move
/// before it happens with an NC error, only record it, or no checks at all.
enum class GuardReaction { kStop, kWarn, kOff };
inline const char* ToString(GuardReaction r) {
  return r == GuardReaction::kStop ? "stop" : r == GuardReaction::kWarn ? "warn" : "off";
}

class PathGuard {
 public:
  virtual ~PathGuard() = default;
  /// A straight move of every drive from `from` to `to` (one position per drive, as DriveBus
  /// numbers them).
  virtual PathCheck CheckMove(const std::vector<double>& from, const std::vector<double>& to) = 0;
  /// A probe's measuring path: as CheckMove, but its measuring sphere touching the workpiece
  /// is the measurement. On every other move (jog, approach, escape) that touch is a collision.
  virtual PathCheck CheckMeasuringPath(const std::vector<double>& from,
                                       const std::vector<double>& to) {
    return CheckMove(from, to);
  }
  /// A straight move that an earlier check may answer for without a new query (a jog checked
  /// ahead again a little further on): true and `check` (clear, the clearance still proven) if
  /// it does; false if the move needs its own CheckMove.
  virtual bool Proves(const std::vector<double>& /*from*/, const std::vector<double>& /*to*/,
                      PathCheck& /*check*/) {
    return false;
  }
  /// Spindle drive `spindle` starting to turn with every drive standing at `at`: whatever turns
  /// with it (chuck, jaws, workpiece) checked as the solid it sweeps against everything else,
  /// where that stands. A guard that knows no sweep of that spindle has nothing to check.
  virtual PathCheck CheckSpindleStart(const std::vector<double>& /*at*/, int /*spindle*/) {
    return {};
  }
};

}  // namespace vmt::control
