#pragma once
// Turning, as far as PathGuard and the pictures need it: while the spindle turns, a tool's
// cutting part (machine.yaml `cutting_parts:`) inside the workpiece cuts from the turned stock
// the ring it sweeps, per slice: a turning insert lowers the surface, a boring bar or drill at
// the axis bores, a grooving tool in the end face cuts a face groove. No cutting forces, chips
// or tool wear: the part's shape is what PathGuard needs so that a tool standing in its own cut
// is clear and an approach into the cut meets only what is left.

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "sim/collision/turned_stock.hpp"
#include "sim/model/machine_model.hpp"
#include "sim/model/revolved_part.hpp"

namespace vmt::sim {

/// Below this the spindle is positioning (C axis, M19), not turning: a cutting part in the
/// stock then is a collision for PathGuard to see, not a cut.
inline constexpr double kTurningSpeedRadS = 1.0;  // ~10 rpm
/// Slices of the turned stock along the spindle axis.
inline constexpr double kStockSliceM = 1e-4;
/// What a cut leaves standing below the edge, so that the tool in its cut is clear of it.
inline constexpr double kCutAllowanceM = 2e-5;

class StockCutter {
 public:
  /// Throws ModelError if the part's link is not the model's.
  StockCutter(const MachineModel& model, const RevolvedPart& part);

  /// The machine at joint positions `q` (SI) at time `t_s`: cuts if the spindle turned fast
  /// enough since the last call. True if the stock changed.
  bool Cut(const std::vector<double>& q, double t_s);

  const TurnedStock& stock() const { return stock_; }

  /// Where the tool in work cuts, world frame (m), at joint positions `q`: of the cutting
  /// parts, the corners nearest the spindle axis (their middle: an edge square to the tool's
  /// ray has its nearest point between its corners). The station facing the spindle holds its
  /// tool nearer the axis than every other station, so these are the tool in work's; none when
  /// something else of that link is nearer still (a probe, a drill or an empty holder faces the
  /// spindle). Reads only: cutting is Cut's.
  std::optional<Eigen::Vector3d> CuttingPoint(const std::vector<double>& q) const;

 private:
  struct Cutter {
    int link = -1;
    std::vector<Eigen::Vector3d> corners;  ///< the triangles' corners, link frame, m
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double radius = 0;  ///< bounding sphere of the corners, link frame
  };
  const MachineModel* model_;
  TurnedStock stock_;
  int link_ = -1, spindle_joint_ = -1;
  std::vector<Cutter> cutters_;
  /// Per link that holds a cutting part: the corners of its other collision parts (link frame).
  struct Holder {
    int link = -1;
    std::vector<Eigen::Vector3d> corners;
  };
  std::vector<Holder> holders_;
  double last_angle_ = 0, last_t_ = -1;
  /// The stock's largest outer radius, kept with the stock: a tick's cull needs it and the
  /// slices are thousands.
  double r_max_ = 0;
  std::vector<Eigen::Vector3d> corners_;  ///< a cutter's corners in the part's frame, reused
  /// The links Cut poses (the part's and the cutters' chains, LinkChains), and their poses,
  /// reused: the rest of the machine does not matter to a cut.
  std::vector<bool> posed_links_;
  std::vector<Eigen::Isometry3d> X_W_;
};

}  // namespace vmt::sim
