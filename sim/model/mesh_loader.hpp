#pragma once
#include <Eigen/Core>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "render/mesh.hpp"

namespace vmt::sim {

/// Loads meshes through assimp (PLY, OBJ, STL, ...), each file once per scale and file version.
class MeshCache {
 public:
  /// Throws std::runtime_error with the file name when the file is missing or has no triangles.
  std::shared_ptr<const render::Mesh> Load(const std::string& path, const Eigen::Vector3d& scale);

  /// The process' cache: a model loaded again (scene tests, studies) reuses its meshes.
  /// assimp's OBJ reader fills a fixed stream buffer of megabytes per file, whatever its size,
  /// so an OBJ is page faults more than parsing (the shipped models are PLY, read at their
  /// size); a mesh is immutable once loaded. Thread-safe.
  static MeshCache& Shared();

 private:
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<const render::Mesh>> meshes_;
};

}  // namespace vmt::sim
