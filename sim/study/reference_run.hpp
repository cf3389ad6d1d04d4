#pragma once
// The reference run of a study: the scene's program once, uninterrupted, on the kinematic
// backend. Its trace gives the time span of every block of the main program (where per-mille
// interruption points lie), the program's end (where every-T-ms points stop) and the tool's
// XZ path (the contour as turned, the report's background).

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/scene/scene.hpp"

namespace vmt::sim::study {

/// A block of the main program as it ran: its source line and the time it was current.
struct BlockSpan {
  int line = 0;
  std::string label;  ///< the block's first word (N0030), else "L<line>"
  double start_s = 0, end_s = 0;
  bool motion = false;  ///< X or Z moved while it was current
};

/// A part that turns with the spindle (chuck body, jaw) as the envelope it sweeps, in the XZ
/// plane of the machine coordinates: X from 0 to x1, Z from z0 to z1, mm.
struct ChuckOutline {
  std::string name;
  double x1 = 0, z0 = 0, z1 = 0;
};

struct Reference {
  double start_s = 0;  ///< the program started (the NC ran)
  double end_s = 0;    ///< it ended
  std::vector<BlockSpan> blocks;
  std::vector<std::pair<double, double>> path;  ///< (X, Z) of the tool, mm, every 10 ms
  /// Where the tool's tip stands in the model frame (x radial, z the spindle axis, mm) less
  /// the axis positions X, Z: a point p of the model frame lies at the machine coordinates
  /// (|p radial| - tip_x, p.z - tip_z), where the tool tip touches it. Unknown without a
  /// turned workpiece (no cutting tool).
  bool has_tip = false;
  double tip_x = 0, tip_z = 0;
  /// The chuck's parts in machine coordinates (empty when the tip is unknown).
  std::vector<ChuckOutline> chuck;
};

/// Runs `scene`'s program alone (timeline: start, run to its end) and reads its trace in
/// `work_dir` (created; the trace stays there). Throws std::runtime_error if the program does
/// not end within the scene's duration without an error, ReferenceStopped if `stop` (asked at
/// every tick) says so first.
Reference RunReference(const Scene& scene, const std::string& work_dir,
                       const std::function<bool()>& stop = {});

/// The reference run was asked to stop (a study stopped by SIGINT / SIGTERM): there is none.
struct ReferenceStopped : std::runtime_error {
  ReferenceStopped() : std::runtime_error("the reference run was stopped") {}
};

/// The reference as JSON (the study folder's reference.json) and back.
std::string ReferenceJson(const Reference& r);
Reference ReferenceFromJson(const std::string& text);

}  // namespace vmt::sim::study
