#include "sim/renderer.hpp"

#include <cstring>

#include "common/error.hpp"
#include "sim/osmesa_library.hpp"

namespace centaur::sim {

struct Renderer::Impl {
  const OsMesaLibrary* osmesa = nullptr;
  OSMesaContext gl = nullptr;
  std::vector<unsigned char> gl_buffer;  // OSMesa's window buffer (unused: we draw offscreen)
  mjModel* model = nullptr;              // private copy (offscreen size may be raised)
  mjvScene scene;
  mjvCamera camera;
  mjvOption option;
  mjrContext context;
  std::vector<std::uint8_t> rgb, flipped;
};

Renderer::Renderer(const mjModel* model, int width, int height, const std::string& camera,
                   const std::string& track_body, bool shadows, bool reflections)
    : impl_(std::make_unique<Impl>()), width_(width), height_(height) {
  Impl& r = *impl_;
  r.osmesa = &osMesaLibrary();
  r.gl = r.osmesa->createContextExt(OSMESA_RGBA, 24, 8, 0, nullptr);
  if (!r.gl) throw RuntimeError("cannot create an OSMesa context for offscreen rendering");
  r.gl_buffer.resize(static_cast<std::size_t>(width) * height * 4);
  if (!r.osmesa->makeCurrent(r.gl, r.gl_buffer.data(), GL_UNSIGNED_BYTE, width, height)) {
    r.osmesa->destroyContext(r.gl);
    throw RuntimeError("cannot make the OSMesa context current");
  }
  r.model = mj_copyModel(nullptr, model);
  if (r.model->vis.global.offwidth < width) r.model->vis.global.offwidth = width;
  if (r.model->vis.global.offheight < height) r.model->vis.global.offheight = height;
  mjv_defaultScene(&r.scene);
  mjv_defaultCamera(&r.camera);
  mjv_defaultOption(&r.option);
  mjr_defaultContext(&r.context);
  mjv_makeScene(r.model, &r.scene, 10000);
  r.scene.flags[mjRND_SHADOW] = shadows ? 1 : 0;
  r.scene.flags[mjRND_REFLECTION] = reflections ? 1 : 0;
  mjr_makeContext(r.model, &r.context, mjFONTSCALE_100);
  mjr_setBuffer(mjFB_OFFSCREEN, &r.context);
  if (r.context.currentBuffer != mjFB_OFFSCREEN) throw RuntimeError("offscreen rendering is not supported");
  const int cam = camera.empty() ? -1 : mj_name2id(r.model, mjOBJ_CAMERA, camera.c_str());
  if (cam >= 0) {
    r.camera.type = mjCAMERA_FIXED;
    r.camera.fixedcamid = cam;
  } else {
    mjv_defaultFreeCamera(r.model, &r.camera);
    const int body = mj_name2id(r.model, mjOBJ_BODY, track_body.c_str());
    if (body >= 0) {
      r.camera.type = mjCAMERA_TRACKING;
      r.camera.trackbodyid = body;
    }
    r.camera.distance = 3.0;
    r.camera.azimuth = 120.0;
    r.camera.elevation = -15.0;
  }
  r.rgb.resize(static_cast<std::size_t>(width) * height * 3);
  r.flipped.resize(r.rgb.size());
}

Renderer::~Renderer() {
  mjr_freeContext(&impl_->context);
  mjv_freeScene(&impl_->scene);
  mj_deleteModel(impl_->model);
  impl_->osmesa->destroyContext(impl_->gl);
}

const std::vector<std::uint8_t>& Renderer::render(mjData* data) {
  Impl& r = *impl_;
  r.osmesa->makeCurrent(r.gl, r.gl_buffer.data(), GL_UNSIGNED_BYTE, width_, height_);
  mjrRect viewport = {0, 0, width_, height_};
  mjv_updateScene(r.model, data, &r.option, nullptr, &r.camera, mjCAT_ALL, &r.scene);
  mjr_render(viewport, &r.scene, &r.context);
  mjr_readPixels(r.rgb.data(), nullptr, viewport, &r.context);
  // OpenGL rows start at the bottom.
  const std::size_t row = static_cast<std::size_t>(width_) * 3;
  for (int y = 0; y < height_; ++y) {
    std::memcpy(r.flipped.data() + row * y, r.rgb.data() + row * (height_ - 1 - y), row);
  }
  return r.flipped;
}

}  // namespace centaur::sim
