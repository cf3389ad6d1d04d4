#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <span>

#include "render/camera.hpp"
#include "render/image.hpp"
#include "render/mesh.hpp"

namespace vmt::render {

/// One thing to draw: a mesh placed in the world with a uniform colour.
struct DrawItem {
  /// Not owned; must stay alive and unchanged while the renderer caches it (see Forget).
  const Mesh* mesh;
  /// Pose of the mesh frame in the world frame.
  Eigen::Isometry3d X_WorldMesh;
  Rgba colour;
};

/// Whether this process has made a GL context. Its renderer's threads then stand, and fork()
/// copies none of them: a forked copy that renders would wait for them forever.
bool RendererStarted();

/// Draws lit, coloured meshes into an offscreen picture with OSMesa (llvmpipe on the CPU). The
/// same scene gives the same bytes on every run and for any LP_NUM_THREADS.
///
/// Each renderer owns its own GL context; renderers may coexist or follow one another. A
/// renderer is not thread-safe: use it from one thread at a time.
class OffscreenRenderer {
 public:
  /// A renderer for width x height pictures. It draws at `supersample` times that size and
  /// box-filters down, which smooths edges (1 = no supersampling, at most 4).
  /// Throws std::runtime_error if the size is out of range or no GL context can be created.
  OffscreenRenderer(int width, int height, int supersample = 2);
  ~OffscreenRenderer();
  OffscreenRenderer(OffscreenRenderer&&) noexcept;
  OffscreenRenderer& operator=(OffscreenRenderer&&) noexcept;
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  /// Draws `items` seen from `camera` over `background`. Opaque items (colour.a == 1) are drawn
  /// first, translucent ones after, in the order given. A mesh is uploaded to the GL once and
  /// reused while its vector sizes and data pointers stay the same.
  /// Throws std::runtime_error for a null or malformed mesh, an invalid camera or a GL error.
  Image Draw(const Camera& camera, std::span<const DrawItem> items,
             Rgba background = {0.93f, 0.94f, 0.96f, 1});

  /// Drops the uploaded copy of `mesh`; call it before changing a mesh's contents in place or
  /// destroying it if another mesh could later take its address.
  void Forget(const Mesh* mesh);
  /// Drops all uploaded meshes.
  void ForgetAll();

  int Width() const { return width_; }
  int Height() const { return height_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_ = 0, height_ = 0;
};

}  // namespace vmt::render
