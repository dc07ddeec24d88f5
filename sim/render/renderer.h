#pragma once
// Off-screen RGB, metric depth and per-pixel instance ids of one MuJoCo
// camera, with the pinhole intrinsics of the dataset (principal point set by
// overriding the GL frustum).
#include <cstdint>
#include <memory>
#include <vector>

#include <mujoco/mujoco.h>

#include "sim/render/gl_context.h"
#include "sim/render/rendered_frame.h"
#include "sim/scenario/scenario.h"

namespace depot::sim {

struct RenderTimings {
  double color_depth_ms = 0;
  double segmentation_ms = 0;
  double convert_ms = 0;
};

class Renderer {
 public:
  // `geom_instance[g]` is the instance id of geom g, `skin_instance[s]` that
  // of skin s (empty when the model has no skins).
  Renderer(const mjModel* model, int camera_id, const CameraIntrinsics& intrinsics,
           GlBackend backend, std::vector<uint16_t> geom_instance,
           std::vector<uint16_t> skin_instance = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders the current state of `data` (kinematics must be up to date).
  void render(mjData* data, RenderedFrame& out, RenderTimings* timings = nullptr);
  // The colour image only (sub-frames of an exposure): the same pixels as
  // render()'s bgr, without depth and labels.
  void render_colour(mjData* data, cv::Mat& bgr, RenderTimings* timings = nullptr);
  // Scales each model light's colours (indexed as the model's lights; empty
  // or 1: as modelled) in the renders that follow: lamps switched or dimmed.
  void set_light_scales(std::vector<float> scales) { light_scales_ = std::move(scales); }

 private:
  void apply_intrinsics();
  void apply_light_scales(const mjData* data);

  const mjModel* model_;
  CameraIntrinsics intrinsics_;
  std::unique_ptr<GlContext> gl_;
  std::vector<uint16_t> geom_instance_;
  std::vector<uint16_t> skin_instance_;
  mjvScene scene_;
  mjvCamera camera_;
  mjvOption option_;
  mjrContext context_;
  std::vector<unsigned char> rgb_;
  std::vector<float> depth_;
  std::vector<unsigned char> seg_;
  double near_ = 0, far_ = 0;
  std::vector<float> light_scales_;
};

}  // namespace depot::sim
