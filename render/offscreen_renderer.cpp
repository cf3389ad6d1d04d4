#include "render/offscreen_renderer.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <atomic>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace vmt::render {
namespace {

// A mesh as uploaded. The data pointers and sizes tell whether the Mesh behind the cached
// address was reallocated since; changes in place need Forget().
struct GpuMesh {
  GLuint vertex_buffer = 0, index_buffer = 0;
  GLsizei index_count = 0;
  size_t normals_offset = 0;  // bytes into vertex_buffer; 0 when the mesh has no normals
  const float* positions = nullptr;
  const float* normals = nullptr;
  const uint32_t* indices = nullptr;
  size_t positions_size = 0, normals_size = 0, indices_size = 0;

  bool Matches(const Mesh& mesh) const {
    return positions == mesh.positions.data() && normals == mesh.normals.data() &&
           indices == mesh.indices.data() && positions_size == mesh.positions.size() &&
           normals_size == mesh.normals.size() && indices_size == mesh.indices.size();
  }
};

void ValidateMesh(const Mesh& mesh) {
  const size_t vertices = mesh.positions.size() / 3;
  const char* problem = nullptr;
  if (mesh.positions.size() % 3 != 0) {
    problem = "positions.size() is not a multiple of 3";
  } else if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) {
    problem = "normals.size() differs from positions.size()";
  } else if (mesh.indices.size() % 3 != 0) {
    problem = "indices.size() is not a multiple of 3";
  } else if (mesh.indices.size() > size_t(INT_MAX) || vertices > size_t(UINT32_MAX)) {
    problem = "too many vertices or indices";
  } else {
    for (const uint32_t index : mesh.indices) {
      if (index >= vertices) {
        problem = "an index is out of range";
        break;
      }
    }
  }
  if (problem) {
    throw std::runtime_error(std::string("OffscreenRenderer: malformed mesh (") +
                             std::to_string(vertices) + " vertices, " +
                             std::to_string(mesh.indices.size()) + " indices): " + problem);
  }
}

void CheckGl(const char* what) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR) {
    char message[96];
    std::snprintf(message, sizeof message, "OffscreenRenderer: GL error 0x%04X in %s", error, what);
    throw std::runtime_error(message);
  }
}

// Column-major 4x4 for glLoadMatrixd.
Eigen::Matrix4d LookAt(const Camera& camera) {
  const Eigen::Vector3d forward = (camera.target - camera.eye).normalized();
  const Eigen::Vector3d side = forward.cross(camera.up).normalized();
  const Eigen::Vector3d up = side.cross(forward);
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  view.block<1, 3>(0, 0) = side.transpose();
  view.block<1, 3>(1, 0) = up.transpose();
  view.block<1, 3>(2, 0) = -forward.transpose();
  view.block<3, 1>(0, 3) = -view.block<3, 3>(0, 0) * camera.eye;
  return view;
}

Eigen::Matrix4d Perspective(const Camera& camera, double aspect) {
  const double f = 1.0 / std::tan(camera.fov_y_deg * std::numbers::pi / 360.0);
  const double n = camera.near_m, far = camera.far_m;
  Eigen::Matrix4d projection = Eigen::Matrix4d::Zero();
  projection(0, 0) = f / aspect;
  projection(1, 1) = f;
  projection(2, 2) = (far + n) / (n - far);
  projection(2, 3) = 2 * far * n / (n - far);
  projection(3, 2) = -1;
  return projection;
}

void ValidateCamera(const Camera& camera) {
  const Eigen::Vector3d forward = camera.target - camera.eye;
  const bool finite = camera.eye.allFinite() && camera.target.allFinite() &&
                      camera.up.allFinite() && std::isfinite(camera.near_m) &&
                      std::isfinite(camera.far_m);
  const char* problem = nullptr;
  if (!finite) {
    problem = "non-finite value";
  } else if (forward.norm() == 0) {
    problem = "eye equals target";
  } else if (forward.normalized().cross(camera.up).norm() < 1e-9 * camera.up.norm() ||
             camera.up.norm() == 0) {
    problem = "up is zero or parallel to the viewing direction";
  } else if (!(camera.fov_y_deg > 0 && camera.fov_y_deg < 180)) {
    problem = "fov_y_deg outside (0, 180)";
  } else if (!(camera.near_m > 0 && camera.near_m < camera.far_m)) {
    problem = "need 0 < near_m < far_m";
  }
  if (problem) throw std::runtime_error(std::string("OffscreenRenderer: bad camera: ") + problem);
}

