#include "sim/model/named_camera.hpp"

#include "sim/model/machine_model.hpp"
#include "sim/model/yaml_reader.hpp"

namespace vmt::sim {

NamedCamera ReadCamera(const std::string& name, const YamlNode& c) {
  c.AllowKeys({"eye", "target", "up", "fov"});
  NamedCamera cam;
  cam.name = name;
  const auto eye = c["eye"].Doubles(3), target = c["target"].Doubles(3);
  cam.eye_m = Eigen::Vector3d(eye[0], eye[1], eye[2]) / kMmPerM;
  cam.target_m = Eigen::Vector3d(target[0], target[1], target[2]) / kMmPerM;
  if (c.Has("up")) {
    const auto up = c["up"].Doubles(3);
    cam.up = Eigen::Vector3d(up[0], up[1], up[2]);
    if (cam.up.norm() < 1e-9) c["up"].Fail("must not be zero");
  }
  cam.fov_y_deg = c.Double("fov", 40);
  if (cam.fov_y_deg <= 1 || cam.fov_y_deg >= 170)
    c["fov"].Fail("must be between 1 and 170 degrees");
  if ((cam.eye_m - cam.target_m).norm() < 1e-9) c.Fail("eye and target coincide");
  if ((cam.target_m - cam.eye_m).normalized().cross(cam.up.normalized()).norm() < 1e-6)
    c.Fail("up is parallel to the viewing direction");
  return cam;
}

}  // namespace vmt::sim
