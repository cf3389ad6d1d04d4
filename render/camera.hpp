#pragma once

#include <Eigen/Core>

namespace vmt::render {

/// A perspective camera in world coordinates (metres). The aspect ratio comes from the image.
struct Camera {
  /// Where the camera is.
  Eigen::Vector3d eye{0, 0, 1};
  /// The point it looks at; must differ from eye.
  Eigen::Vector3d target{0, 0, 0};
  /// Up direction; must not be parallel to target - eye.
  Eigen::Vector3d up{0, 1, 0};
  /// Vertical field of view, degrees, in (0, 180).
  double fov_y_deg = 40;
  /// Clip planes, metres, 0 < near_m < far_m.
  double near_m = 0.01, far_m = 10;
};

}  // namespace vmt::render