// Averages each S x S block of the bottom-up RGBA8 `source` (image.width * S wide) with
// integer rounding, which keeps the result exact and deterministic, and stores the rows
// top-down in `image`. S is a template parameter so the division is by a constant.
template <int S>
void DownsampleAndFlip(const uint8_t* source, Image& image) {
  const size_t out_stride = size_t(image.width) * 4;
  const size_t in_stride = out_stride * S;
  std::vector<uint32_t> sums(out_stride);
  for (int y = 0; y < image.height; ++y) {
    uint8_t* out = &image.rgba[size_t(image.height - 1 - y) * out_stride];
    if constexpr (S == 1) {
      std::memcpy(out, source + size_t(y) * in_stride, out_stride);
      continue;
    }
    std::fill(sums.begin(), sums.end(), 0u);
    for (int dy = 0; dy < S; ++dy) {
      const uint8_t* in = source + size_t(y * S + dy) * in_stride;
      uint32_t* sum = sums.data();
      for (int x = 0; x < image.width; ++x, sum += 4) {
        for (int dx = 0; dx < S; ++dx, in += 4) {
          sum[0] += in[0], sum[1] += in[1], sum[2] += in[2], sum[3] += in[3];
        }
      }
    }
    constexpr uint32_t kSamples = S * S;
    for (size_t i = 0; i < out_stride; ++i) out[i] = uint8_t((sums[i] + kSamples / 2) / kSamples);
  }
}

std::atomic<bool> started{false};

OSMesaContext CreateContext() {
  started = true;
  // Pictures must not depend on the machine's GL: softpipe and hardware drivers give other
  // bytes. Someone who sets the variable on purpose keeps their choice.
  setenv("GALLIUM_DRIVER", "llvmpipe", 0);
  OSMesaContext context = nullptr;
#ifdef OSMESA_CONTEXT_MAJOR_VERSION
  // The fixed-function pipeline needs a compatibility profile.
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            24,
                            OSMESA_STENCIL_BITS,
                            0,
                            OSMESA_ACCUM_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_COMPAT_PROFILE,
                            0};
  context = OSMesaCreateContextAttribs(attributes, nullptr);
#endif
  if (!context) context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (!context) throw std::runtime_error("OffscreenRenderer: cannot create an OSMesa context");
  return context;
}

}  // namespace

bool RendererStarted() { return started; }

struct OffscreenRenderer::Impl {
  OSMesaContext context = nullptr;
  int supersample = 1;
  int render_width = 0, render_height = 0;
  std::vector<uint8_t> framebuffer;  // OSMesa's colour buffer, bottom-up
  std::vector<uint8_t> pixels;       // glReadPixels target, bottom-up
  std::map<const Mesh*, GpuMesh> meshes;

  ~Impl() {
    if (!context) return;
    if (MakeCurrent()) {
      for (auto& [mesh, gpu] : meshes) Release(gpu);
    }
    OSMesaDestroyContext(context);
  }

  bool MakeCurrent() {
    return OSMesaMakeCurrent(context, framebuffer.data(), GL_UNSIGNED_BYTE, render_width,
                             render_height) == GL_TRUE;
  }

  static void Release(GpuMesh& gpu) {
    const GLuint buffers[] = {gpu.vertex_buffer, gpu.index_buffer};
    glDeleteBuffers(2, buffers);
    gpu = {};
  }

