#include "sim/world/simulated_sequence.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "common/error.h"
#include "common/rng.h"
#include "common/tum_io.h"
#include "sim/actors/actor_variation.h"
#include "sim/actors/crowd.h"
#include "sim/scenario/scene_layout.h"
#include "sim/scene/obstacles.h"
#include "sim/sensor/light.h"
#include "sim/sensor/motion_field.h"
#include "sim/sensor/shutter.h"
#include "sim/world/camera_clearance.h"

namespace depot::sim {

namespace {
// The distance at which sub-frames are spaced about one pixel of smear
// apart: nearer surfaces moving fast get coarser steps (still capped by
// max_subframes in any case).
constexpr double kSmearDepth = 1.0;  // m

// Each lamp drives the ceiling light nearest it (the model's lights are the
// layout's, in order); two lamps may not share one.
std::vector<int> lamp_lights(const Scenario& scenario, const SceneLayout& layout) {
  std::vector<int> lights;
  for (const Scenario::Lamp& lamp : scenario.lamps) {
    if (layout.lights.empty()) fail(scenario.source_path, "lamps: the scene has no lights");
    auto distance = [&](size_t i) {
      return (layout.lights[i].position.head<2>() - lamp.near).norm();
    };
    int nearest = 0;
    for (size_t i = 1; i < layout.lights.size(); ++i)
      if (distance(i) < distance(nearest)) nearest = static_cast<int>(i);
    const auto same = std::find(lights.begin(), lights.end(), nearest);
    if (same != lights.end())
      fail(scenario.source_path, "lamps " + std::to_string(same - lights.begin() + 1) + " and " +
                                     std::to_string(lights.size() + 1) +
                                     " both pick the ceiling light at (" +
                                     std::to_string(layout.lights[nearest].position.x()) + ", " +
                                     std::to_string(layout.lights[nearest].position.y()) + ")");
    lights.push_back(nearest);
  }
  return lights;
}
}  // namespace

std::pair<double, double> frame_instants_range(const Scenario& s) {
  if (s.sensor.ideal) return {0.0, 0.0};
  const double half = 0.5 * (s.sensor.longest_exposure() + s.sensor.readout);
  return {std::min(-half, s.sensor.depth_offset), std::max(half, s.sensor.depth_offset)};
}

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
    const TimestampSpec& ts = s.timestamps;
    const double period = 1.0 / ts.rate;
    // Jitter keeps the frames in order, at least half a period apart (a
    // shutter may span more than that: sim/world/world.h checkpoints).
    const double limit = 0.25 * period;
    Rng jitter(derive_seed(s.seed, 0x71773e));
    Rng drops(derive_seed(s.seed, 0xd709));
    // Round to microseconds, as TUM files are written.
    auto microseconds = [](double t) { return std::round(t * 1e6) / 1e6; };
    for (int i = 0; i < s.frames; ++i) {
      double t = ts.start + i / ts.rate;
      if (ts.jitter > 0) t += std::clamp(ts.jitter * jitter.normal(), -limit, limit);
      if (ts.drop_rate > 0 && drops.uniform() < ts.drop_rate) continue;
      const double rgb = microseconds(t);
      const double depth = s.sensor.ideal ? rgb : microseconds(t + s.sensor.depth_offset);
      out.emplace_back(rgb, depth);
    }
    if (out.empty()) fail(s.source_path, "every frame was dropped (timestamps.drop_rate)");
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
    : scenario_(scenario),
      classes_(ClassTable::load(scenario.classes_path)),
      exposure_control_(scenario.sensor.exposure_control, scenario.sensor.exposure) {
  stamps_ = frame_timestamps(scenario_);
  if (stamps_.empty()) fail(scenario_.source_path, "no frames to render");
  const SceneLayout& layout = scenario_.layout;
  // Before anything is built or rendered: the camera keeps its clearance to
  // the static scene, and the world seed draws the actors' variation.
  const StaticObstacles obstacles(layout, scenario_.world_seed());
  motion_ = std::make_unique<CameraMotion>(scenario_.motion, scenario_.seed, stamps_.front().first);
  enforce_camera_clearance(scenario_,
                           measure_camera_clearance(scenario_, obstacles, *motion_, stamps_));
  scenario_.actors =
      vary_actors(scenario_.actors, scenario_.world_seed(), obstacles.column_clearance());
  // Crowds: their walkers simulated once over the whole sequence, clear of
  // each other and of the static scene.
  const double duration = stamps_.back().first - stamps_.front().first + 1.0;
  for (ActorSpec& walker : simulate_crowds(scenario_.crowds, scenario_.dynamic_load, duration,
                                           scenario_.world_seed(), obstacles.column_clearance()))
    scenario_.actors.push_back(std::move(walker));
  // A lens or non-square pixels: render a wider square-pixel canvas and
  // resample it (sim/sensor/lens.h); --ideal keeps the pixels, drops the lens.
  const LensDistortion lens = scenario_.sensor.ideal ? LensDistortion{} : scenario_.sensor.lens;
  if (lens_resamples(scenario_.camera, lens))
    lens_ = std::make_unique<LensMapping>(
        make_lens_mapping(scenario_.camera, lens, scenario_.source_path));
  const CameraIntrinsics& render_camera = lens_ ? lens_->canvas : scenario_.camera;
  lamp_lights_ = lamp_lights(scenario_, layout);
  openings_ = place_openings(scenario_.openings, layout.length, layout.width, layout.height);
  if (!openings_.empty()) pixel_rays_ = pixel_rays(scenario_.camera, lens_.get());
  world_ = std::make_unique<World>(build_scene(layout, classes_, scenario_, render_camera));
  if (render)
    renderer_ =
        std::make_unique<Renderer>(world_->model(), world_->camera_id(), render_camera, backend,
                                   world_->geom_instances(), world_->skin_instances());
  for (const Instance& inst : world_->instances())
    if (inst.kind == InstanceKind::kPushable || inst.kind == InstanceKind::kActor)
      tracked_.push_back(&inst);
  if (!scenario_.sensor.ideal) {
    shutter_.exposure = scenario_.sensor.exposure;
    shutter_.readout = scenario_.sensor.readout;
    shutter_.max_subframes = scenario_.sensor.max_subframes;
    depth_offset_ = scenario_.sensor.depth_offset;
  }
  previous_bodies_.resize(tracked_.size());
  for (size_t i = 0; i < tracked_.size(); ++i) {
    world_->body_poses(*tracked_[i], previous_bodies_[i]);
    tracked_body_instance_.insert(tracked_body_instance_.end(), previous_bodies_[i].size(),
                                  tracked_[i]->id);
  }
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
  if (timings) *timings = SequenceTimings();
  // Auto-exposure chose this frame's exposure from the frames before it.
  if (scenario_.sensor.forms_colour()) shutter_.exposure = exposure_control_.current().exposure;
  // Sub-frames across the exposure and readout (sim/sensor/shutter.h), in
  // time order; the one at offset 0 gives depth, labels and truth.
  const bool shutter = frame && !covered && shutter_.active();
  const std::vector<double> offsets =
      shutter ? subframe_offsets(shutter_, image_motion_over_span(t_rgb))
              : std::vector<double>{0.0};
  // The depth camera's own instant (sensor.depth_offset), in time order
  // among the colour camera's.
  const bool own_depth = frame && !covered && depth_offset_ != 0.0;
  std::vector<double> instants = offsets;
  if (own_depth)
    instants.insert(std::upper_bound(instants.begin(), instants.end(), depth_offset_),
                    depth_offset_);
  // A span longer than the gap between two timestamps reaches back before
  // where the last frame left the world: start from the state saved for it.
  if (world_->time() > world_time + instants.front() + 1e-9) {
    const double saved = world_->checkpoint_time();
    if (saved < 0 || saved > world_time + instants.front() + 1e-9)
      fail(scenario_.source_path,
           "internal: frame " + std::to_string(next_) + " reaches before the world's checkpoint");
    world_->restore_checkpoint();
  }
  // The next frame's earliest instant: save the world there on the way past.
  double next_earliest = INFINITY;
  if (next_ + 1 < frame_count())
    next_earliest = stamps_[next_ + 1].first - stamps_.front().first +
                    1.0 / scenario_.timestamps.rate + frame_instants_range(scenario_).first;
  // The motion field renders the timestamp only and keeps, per sub-frame,
  // the camera and every tracked body to move that render by.
  // A lamp changing during the span is light the one render cannot show:
  // that frame is rendered sub-frame by sub-frame.
  const bool field = shutter && scenario_.sensor.motion_blur == "field" &&
                     !lamps_change(since_first + offsets.front(), since_first + offsets.back());
  std::vector<Pose> field_cameras(field ? offsets.size() : 0);
  std::vector<std::vector<Pose>> field_bodies(field ? offsets.size() : 0);
  RenderedFrame stamp;  // the render the field moves
  std::vector<cv::Mat> colours;
  RenderedFrame depth_frame;
  bool depth_done = false;
  size_t subframe = 0;
  for (double offset : instants) {
    auto t0 = std::chrono::steady_clock::now();
    // advance_to() ends on the physics step nearest its time, up to half a
    // step past it: save before that could pass the next frame's start.
    if (world_time + offset + 0.5 * world_->timestep() > next_earliest) {
      world_->save_checkpoint_before(next_earliest);
      next_earliest = INFINITY;
    }
    world_->advance_to(world_time + offset);
    const Pose world_camera = motion_->pose_at(t_rgb + offset);
    world_->set_camera_pose(world_camera);
    light_lamps(since_first + offset);
    if (timings)
      timings->physics_ms +=
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (frame && covered) {
      *frame = covered_frame(scenario_.camera);
    } else if (frame) {
      RenderTimings r;
      if (own_depth && offset == depth_offset_ && !depth_done) {
        render(depth_frame, &r);
        depth_done = true;
      } else {
        if (field) {
          field_cameras[subframe] = world_camera;
          tracked_body_poses(field_bodies[subframe]);
        }
        if (offset == 0.0) {
          render(*frame, &r);
          colours.push_back(frame->bgr);
          // A later render (the depth camera's) reuses the renderer's buffers.
          if (field && lens_)
            stamp = {canvas_.bgr.clone(), canvas_.depth.clone(), canvas_.instance.clone()};
          else if (field)
            stamp = {frame->bgr, frame->depth, frame->instance};
        } else {
          colours.emplace_back();
          if (!field) render_colour(colours.back(), &r);
        }
        ++subframe;
      }
      if (timings) {
        timings->render.color_depth_ms += r.color_depth_ms;
        timings->render.segmentation_ms += r.segmentation_ms;
        timings->render.convert_ms += r.convert_ms;
      }
    }
    if (offset == 0.0) record_truth(world_camera, t_rgb, t_depth, covered, truth);
  }
  if (field) {
    auto t0 = std::chrono::steady_clock::now();
    synthesise_subframes(stamp, offsets, field_cameras, field_bodies, colours);
    if (timings)
      timings->field_ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  if (shutter) frame->bgr = integrate_shutter(colours, offsets, shutter_);
  const cv::Mat daylight =
      frame && !covered
          ? let_in_daylight(*frame, own_depth ? &depth_frame.depth : nullptr, t_rgb, since_first)
          : cv::Mat();
  if (own_depth) frame->depth = depth_frame.depth;
  if (scenario_.sensor.forms_colour())
    truth.capture = expose(frame ? &frame->bgr : nullptr, since_first, daylight);
  if (timings) {
    timings->subframes = static_cast<int>(offsets.size());
    timings->renders = field ? 1 : static_cast<int>(offsets.size());
  }
  ++next_;
  return true;
}

void SimulatedSequence::tracked_body_poses(std::vector<Pose>& out) const {
  out.clear();
  std::vector<Pose> bodies;
  for (const Instance* inst : tracked_) {
    world_->body_poses(*inst, bodies);
    out.insert(out.end(), bodies.begin(), bodies.end());
  }
}

void SimulatedSequence::synthesise_subframes(const RenderedFrame& stamp,
                                             const std::vector<double>& offsets,
                                             const std::vector<Pose>& cameras,
                                             const std::vector<std::vector<Pose>>& bodies,
                                             std::vector<cv::Mat>& colours) {
  const size_t at_stamp = std::find(offsets.begin(), offsets.end(), 0.0) - offsets.begin();
  const Pose& camera = cameras[at_stamp];
  // Which body each pixel moves with, from the bodies' origins at the stamp.
  std::vector<Eigen::Vector3d> body_origin;
  const Pose camera_from_world = camera.inverse();
  for (const Pose& b : bodies[at_stamp]) body_origin.push_back(camera_from_world * b.translation());
  const CameraIntrinsics& render_camera = lens_ ? lens_->canvas : scenario_.camera;
  const cv::Mat body = assign_bodies(stamp.depth, stamp.instance, render_camera,
                                     tracked_body_instance_, body_origin);
  const FieldSource source = make_field_source(stamp.bgr, stamp.depth, body, render_camera);
  auto motion_to = [&](size_t k) {
    return instant_motion(camera, bodies[at_stamp], cameras[k], bodies[k]);
  };
  // Kept across frames: fresh pages every frame cost more than the splatting.
  if (subframe_buffers_.size() < offsets.size()) subframe_buffers_.resize(offsets.size());
  // Sub-frames are independent of each other: one per worker.
  cv::parallel_for_(cv::Range(0, static_cast<int>(offsets.size())), [&](const cv::Range& range) {
    for (int k = range.start; k < range.end; ++k) {
      if (static_cast<size_t>(k) == at_stamp) continue;
      if (lens_) {
        thread_local cv::Mat canvas;
        synthesise_subframe(source, motion_to(k), canvas);
        apply_lens_colour(*lens_, canvas, subframe_buffers_[k]);
      } else {
        synthesise_subframe(source, motion_to(k), subframe_buffers_[k]);
      }
      colours[k] = subframe_buffers_[k];
    }
  });
}

bool SimulatedSequence::lamps_change(double t0, double t1) const {
  for (const Scenario::Lamp& lamp : scenario_.lamps) {
    if (light_level_at(lamp.level, t0) != light_level_at(lamp.level, t1)) return true;
    for (const Eigen::Vector2d& e : lamp.level.events)
      if (e.x() > t0 && e.x() < t1) return true;
  }
  return false;
}

void SimulatedSequence::light_lamps(double since_first) {
  if (!renderer_ || lamp_lights_.empty()) return;
  std::vector<float> scales(world_->model()->nlight, 1.0f);
  for (size_t k = 0; k < lamp_lights_.size(); ++k)
    scales.at(lamp_lights_[k]) =
        static_cast<float>(light_level_at(scenario_.lamps[k].level, since_first));
  renderer_->set_light_scales(std::move(scales));
}

void SimulatedSequence::render(RenderedFrame& out, RenderTimings* timings) {
  if (!lens_) return renderer_->render(world_->data(), out, timings);
  renderer_->render(world_->data(), canvas_, timings);
  apply_lens(*lens_, canvas_, out);
}

void SimulatedSequence::render_colour(cv::Mat& bgr, RenderTimings* timings) {
  if (!lens_) return renderer_->render_colour(world_->data(), bgr, timings);
  renderer_->render_colour(world_->data(), canvas_.bgr, timings);
  apply_lens_colour(*lens_, canvas_.bgr, bgr);
}

cv::Mat SimulatedSequence::let_in_daylight(RenderedFrame& frame, cv::Mat* own_depth, double t_rgb,
                                           double since_first) const {
  if (openings_.empty()) return {};
  // The colour and the labels as the render at the timestamp shows them.
  const cv::Mat radiance =
      daylight_radiance(frame.depth, pixel_rays_, motion_->pose_at(t_rgb), openings_, since_first);
  cv::Mat none;
  show_daylight(radiance, frame.bgr, own_depth ? none : frame.depth, frame.instance);
  // The depth camera's own image at its own instant.
  if (own_depth)
    show_daylight(
        daylight_radiance(*own_depth, pixel_rays_, motion_->pose_at(t_rgb + depth_offset_),
                          openings_, since_first + depth_offset_),
        none, *own_depth, none);
  return radiance;
}

ColourCapture SimulatedSequence::expose(const cv::Mat* bgr, double since_first,
                                        const cv::Mat& daylight) {
  ColourCapture capture;
  capture.daylight = daylight;
  const ExposureSetting& setting = exposure_control_.current();
  capture.exposure = setting.exposure;
  capture.gain = setting.gain;
  capture.scale = setting.scale;
  const int rows = scenario_.camera.height;
  std::vector<double> row_offsets(rows);
  for (int y = 0; y < rows; ++y) row_offsets[y] = shutter_.row_offset(y, rows);
  capture.row_light =
      row_light_levels(scenario_.sensor.light, since_first, setting.exposure, row_offsets);
  // The meter reads the frame as the sensor will expose it; without images
  // (truth only) the loop cannot run and the exposure stays where it is.
  if (bgr && !bgr->empty())
    exposure_control_.observe(metered_brightness(*bgr, scenario_.sensor.colour, capture),
                              1.0 / scenario_.timestamps.rate);
  return capture;
}

double SimulatedSequence::image_motion_over_span(double t_rgb) const {
  const CameraIntrinsics& c = scenario_.camera;
  const double half = 0.5 * shutter_.span();
  // The camera's own motion smears a surface 1 m away by this much; an
  // actor moving as fast as the fastest body part did over the last frame
  // smears by its speed over the span at the same distance.
  const double camera =
      camera_image_motion(motion_->pose_at(t_rgb - half), motion_->pose_at(t_rgb + half), c.f, c.cx,
                          c.cy, c.width, c.height, kSmearDepth);
  const double actors = c.f * last_body_speed_ * shutter_.span() / kSmearDepth;
  return camera + actors;
}

void SimulatedSequence::record_truth(const Pose& world_camera, double t_rgb, double t_depth,
                                     bool covered, FrameTruth& truth) {
  const Pose dataset_from_world = motion_->world_from_dataset().inverse();
  truth.index = next_;
  truth.rgb_timestamp = t_rgb;
  truth.depth_timestamp = t_depth;
  truth.camera = dataset_from_world * world_camera;
  truth.covered = covered;
  truth.rows.clear();
  if (shutter_.readout > 0) {
    const int height = scenario_.camera.height;
    for (int k = 0; k <= kRowPoseIntervals; ++k) {
      RowPose r;
      r.row =
          static_cast<int>(std::lround(static_cast<double>(k) * (height - 1) / kRowPoseIntervals));
      r.time = t_rgb + shutter_.row_offset(r.row, height);
      r.camera = dataset_from_world * motion_->pose_at(r.time);
      truth.rows.push_back(r);
    }
  }
  truth.objects.clear();
  std::vector<Pose> bodies;
  double fastest_step = 0.0;
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
    fastest_step = std::max(fastest_step, s.max_translation);
    previous_bodies_[i] = bodies;
    truth.objects.push_back(s);
  }
  last_body_speed_ = fastest_step * scenario_.timestamps.rate;
}

}  // namespace depot::sim
