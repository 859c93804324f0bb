#include "sim/offscreen_renderer.h"

#include <GL/osmesa.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "sim/camera_model.h"
#include "sim/mujoco_handlers.h"

namespace sortcell::sim {
namespace {

// One OSMesa context per process. MuJoCo renders into its own off-screen framebuffer, so the
// context's window buffer only needs to exist, not to be large.
class GlContext {
 public:
  static GlContext& Instance() {
    static GlContext context;
    return context;
  }
  void MakeCurrent() {
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, kSize, kSize)) {
      throw std::runtime_error("OSMesa: OSMesaMakeCurrent failed");
    }
  }

 private:
  static constexpr int kSize = 64;
  GlContext() : buffer_(kSize * kSize * 4) {
    context_ = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, nullptr);
    if (context_ == nullptr) throw std::runtime_error("OSMesa: cannot create an off-screen GL context");
    MakeCurrent();
  }
  ~GlContext() { OSMesaDestroyContext(context_); }
  OSMesaContext context_ = nullptr;
  std::vector<unsigned char> buffer_;
};

}  // namespace

struct OffscreenRenderer::Impl {
  const Model* model = nullptr;
  mjvScene scene;
  mjvOption option;
  mjrContext context;
  std::vector<unsigned char> rgb_buffer;
  std::vector<float> depth_buffer;
  Lighting lighting;

  void CheckViewSize(int width, int height) const {
    if (width <= 0 || height <= 0 || width > context.offWidth || height > context.offHeight) {
      throw std::invalid_argument("scene '" + model->source() + "': a " + std::to_string(width) + "x" +
                                  std::to_string(height) +
                                  " render needs <visual><global offwidth offheight> at least that large, found " +
                                  std::to_string(context.offWidth) + "x" + std::to_string(context.offHeight));
    }
  }

  void ApplyLighting() {
    const float k = static_cast<float>(lighting.intensity);
    for (int i = 0; i < scene.nlight; ++i) {
      mjvLight& light = scene.lights[i];
      for (int c = 0; c < 3; ++c) {
        light.ambient[c] *= k;
        light.diffuse[c] *= k;
        light.specular[c] *= k;
      }
      light.dir[0] += static_cast<float>(lighting.tilt_x);
      light.dir[1] += static_cast<float>(lighting.tilt_y);
      const float n =
          std::sqrt(light.dir[0] * light.dir[0] + light.dir[1] * light.dir[1] + light.dir[2] * light.dir[2]);
      if (n > 0) {
        for (float& d : light.dir) d /= n;
      }
    }
  }

  // Draws the view into the off-screen buffer and reads it back (rows bottom-up, as GL gives them).
  void Draw(const Data& data, const RenderView& view, bool segmentation, bool want_depth) {
    CheckCameraId(*model, view.camera_id);
    CheckViewSize(view.width, view.height);
    GlContext::Instance().MakeCurrent();
    // Every renderer shares the one GL context but has its own framebuffer: bind ours, or a render
    // after another renderer's would read back the other one's buffer.
    mjr_setBuffer(mjFB_OFFSCREEN, &context);
    mjvCamera camera;
    mjv_defaultCamera(&camera);
    camera.type = mjCAMERA_FIXED;
    camera.fixedcamid = view.camera_id;
    scene.flags[mjRND_SEGMENT] = segmentation ? 1 : 0;
    scene.flags[mjRND_IDCOLOR] = segmentation ? 1 : 0;
    scene.flags[mjRND_SHADOW] = view.shadows ? 1 : 0;
    scene.flags[mjRND_REFLECTION] = view.reflections ? 1 : 0;
    // mjv_updateScene only reads the simulation state, but its signature is not const-correct.
    mjv_updateScene(model->get(), const_cast<mjData*>(data.get()), &option, nullptr, &camera, mjCAT_ALL, &scene);
    ApplyLighting();
    const mjrRect viewport = {0, 0, view.width, view.height};
    mjr_render(viewport, &scene, &context);
    const size_t pixels = static_cast<size_t>(view.width) * view.height;
    rgb_buffer.resize(3 * pixels);
    depth_buffer.resize(pixels);
    mjr_readPixels(rgb_buffer.data(), want_depth ? depth_buffer.data() : nullptr, viewport, &context);
  }
};