  const GpuMesh& Upload(const Mesh& mesh) {
    auto found = meshes.find(&mesh);
    if (found != meshes.end() && found->second.Matches(mesh)) return found->second;
    ValidateMesh(mesh);
    if (found == meshes.end()) found = meshes.emplace(&mesh, GpuMesh{}).first;
    GpuMesh& gpu = found->second;
    if (gpu.vertex_buffer == 0) {
      glGenBuffers(1, &gpu.vertex_buffer);
      glGenBuffers(1, &gpu.index_buffer);
    }
    const size_t positions_bytes = mesh.positions.size() * sizeof(float);
    const size_t normals_bytes = mesh.normals.size() * sizeof(float);
    glBindBuffer(GL_ARRAY_BUFFER, gpu.vertex_buffer);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(positions_bytes + normals_bytes), nullptr,
                 GL_STATIC_DRAW);
    glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(positions_bytes), mesh.positions.data());
    glBufferSubData(GL_ARRAY_BUFFER, GLintptr(positions_bytes), GLsizeiptr(normals_bytes),
                    mesh.normals.data());
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.index_buffer);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(uint32_t)),
                 mesh.indices.data(), GL_STATIC_DRAW);
    gpu.index_count = GLsizei(mesh.indices.size());
    gpu.normals_offset = mesh.normals.empty() ? 0 : positions_bytes;
    gpu.positions = mesh.positions.data();
    gpu.normals = mesh.normals.data();
    gpu.indices = mesh.indices.data();
    gpu.positions_size = mesh.positions.size();
    gpu.normals_size = mesh.normals.size();
    gpu.indices_size = mesh.indices.size();
    if (glGetError() != GL_NO_ERROR) {
      Release(gpu);
      meshes.erase(found);
      throw std::runtime_error("OffscreenRenderer: cannot upload a mesh of " +
                               std::to_string(mesh.positions.size() / 3) + " vertices");
    }
    return gpu;
  }

  // State that never changes between frames.
  void SetUpFixedState() {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glShadeModel(GL_SMOOTH);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DITHER);  // dithering is allowed to vary; keep bytes stable
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glEnable(GL_LIGHTING);
    // Models from CAD often mix windings; light both sides rather than show black faces.
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
    const GLfloat ambient[] = {0.30f, 0.30f, 0.30f, 1};
    glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
    glEnable(GL_COLOR_MATERIAL);
    glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
    const GLfloat no_specular[] = {0, 0, 0, 1};
    glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, no_specular);
    // Poses are isometries, but mesh normals from files need not be unit length.
    glEnable(GL_NORMALIZE);
    // Two directional lights fixed to the camera (set under an identity modelview), so every
    // view is lit the same: a key light from upper left, a weaker fill from lower right.
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    const GLfloat key_direction[] = {-0.35f, 0.55f, 0.75f, 0};
    const GLfloat key_diffuse[] = {0.65f, 0.65f, 0.65f, 1};
    const GLfloat fill_direction[] = {0.5f, -0.3f, 0.6f, 0};
    const GLfloat fill_diffuse[] = {0.25f, 0.25f, 0.25f, 1};
    const GLfloat black[] = {0, 0, 0, 1};
    glEnable(GL_LIGHT0);
    glLightfv(GL_LIGHT0, GL_POSITION, key_direction);
    glLightfv(GL_LIGHT0, GL_DIFFUSE, key_diffuse);
    glLightfv(GL_LIGHT0, GL_SPECULAR, black);
    glLightfv(GL_LIGHT0, GL_AMBIENT, black);
    glEnable(GL_LIGHT1);
    glLightfv(GL_LIGHT1, GL_POSITION, fill_direction);
    glLightfv(GL_LIGHT1, GL_DIFFUSE, fill_diffuse);
    glLightfv(GL_LIGHT1, GL_SPECULAR, black);
    glLightfv(GL_LIGHT1, GL_AMBIENT, black);
    glEnableClientState(GL_VERTEX_ARRAY);
    // Colour blends by the item's alpha; alpha accumulates coverage, so a translucent item
    // over an opaque background leaves the picture opaque.
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glViewport(0, 0, render_width, render_height);
  }

  void DrawOne(const DrawItem& item, const GpuMesh& gpu) {
    if (gpu.index_count == 0) return;
    Eigen::Matrix4d X = Eigen::Matrix4d::Identity();
    X.block<3, 4>(0, 0) = item.X_WorldMesh.matrix().block<3, 4>(0, 0);
    glPushMatrix();
    glMultMatrixd(X.data());
    glColor4f(item.colour.r, item.colour.g, item.colour.b, item.colour.a);
    glBindBuffer(GL_ARRAY_BUFFER, gpu.vertex_buffer);
    glVertexPointer(3, GL_FLOAT, 0, nullptr);
    if (gpu.normals_offset != 0) {
      glEnableClientState(GL_NORMAL_ARRAY);
      glNormalPointer(GL_FLOAT, 0, reinterpret_cast<const void*>(gpu.normals_offset));
    } else {
      glDisableClientState(GL_NORMAL_ARRAY);
      glNormal3f(0, 0, 1);
    }
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.index_buffer);
    glDrawElements(GL_TRIANGLES, gpu.index_count, GL_UNSIGNED_INT, nullptr);
    glPopMatrix();
  }
};

