#pragma once
// A scenario played frame by frame in memory: exact RGB, depth and instance
// images plus the ground truth of each frame. The dataset writer stores it;
// SLAM tests may also consume it directly.
#include <memory>
#include <string>
#include <vector>

#include "common/pose.h"
#include "sim/camera/camera_motion.h"
#include "sim/render/renderer.h"
#include "sim/scenario/class_table.h"
#include "sim/scenario/scenario.h"
#include "sim/sensor/auto_exposure.h"
#include "sim/sensor/colour_pipeline.h"
#include "sim/sensor/daylight.h"
#include "sim/sensor/lens.h"
#include "sim/sensor/shutter.h"
#include "sim/world/world.h"

namespace depot::sim {

struct ObjectState {
  uint16_t id = 0;
  Pose pose = Pose::Identity();  // in the dataset frame
  bool moving = false;           // moved > 1 mm or 0.1 deg since the previous frame
  double max_translation = 0.0;  // m, largest body displacement since the previous frame
  double max_rotation_deg = 0.0;
};

// Under a rolling shutter, the camera when one row was exposed (the middle
// of that row's exposure), in the dataset frame.
struct RowPose {
  int row = 0;
  double time = 0.0;
  Pose camera = Pose::Identity();  // T_dataset_camera
};

// Rows of a rolling-shutter frame given a pose of their own: every eighth of
// the height, first and last included (rows between: interpolate).
constexpr int kRowPoseIntervals = 8;

struct FrameTruth {
  int index = 0;
  double rgb_timestamp = 0.0;
  double depth_timestamp = 0.0;
  Pose camera = Pose::Identity();  // T_dataset_camera
  // Inside a `camera_cover` interval: the images are a covered camera's (see
  // covered_frame()), while the camera and the objects keep their true poses.
  bool covered = false;
  std::vector<ObjectState> objects;  // every pushable and actor instance
  // With a readout time (not ideal): the camera at sampled rows' instants,
  // first row first (groundtruth_rows.txt). Empty for a global shutter.
  std::vector<RowPose> rows;
  // How the colour image was exposed (sim/sensor/colour_pipeline.h): the
  // exposure and gain auto-exposure chose, the light each row saw.
  ColourCapture capture;
};

struct SequenceTimings {
  double physics_ms = 0;
  RenderTimings render;  // summed over the frame's sub-frames
  int subframes = 1;     // sub-frame instants of the frame (sim/sensor/shutter.h)
  int renders = 1;       // colour renders among them (1 when the motion field made the rest)
  double field_ms = 0;   // synthesising sub-frames by the motion field
};

// The frame timestamps of a scenario: (rgb, depth) pairs (with the
// timestamps block's jitter and dropped frames, and the depth clock's offset).
std::vector<std::pair<double, double>> frame_timestamps(const Scenario& scenario);

// The earliest and latest instant a frame renders, in seconds from its
// timestamp: the shutter's span and the depth camera's offset.
std::pair<double, double> frame_instants_range(const Scenario& scenario);

// What a covered RGB-D camera gives: a black colour image, no depth (0 =
// invalid) and, since nothing is seen, no instance in the labels.
RenderedFrame covered_frame(const CameraIntrinsics& camera);

constexpr double kMovingTranslation = 0.001;  // m
constexpr double kMovingRotationDeg = 0.1;

class SimulatedSequence {
 public:
  // `render` = false: ground truth only (no GL context, no images).
  SimulatedSequence(const Scenario& scenario, GlBackend backend, bool render = true);
  int frame_count() const { return static_cast<int>(stamps_.size()); }
  int next_index() const { return next_; }
  // Renders the next frame; false after the last. With an exposure or a
  // readout time (sensor block, not ideal) the colour image integrates
  // sub-frames around the timestamp (sim/sensor/shutter.h); depth, labels
  // and truth are the timestamp's. A lens distortion (sensor.k1..k3) or
  // non-square pixels (camera.fy) apply to all three alike.
  bool next(RenderedFrame& frame, FrameTruth& truth, SequenceTimings* timings = nullptr);
  // Advances to the next frame without rendering; false after the last.
  bool next_truth(FrameTruth& truth);

  const World& world() const { return *world_; }
  const ClassTable& classes() const { return classes_; }
  const Scenario& scenario() const { return scenario_; }
  const Pose& world_from_dataset() const { return motion_->world_from_dataset(); }

 private:
  Scenario scenario_;
  ClassTable classes_;
  std::unique_ptr<World> world_;
  std::unique_ptr<Renderer> renderer_;
  std::unique_ptr<LensMapping> lens_;      // null: the render is the image
  RenderedFrame canvas_;                   // the render a lens resamples
  std::vector<cv::Mat> subframe_buffers_;  // the motion field's sub-frames, reused
  std::unique_ptr<CameraMotion> motion_;
  std::vector<std::pair<double, double>> stamps_;
  std::vector<const Instance*> tracked_;            // pushables and actors
  std::vector<std::vector<Pose>> previous_bodies_;  // per tracked instance
  std::vector<uint16_t> tracked_body_instance_;     // instance id of each tracked body, in order
  int next_ = 0;
  ShutterTiming shutter_;  // inactive for an ideal sensor
  ExposureControl exposure_control_;
  double depth_offset_ = 0;            // s, the depth camera's instant (0 for an ideal sensor)
  double last_body_speed_ = 0;         // m/s, fastest tracked body over the last frame
  std::vector<int> lamp_lights_;       // per scenario lamp, the model light it drives
  std::vector<WallOpening> openings_;  // doorways to daylight (sim/sensor/daylight.h)
  cv::Mat pixel_rays_;                 // the output pixels' rays, when there are openings

  // Sets the renderer's lamps to their levels at `since_first` seconds.
  void light_lamps(double since_first);
  // Whether any lamp's level changes between the two instants.
  bool lamps_change(double t0, double t1) const;

  // The dataset camera's images of the world's current state.
  void render(RenderedFrame& out, RenderTimings* timings);
  void render_colour(cv::Mat& bgr, RenderTimings* timings);
  bool advance(RenderedFrame* frame, FrameTruth& truth, SequenceTimings* timings);
  // The colour sub-frames at `offsets` by the motion field
  // (sim/sensor/motion_field.h) from the render at offset 0 (`stamp`, the
  // canvas when a lens resamples) and the camera and bodies at each offset.
  void synthesise_subframes(const RenderedFrame& stamp, const std::vector<double>& offsets,
                            const std::vector<Pose>& cameras,
                            const std::vector<std::vector<Pose>>& bodies,
                            std::vector<cv::Mat>& colours);
  // Every body of the tracked instances now, in one order.
  void tracked_body_poses(std::vector<Pose>& out) const;
  // Largest image motion (px) expected over the shutter's span at t_rgb.
  double image_motion_over_span(double t_rgb) const;
  void record_truth(const Pose& world_camera, double t_rgb, double t_depth, bool covered,
                    FrameTruth& truth);
  // The capture's exposure and light (and `daylight`, the radiance through
  // openings); meters `bgr` for the next frame.
  ColourCapture expose(const cv::Mat* bgr, double since_first, const cv::Mat& daylight);
  // Shows daylight through the openings in the finished frame: its colour
  // and labels from the render at the timestamp, the depth camera's own
  // image (`own_depth`, when it has its own instant) from that image at its
  // instant. Returns the radiance for the colour pipeline.
  cv::Mat let_in_daylight(RenderedFrame& frame, cv::Mat* own_depth, double t_rgb,
                          double since_first) const;
};

}  // namespace depot::sim