OffscreenRenderer::OffscreenRenderer(const Model& model) : impl_(std::make_unique<Impl>()) {
  InstallMujocoHandlers();
  // MuJoCo 2.2.2 draws at most 100 textures per render context; the rest render white, silently
  // (DESIGN.md section 5): refuse rather than render garbage.
  if (model->ntex > kMaxTextures) {
    throw std::invalid_argument("scene '" + model.source() + "': " + std::to_string(model->ntex) +
                                " textures, more than the " + std::to_string(kMaxTextures) +
                                " MuJoCo 2.2's renderer draws (compose fewer textured objects into one scene)");
  }
  impl_->model = &model;
  GlContext::Instance().MakeCurrent();
  mjv_defaultScene(&impl_->scene);
  mjv_makeScene(model.get(), &impl_->scene, 4000);
  mjv_defaultOption(&impl_->option);
  for (int g = 0; g < mjNGROUP; ++g) {
    impl_->option.geomgroup[g] = g <= 2 ? 1 : 0;
    impl_->option.sitegroup[g] = 0;
  }
  for (int f = 0; f < mjNVISFLAG; ++f) impl_->option.flags[f] = 0;
  impl_->option.flags[mjVIS_TEXTURE] = 1;
  impl_->option.flags[mjVIS_STATIC] = 1;
  impl_->option.flags[mjVIS_SKIN] = 1;
  mjr_defaultContext(&impl_->context);
  mjr_makeContext(model.get(), &impl_->context, mjFONTSCALE_100);
  mjr_setBuffer(mjFB_OFFSCREEN, &impl_->context);
  if (impl_->context.currentBuffer != mjFB_OFFSCREEN) {
    throw std::runtime_error("OSMesa: MuJoCo's off-screen framebuffer is not available");
  }
}

OffscreenRenderer::~OffscreenRenderer() {
  GlContext::Instance().MakeCurrent();
  mjr_freeContext(&impl_->context);
  mjv_freeScene(&impl_->scene);
}

void OffscreenRenderer::SetLighting(const Lighting& lighting) { impl_->lighting = lighting; }

void OffscreenRenderer::CheckViewSize(int width, int height) const { impl_->CheckViewSize(width, height); }

void OffscreenRenderer::Render(const Data& data, const RenderView& view, cv::Mat& rgb, cv::Mat& depth_buffer) {
  impl_->Draw(data, view, /*segmentation=*/false, /*want_depth=*/true);
  rgb.create(view.height, view.width, CV_8UC3);
  depth_buffer.create(view.height, view.width, CV_32FC1);
  const size_t row_rgb = 3 * static_cast<size_t>(view.width);
  for (int r = 0; r < view.height; ++r) {
    const int src = view.height - 1 - r;  // GL rows are bottom-up.
    std::memcpy(rgb.ptr<unsigned char>(r), impl_->rgb_buffer.data() + src * row_rgb, row_rgb);
    std::memcpy(depth_buffer.ptr<float>(r), impl_->depth_buffer.data() + static_cast<size_t>(src) * view.width,
                sizeof(float) * view.width);
  }
}

void OffscreenRenderer::RenderRgb(const Data& data, const RenderView& view, cv::Mat& rgb) {
  impl_->Draw(data, view, /*segmentation=*/false, /*want_depth=*/false);
  rgb.create(view.height, view.width, CV_8UC3);
  const size_t row_rgb = 3 * static_cast<size_t>(view.width);
  for (int r = 0; r < view.height; ++r) {
    std::memcpy(rgb.ptr<unsigned char>(r), impl_->rgb_buffer.data() + (view.height - 1 - r) * row_rgb, row_rgb);
  }
}

void OffscreenRenderer::RenderGeomIds(const Data& data, const RenderView& view, cv::Mat& geom_ids) {
  impl_->Draw(data, view, /*segmentation=*/true, /*want_depth=*/false);
  // Each drawn mjvGeom is coloured segid + 1 (little-endian RGB); 0 is the background.
  std::vector<int> segid_to_geom(impl_->scene.ngeom, -1);
  for (int i = 0; i < impl_->scene.ngeom; ++i) {
    const mjvGeom& g = impl_->scene.geoms[i];
    if (g.segid >= 0 && g.segid < impl_->scene.ngeom && g.objtype == mjOBJ_GEOM) {
      segid_to_geom[g.segid] = g.objid;
    }
  }
  geom_ids.create(view.height, view.width, CV_32SC1);
  for (int r = 0; r < view.height; ++r) {
    const unsigned char* src = impl_->rgb_buffer.data() + 3 * static_cast<size_t>(view.height - 1 - r) * view.width;
    int* dst = geom_ids.ptr<int>(r);
    for (int c = 0; c < view.width; ++c) {
      const int code = src[3 * c] | (src[3 * c + 1] << 8) | (src[3 * c + 2] << 16);
      const int segid = code - 1;
      dst[c] = (segid >= 0 && segid < static_cast<int>(segid_to_geom.size())) ? segid_to_geom[segid] : -1;
    }
  }
}

}  // namespace sortcell::sim
