#pragma once
// machine.yaml `probe:`: the measuring styluses of the machine as the fast-measurement manual's
// TASTWERKZEUGPAGE describes them (3.1: up to four, each a T number, NO/NC contact, the drive's
// probe input PIN4/PIN5 and up to five measuring sphere radii), plus what the simulation needs
// to make one switch: where the spheres are, the compliant mount and the I/O it drives.
// SI after loading (m).

#include <Eigen/Core>
#include <string>
#include <vector>

namespace vmt::sim {

class YamlNode;
struct MachineModel;

/// A measuring sphere (ruby ball): centre in the stylus' link frame and radius, m.
struct MeasuringSphere {
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();
  double radius_m = 0;
};

struct ProbeStylus {
  int t_number = 0;              ///< 00001 tool number: the tool list's T, its turret station
  bool normally_closed = false;  ///< 00002 NO (0) / NC (1)
  bool pin5 = false;             ///< 00003 PIN4 (0) / PIN5 (1): the drive's probe input E4/E5
  int link = -1;                 ///< the link carrying it
  std::vector<MeasuringSphere> spheres;  ///< 00004..00008: 1 to 5
  /// The link's <collision> parts that are the spheres: their touching a part the scene adds
  /// (the workpiece) is measuring, not a collision.
  std::vector<std::string> sphere_parts;
  /// The compliant mount: the deflection at which the switch trips (and below which it
  /// releases), and the deflection it gives before the stylus is damaged, m.
  double pre_travel_m = 0, over_travel_m = 0;
  int contact_input = -1;  ///< I/O index of the input the switch drives (IPROBE_CONTACT)
  /// I/O index of the probe's ready message (IPROBE_READY); the switch shows on its input only
  /// while it is on. -1: always ready (a cabled probe).
  int ready_input = -1;
};

/// Reads `probe:`; io, drives and `nc:` must be loaded. Throws ModelError (file, YAML path).
std::vector<ProbeStylus> ReadProbeStyluses(const MachineModel& m, const YamlNode& list);

}  // namespace vmt::sim
