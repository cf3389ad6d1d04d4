#pragma once
#include <Eigen/Core>
#include <map>
#include <memory>
#include <string>

#include "render/mesh.hpp"

namespace vmt::sim {

/// Loads meshes through assimp (OBJ, STL, ...), each file once per scale.
class MeshCache {
 public:
  /// Throws std::runtime_error with the file name when the file is missing or has no triangles.
  std::shared_ptr<const render::Mesh> Load(const std::string& path, const Eigen::Vector3d& scale);

 private:
  std::map<std::string, std::shared_ptr<const render::Mesh>> meshes_;
};

}  // namespace vmt::sim
