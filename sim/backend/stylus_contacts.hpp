#pragma once
// The machine's measuring styluses (machine.yaml `probe:`) against the scene's workpiece, stepped
// inside a backend's Step: after the links moved and before the drives sample their probe
// inputs, so that ProbeWiring knows the exact instant of a contact within the tick being stepped
// (it interpolates the drives' positions between the tick's start and end). Stepping it after
// Step and setting the switch for the next tick would latch one tick's travel late.
//
// Shared by both backends: they hand over the joint positions before and after the tick's
// motion; the stylus' link and the part's link are posed from them (LinkPoses).

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "sim/backend/probe_wiring.hpp"
#include "sim/backend/stylus.hpp"
#include "sim/model/machine_model.hpp"
#include "sim/model/revolved_part.hpp"

namespace vmt::sim {

/// A stylus deflected beyond its over-travel: the stylus crashed into the part (once per stylus
/// and run, StylusState::damaged).
struct StylusOverTravel {
  double t_s = 0;           ///< the instant within the tick where it passed the over-travel
  int t_number = 0;         ///< the stylus' T (TASTWERKZEUGPAGE 00001)
  int sphere = -1;          ///< the measuring sphere pushed deepest (0-based)
  std::string sphere_part;  ///< its <collision> part (probe: sphere_parts), "" if none named
  std::string part;         ///< the workpiece's name
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();  ///< nearest point on the part, world
};

class StylusContacts {
 public:
  explicit StylusContacts(const MachineModel& model);

  /// The workpiece the styluses touch (the scene's `workpiece:`); replaces any before. Throws
  /// std::invalid_argument when the model has no link of the part's name.
  void SetPart(const RevolvedPart& part);

  /// The model has styluses and a part is set: without, Step has nothing to do.
  bool any() const { return any_; }

  /// One tick: each stylus between its pose at `q_before` and at `q_now` (joint positions, SI,
  /// before and after the tick's motion) against the part as it stands at `q_now`. A change of
  /// a contact goes to `wiring` with its tick fraction; `inputs`: the machine's inputs as last
  /// read (the ready message); `t_s`: the time at the tick's start.
  void Step(const std::vector<double>& q_before, const std::vector<double>& q_now,
            const std::vector<uint8_t>& inputs, double t_s, ProbeWiring& wiring);

  /// The over-travels since the last call, in order.
  std::vector<StylusOverTravel> TakeOverTravels();

 private:
  /// The tick from `q_before` to `q_now` is a quiet one for every stylus, shown by the joints'
  /// motion since the last posed tick alone.
  bool StaysFar(const std::vector<double>& q_before, const std::vector<double>& q_now) const;

  const MachineModel* model_;
  RevolvedPart part_;
  int part_link_ = -1;
  bool any_ = false;
  std::vector<StylusState> states_;  ///< per stylus of the model
  std::vector<StylusOverTravel> over_travels_;
  std::vector<bool> needed_;  ///< the links posed (LinkChains of the styluses' and the part's)
  /// Per joint: how far one unit of its motion can move a sphere centre relative to the part
  /// (1 for a slide, a sphere's distance from the axis for a turn, 0 for the part turning about
  /// its own axis), m per m or rad; infinite where no bound is known.
  std::vector<double> reach_;
  /// Where the last posed tick ended, and how much nearer the spheres could come from there
  /// with every tick still a quiet one (FarRoom; <= 0: each tick is posed).
  std::vector<double> q_far_;
  double far_room_ = 0;
  /// The last step's joint positions and link poses: the next step's "before", as a rule.
  std::vector<double> q_last_;
  std::vector<Eigen::Isometry3d> X_last_, X_now_;
};

}  // namespace vmt::sim
