#include "sim/world/simulated_sequence.h"

#include <chrono>
#include <cmath>

#include "common/error.h"
#include "common/tum_io.h"
#include "sim/actors/actor_variation.h"
#include "sim/scene/obstacles.h"
#include "sim/scene/scene_layout.h"
#include "sim/world/camera_clearance.h"

namespace depot::sim {

std::vector<std::pair<double, double>> frame_timestamps(const Scenario& s) {
  std::vector<std::pair<double, double>> out;
  if (!s.timestamps.file.empty()) {
    // An association file gives (rgb, depth) pairs; any other TUM file its
    // first column for both.
    if (detect_tum_file_kind(s.timestamps.file) == TumFileKind::kAssociation) {
      for (const auto& a : read_associations(s.timestamps.file))
        out.emplace_back(a.rgb_timestamp, a.depth_timestamp);
    } else {
      for (double t : read_timestamps(s.timestamps.file)) out.emplace_back(t, t);
    }
  } else {
    for (int i = 0; i < s.frames; ++i) {
      // Round to microseconds, as TUM files are written.
      double t = std::round((s.timestamps.start + i / s.timestamps.rate) * 1e6) / 1e6;
      out.emplace_back(t, t);
    }
  }
  if (static_cast<int>(out.size()) > s.frames) out.resize(s.frames);
  return out;
}

RenderedFrame covered_frame(const CameraIntrinsics& camera) {
  RenderedFrame f;
  f.bgr = cv::Mat::zeros(camera.height, camera.width, CV_8UC3);
  f.depth = cv::Mat::zeros(camera.height, camera.width, CV_32F);
  f.instance = cv::Mat::zeros(camera.height, camera.width, CV_16U);
  return f;
}

SimulatedSequence::SimulatedSequence(const Scenario& scenario, GlBackend backend, bool render)
    : scenario_(scenario), classes_(ClassTable::load(scenario.classes_path)) {
  stamps_ = frame_timestamps(scenario_);
  if (stamps_.empty()) fail(scenario_.source_path, "no frames to render");
  SceneLayout layout = load_scene_layout(scenario_.scene_path);
  // Before anything is built or rendered: the camera keeps its clearance to
  // the static scene, and the world seed draws the actors' variation.
  const StaticObstacles obstacles(layout, scenario_.world_seed());
  motion_ = std::make_unique<CameraMotion>(scenario_.motion, scenario_.seed, stamps_.front().first);
  enforce_camera_clearance(scenario_,
                           measure_camera_clearance(scenario_, obstacles, *motion_, stamps_));
  scenario_.actors = vary_actors(scenario_.actors, scenario_.world_seed(), obstacles);
  world_ = std::make_unique<World>(build_scene(layout, classes_, scenario_));
  if (render)
    renderer_ =
        std::make_unique<Renderer>(world_->model(), world_->camera_id(), scenario_.camera, backend,
                                   world_->geom_instances(), world_->skin_instances());
  for (const Instance& inst : world_->instances())
    if (inst.kind == InstanceKind::kPushable || inst.kind == InstanceKind::kActor)
      tracked_.push_back(&inst);
  previous_bodies_.resize(tracked_.size());
  for (size_t i = 0; i < tracked_.size(); ++i)
    world_->body_poses(*tracked_[i], previous_bodies_[i]);
}

bool SimulatedSequence::next(RenderedFrame& frame, FrameTruth& truth, SequenceTimings* timings) {
  if (!renderer_) fail(scenario_.name, "sequence was created without rendering");
  return advance(&frame, truth, timings);
}

bool SimulatedSequence::next_truth(FrameTruth& truth) {
  return advance(nullptr, truth, nullptr);
}

bool SimulatedSequence::advance(RenderedFrame* frame, FrameTruth& truth, SequenceTimings* timings) {
  if (next_ >= frame_count()) return false;
  const auto [t_rgb, t_depth] = stamps_[next_];
  // The world runs one frame period ahead of the first timestamp, so frame 0
  // already has a previous state to compare moving flags against.
  const double since_first = t_rgb - stamps_.front().first;
  const double world_time = since_first + 1.0 / scenario_.timestamps.rate;
  // Under a cover the world and the camera move on as usual; only the images
  // are the covered camera's (nothing rendered, so a cover also costs nothing).
  const bool covered = is_covered(scenario_.camera_cover, since_first);
  auto t0 = std::chrono::steady_clock::now();
  world_->advance_to(world_time);
  const Pose world_camera = motion_->pose_at(t_rgb);
  world_->set_camera_pose(world_camera);
  if (timings)
    timings->physics_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (frame && covered) {
    *frame = covered_frame(scenario_.camera);
    if (timings) timings->render = RenderTimings();
  } else if (frame) {
    renderer_->render(world_->data(), *frame, timings ? &timings->render : nullptr);
  }

  const Pose dataset_from_world = motion_->world_from_dataset().inverse();
  truth.index = next_;
  truth.rgb_timestamp = t_rgb;
  truth.depth_timestamp = t_depth;
  truth.camera = dataset_from_world * world_camera;
  truth.covered = covered;
  truth.objects.clear();
  std::vector<Pose> bodies;
  for (size_t i = 0; i < tracked_.size(); ++i) {
    world_->body_poses(*tracked_[i], bodies);
    ObjectState s;
    s.id = tracked_[i]->id;
    s.pose = dataset_from_world * world_->instance_pose(*tracked_[i]);
    for (size_t b = 0; b < bodies.size(); ++b) {
      s.max_translation =
          std::max(s.max_translation, translation_between(bodies[b], previous_bodies_[i][b]));
      s.max_rotation_deg =
          std::max(s.max_rotation_deg,
                   rotation_angle_between(bodies[b], previous_bodies_[i][b]) * 180.0 / M_PI);
    }
    s.moving = s.max_translation > kMovingTranslation || s.max_rotation_deg > kMovingRotationDeg;
    previous_bodies_[i] = bodies;
    truth.objects.push_back(s);
  }
  ++next_;
  return true;
}

}  // namespace depot::sim