OffscreenRenderer::OffscreenRenderer(int width, int height, int supersample)
    : width_(width), height_(height) {
  if (width <= 0 || height <= 0 || supersample < 1 || supersample > 4) {
    throw std::runtime_error("OffscreenRenderer: bad size " + std::to_string(width) + "x" +
                             std::to_string(height) + " or supersample " +
                             std::to_string(supersample));
  }
  auto impl = std::make_unique<Impl>();
  impl->context = CreateContext();
  impl->supersample = supersample;
  impl->render_width = width * supersample;
  impl->render_height = height * supersample;
  GLint max_width = 0, max_height = 0;
  OSMesaGetIntegerv(OSMESA_MAX_WIDTH, &max_width);
  OSMesaGetIntegerv(OSMESA_MAX_HEIGHT, &max_height);
  if ((max_width > 0 && impl->render_width > max_width) ||
      (max_height > 0 && impl->render_height > max_height)) {
    throw std::runtime_error("OffscreenRenderer: " + std::to_string(impl->render_width) + "x" +
                             std::to_string(impl->render_height) + " exceeds the OSMesa limit of " +
                             std::to_string(max_width) + "x" + std::to_string(max_height));
  }
  const size_t bytes = size_t(impl->render_width) * size_t(impl->render_height) * 4;
  impl->framebuffer.resize(bytes);
  impl->pixels.resize(bytes);
  if (!impl->MakeCurrent()) {
    throw std::runtime_error("OffscreenRenderer: cannot make the OSMesa context current");
  }
  impl->SetUpFixedState();
  CheckGl("context set-up");
  impl_ = std::move(impl);
}

OffscreenRenderer::~OffscreenRenderer() = default;
OffscreenRenderer::OffscreenRenderer(OffscreenRenderer&&) noexcept = default;
OffscreenRenderer& OffscreenRenderer::operator=(OffscreenRenderer&&) noexcept = default;

Image OffscreenRenderer::Draw(const Camera& camera, std::span<const DrawItem> items,
                              Rgba background) {
  if (!impl_) throw std::runtime_error("OffscreenRenderer: used after move");
  ValidateCamera(camera);
  for (const DrawItem& item : items) {
    if (!item.mesh) throw std::runtime_error("OffscreenRenderer: DrawItem without a mesh");
  }
  Impl& impl = *impl_;
  // Another renderer may have made its own context current since the last frame.
  if (!impl.MakeCurrent()) {
    throw std::runtime_error("OffscreenRenderer: cannot make the OSMesa context current");
  }
  glGetError();  // start from a clean error state

  // Upload (and so validate) every mesh before drawing anything: bad input then throws with
  // the GL state untouched. std::map keeps the pointers valid while it grows.
  std::vector<const GpuMesh*> gpu_meshes;
  gpu_meshes.reserve(items.size());
  for (const DrawItem& item : items) gpu_meshes.push_back(&impl.Upload(*item.mesh));

  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);  // glClear leaves depth alone under a false mask
  glClearColor(background.r, background.g, background.b, background.a);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glMatrixMode(GL_PROJECTION);
  const Eigen::Matrix4d projection = Perspective(camera, double(width_) / double(height_));
  glLoadMatrixd(projection.data());
  glMatrixMode(GL_MODELVIEW);
  const Eigen::Matrix4d view = LookAt(camera);
  glLoadMatrixd(view.data());

  // Opaque first so translucent items blend over everything behind them.
  for (size_t i = 0; i < items.size(); ++i) {
    if (items[i].colour.a >= 1) impl.DrawOne(items[i], *gpu_meshes[i]);
  }
  glEnable(GL_BLEND);
  glDepthMask(GL_FALSE);
  for (size_t i = 0; i < items.size(); ++i) {
    if (items[i].colour.a < 1) impl.DrawOne(items[i], *gpu_meshes[i]);
  }
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);

  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  glReadPixels(0, 0, impl.render_width, impl.render_height, GL_RGBA, GL_UNSIGNED_BYTE,
               impl.pixels.data());
  CheckGl("Draw");

  Image image;
  image.width = width_;
  image.height = height_;
  image.rgba.resize(size_t(width_) * size_t(height_) * 4);
  switch (impl.supersample) {
    case 1:
      DownsampleAndFlip<1>(impl.pixels.data(), image);
      break;
    case 2:
      DownsampleAndFlip<2>(impl.pixels.data(), image);
      break;
    case 3:
      DownsampleAndFlip<3>(impl.pixels.data(), image);
      break;
    default:
      DownsampleAndFlip<4>(impl.pixels.data(), image);
      break;
  }
  return image;
}

void OffscreenRenderer::Forget(const Mesh* mesh) {
  if (!impl_) return;
  auto found = impl_->meshes.find(mesh);
  if (found == impl_->meshes.end()) return;
  if (impl_->MakeCurrent()) Impl::Release(found->second);
  impl_->meshes.erase(found);
}

void OffscreenRenderer::ForgetAll() {
  if (!impl_) return;
  if (impl_->MakeCurrent()) {
    for (auto& [mesh, gpu] : impl_->meshes) Impl::Release(gpu);
  }
  impl_->meshes.clear();
}

}  // namespace vmt::render
