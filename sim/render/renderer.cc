#include "sim/render/renderer.h"

#include <chrono>
#include <vector>

#include "common/error.h"

namespace depot::sim {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

Renderer::Renderer(const mjModel* model, int camera_id, const CameraIntrinsics& intrinsics,
                   GlBackend backend, std::vector<uint16_t> geom_instance,
                   std::vector<uint16_t> skin_instance)
    : model_(model),
      intrinsics_(intrinsics),
      geom_instance_(std::move(geom_instance)),
      skin_instance_(std::move(skin_instance)) {
  if (model->vis.global.offwidth < intrinsics.width ||
      model->vis.global.offheight < intrinsics.height)
    fail("renderer", "offscreen buffer smaller than the image");
  gl_ = GlContext::create(backend, intrinsics.width, intrinsics.height);
  mjv_defaultScene(&scene_);
  mjv_defaultCamera(&camera_);
  mjv_defaultOption(&option_);
  mjr_defaultContext(&context_);
  mjv_makeScene(model, &scene_, 6000);
  mjr_makeContext(model, &context_, mjFONTSCALE_50);
  mjr_setBuffer(mjFB_OFFSCREEN, &context_);
  if (context_.currentBuffer != mjFB_OFFSCREEN)
    fail("renderer", "offscreen framebuffer not available");
  camera_.type = mjCAMERA_FIXED;
  camera_.fixedcamid = camera_id;
  scene_.flags[mjRND_SKYBOX] = 0;
  scene_.flags[mjRND_SHADOW] = model->vis.quality.shadowsize > 0;
  near_ = model->vis.map.znear * model->stat.extent;
  far_ = model->vis.map.zfar * model->stat.extent;
  const size_t n = static_cast<size_t>(intrinsics.width) * intrinsics.height;
  rgb_.resize(3 * n);
  depth_.resize(n);
  seg_.resize(3 * n);
}

Renderer::~Renderer() {
  mjr_freeContext(&context_);
  mjv_freeScene(&scene_);
}

void Renderer::apply_intrinsics() {
  // MuJoCo sizes the frustum from fovy and the viewport aspect; overwrite it
  // so pixel (u, v) centres follow u = f x/z + cx, v = f y/z + cy exactly.
  const double f = intrinsics_.f, cx = intrinsics_.cx, cy = intrinsics_.cy;
  const double w = intrinsics_.width, h = intrinsics_.height;
  for (int i = 0; i < 2; ++i) {
    mjvGLCamera& c = scene_.camera[i];
    const double n = c.frustum_near;
    c.frustum_top = static_cast<float>(n * (cy + 0.5) / f);
    c.frustum_bottom = static_cast<float>(n * (cy + 0.5 - h) / f);
    c.frustum_center = static_cast<float>(n * (w / 2.0 - 0.5 - cx) / f);
  }
}

void Renderer::apply_light_scales(const mjData* data) {
  if (light_scales_.empty()) return;
  if (static_cast<int>(light_scales_.size()) != model_->nlight)
    fail("renderer", "light scales for " + std::to_string(light_scales_.size()) +
                         " lights, the model has " + std::to_string(model_->nlight));
  // mjv_updateScene copies the model's lights (after the headlight, if on),
  // their world positions and directions cast to float: each model light is
  // the scene light with exactly those, each scene light taken once.
  std::vector<bool> taken(scene_.nlight, false);
  for (int i = 0; i < model_->nlight; ++i) {
    if (light_scales_[i] == 1.0f) continue;
    const mjtNum* pos = data->light_xpos + 3 * i;
    const mjtNum* dir = data->light_xdir + 3 * i;
    mjvLight* found = nullptr;
    for (int j = 0; j < scene_.nlight && !found; ++j) {
      const mjvLight& l = scene_.lights[j];
      if (l.headlight || taken[j]) continue;
      bool same = true;
      for (int k = 0; k < 3; ++k)
        same = same && l.pos[k] == static_cast<float>(pos[k]) &&
               l.dir[k] == static_cast<float>(dir[k]);
      if (same) {
        found = &scene_.lights[j];
        taken[j] = true;
      }
    }
    if (!found) fail("renderer", "light " + std::to_string(i) + " is not in the rendered scene");
    for (int k = 0; k < 3; ++k) {
      found->ambient[k] *= light_scales_[i];
      found->diffuse[k] *= light_scales_[i];
      found->specular[k] *= light_scales_[i];
    }
  }
}

void Renderer::render(mjData* data, RenderedFrame& out, RenderTimings* timings) {
  const int w = intrinsics_.width, h = intrinsics_.height;
  const mjrRect viewport{0, 0, w, h};
  gl_->make_current();
  auto t0 = std::chrono::steady_clock::now();
  mjv_updateScene(model_, data, &option_, nullptr, &camera_, mjCAT_ALL, &scene_);
  apply_light_scales(data);
  apply_intrinsics();
  scene_.flags[mjRND_SEGMENT] = 0;
  scene_.flags[mjRND_IDCOLOR] = 0;
  mjr_render(viewport, &scene_, &context_);
  mjr_readPixels(rgb_.data(), depth_.data(), viewport, &context_);
  auto t1 = std::chrono::steady_clock::now();
  if (timings) timings->color_depth_ms = ms_since(t0);

  scene_.flags[mjRND_SEGMENT] = 1;
  scene_.flags[mjRND_IDCOLOR] = 1;
  mjr_render(viewport, &scene_, &context_);
  mjr_readPixels(seg_.data(), nullptr, viewport, &context_);
  scene_.flags[mjRND_SEGMENT] = 0;
  scene_.flags[mjRND_IDCOLOR] = 0;
  auto t2 = std::chrono::steady_clock::now();
  if (timings)
    timings->segmentation_ms = std::chrono::duration<double, std::milli>(t2 - t1).count();

  out.bgr.create(h, w, CV_8UC3);
  out.depth.create(h, w, CV_32F);
  out.instance.create(h, w, CV_16U);
  const double n = near_, f = far_;
  for (int y = 0; y < h; ++y) {
    const size_t src_row = static_cast<size_t>(h - 1 - y) * w;  // GL rows are bottom-up
    auto* bgr = out.bgr.ptr<cv::Vec3b>(y);
    auto* depth = out.depth.ptr<float>(y);
    auto* inst = out.instance.ptr<uint16_t>(y);
    for (int x = 0; x < w; ++x) {
      const size_t i = src_row + x;
      bgr[x] = cv::Vec3b(rgb_[3 * i + 2], rgb_[3 * i + 1], rgb_[3 * i]);
      const float d = depth_[i];
      depth[x] = d >= 1.0f ? 0.0f : static_cast<float>(n * f / (f - d * (f - n)));
      const int seg = seg_[3 * i] | (seg_[3 * i + 1] << 8) | (seg_[3 * i + 2] << 16);
      uint16_t id = 0;
      if (seg > 0 && seg <= scene_.ngeom) {
        const mjvGeom& g = scene_.geoms[seg - 1];
        if (g.objtype == mjOBJ_GEOM && g.objid >= 0 &&
            g.objid < static_cast<int>(geom_instance_.size()))
          id = geom_instance_[g.objid];
        // Skinned actors: MuJoCo 2.2 draws a skin as its own object type.
        else if (g.objtype == mjOBJ_SKIN && g.objid >= 0 &&
                 g.objid < static_cast<int>(skin_instance_.size()))
          id = skin_instance_[g.objid];
      }
      inst[x] = id;
      if (id == 0) depth[x] = 0.0f;  // nothing there (never inside a closed hall)
    }
  }
  if (timings) timings->convert_ms = ms_since(t2);
}

void Renderer::render_colour(mjData* data, cv::Mat& bgr, RenderTimings* timings) {
  const int w = intrinsics_.width, h = intrinsics_.height;
  const mjrRect viewport{0, 0, w, h};
  gl_->make_current();
  auto t0 = std::chrono::steady_clock::now();
  mjv_updateScene(model_, data, &option_, nullptr, &camera_, mjCAT_ALL, &scene_);
  apply_light_scales(data);
  apply_intrinsics();
  scene_.flags[mjRND_SEGMENT] = 0;
  scene_.flags[mjRND_IDCOLOR] = 0;
  mjr_render(viewport, &scene_, &context_);
  mjr_readPixels(rgb_.data(), nullptr, viewport, &context_);
  auto t1 = std::chrono::steady_clock::now();
  if (timings) timings->color_depth_ms = ms_since(t0);
  bgr.create(h, w, CV_8UC3);
  for (int y = 0; y < h; ++y) {
    const unsigned char* src = rgb_.data() + 3 * static_cast<size_t>(h - 1 - y) * w;
    auto* row = bgr.ptr<cv::Vec3b>(y);
    for (int x = 0; x < w; ++x) row[x] = cv::Vec3b(src[3 * x + 2], src[3 * x + 1], src[3 * x]);
  }
  if (timings) timings->convert_ms = ms_since(t1);
}

}  // namespace depot::sim
