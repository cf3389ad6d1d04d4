#pragma once
// A named viewpoint on the machine (machine YAML `cameras:`, scene `cameras:`).

#include <Eigen/Core>
#include <string>

namespace vmt::sim {

class YamlNode;

struct NamedCamera {
  std::string name;
  Eigen::Vector3d eye_m, target_m, up{0, 1, 0};
  double fov_y_deg = 40;
};

/// Reads `{eye: [x, y, z], target: [...], up: [...], fov: deg}` (mm, degrees); throws ModelError
/// naming the YAML path on a bad entry.
NamedCamera ReadCamera(const std::string& name, const YamlNode& node);

}  // namespace vmt::sim
