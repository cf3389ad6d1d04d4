#include "sim/model/mesh_loader.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "common/input_file.hpp"

namespace vmt::sim {
namespace {

constexpr double kMaxMeshCoordinateM = 100;

}  // namespace

MeshCache& MeshCache::Shared() {
  static MeshCache cache;
  return cache;
}

std::shared_ptr<const render::Mesh> MeshCache::Load(const std::string& path,
                                                    const Eigen::Vector3d& scale) {
  // The file's size and time are part of the key: a file rewritten in the same process (a
  // test, an edited model) is read again.
  std::ostringstream key;
  key.precision(17);
  key << path << '|' << scale.x() << ',' << scale.y() << ',' << scale.z();
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) {
    const auto time = std::filesystem::last_write_time(path, ec);
    key << '|' << size << '|' << (ec ? 0 : time.time_since_epoch().count());
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  if (auto it = meshes_.find(key.str()); it != meshes_.end()) return it->second;

  // Assimp opens the file by name: a FIFO would block it, a directory gives a vague error.
  if (const std::string why = common::InputFileProblem(path); !why.empty())
    throw std::runtime_error("mesh " + path + ": cannot open file: " + why);
  Assimp::Importer importer;
  // Keep vertices as written: the meshes carry their own normals, and joining vertices would
  // smooth hard edges.
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_GenNormals | aiProcess_PreTransformVertices);
  if (!scene || !scene->mRootNode)
    throw std::runtime_error("mesh " + path + ": " + importer.GetErrorString());

  auto mesh = std::make_shared<render::Mesh>();
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* am = scene->mMeshes[m];
    const auto base = static_cast<uint32_t>(mesh->positions.size() / 3);
    for (unsigned v = 0; v < am->mNumVertices; ++v) {
      const aiVector3D& p = am->mVertices[v];
      // A machine part lies within metres of its link; a far or infinite vertex (1e200 in the
      // file) stalls the collision geometry's fitting ("eigen: too many iterations").
      for (const double c : {p.x * scale.x(), p.y * scale.y(), p.z * scale.z()})
        if (!(std::abs(c) <= kMaxMeshCoordinateM))
          throw std::runtime_error("mesh " + path +
                                   ": a vertex lies beyond +-100 m of its link or is not finite");
      mesh->positions.insert(mesh->positions.end(), {static_cast<float>(p.x * scale.x()),
                                                     static_cast<float>(p.y * scale.y()),
                                                     static_cast<float>(p.z * scale.z())});
      const aiVector3D n = am->HasNormals() ? am->mNormals[v] : aiVector3D(0, 0, 1);
      mesh->normals.insert(mesh->normals.end(), {n.x, n.y, n.z});
    }
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines carry no surface
      for (unsigned i = 0; i < 3; ++i) mesh->indices.push_back(base + face.mIndices[i]);
    }
  }
  if (mesh->indices.empty()) throw std::runtime_error("mesh " + path + ": no triangles");
  meshes_[key.str()] = mesh;
  return mesh;
}

}  // namespace vmt::sim
