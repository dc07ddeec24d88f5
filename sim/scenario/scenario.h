#pragma once
// A scenario: everything needed to render one dataset, as plain data.
// Loaded and validated from YAML by scenario_loader.h; nothing here renders.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/lens_model.h"
#include "sim/scenario/camera_cover.h"
#include "sim/scenario/path.h"
#include "sim/scenario/procedural_hall.h"
#include "sim/scenario/scene_layout.h"

namespace depot::sim {

struct CameraIntrinsics {
  int width = 640;
  int height = 480;
  double f = 539.2;  // fx, pixels
  // fy; 0 = square pixels (fy = f). MuJoCo 2.2 renders square pixels only,
  // so other values are made by resampling (sim/sensor/lens.h).
  double fy = 0.0;
  double focal_y() const { return fy > 0 ? fy : f; }
  double cx = 320.1;
  double cy = 247.6;
  double depth_factor = 5000.0;  // PNG value per metre
};

struct CameraMotionSpec {
  std::string type = "static";          // xyz, halfsphere, rpy, static, waypoints, file
  Eigen::Vector3d position{0, 0, 1.3};  // base position (or half-sphere centre)
  Eigen::Vector3d look_at{0, 1, 1.3};
  double amplitude = 0.0;  // xyz: m; rpy: deg; halfsphere: radius m (0 = type default)
  double period = 0.0;     // s (0 = type default)
  double tremor = 1.0;     // scale of hand tremor (0 = none)
  // waypoints: `path`, or `route`, one of the hall's named routes
  // (SceneLayout::routes), which then fills `path`.
  std::vector<Eigen::Vector2d> path;
  std::string route;
  double height = 1.0;
  double speed = 0.5;
  double pitch_deg = 8.0;  // downward tilt of a robot camera
  bool loop = true;
  // file
  std::string file;               // TUM trajectory, resolved path
  bool anchor_first_pose = true;  // place the first pose at position/look_at
  // Least distance (m) from the camera to static scene geometry at any frame;
  // negative = the sensor's min_depth. Closer frames are refused unless
  // allow_close (then warned about). See sim/world/camera_clearance.h.
  double clearance = -1.0;
  bool allow_close = false;
};

struct TimestampSpec {
  double rate = 30.0;
  double start = 1700000000.0;
  std::string file;  // TUM list/association/trajectory; resolved path
  // A real driver's timing (generated timestamps only): each capture is
  // late or early by a seeded normal draw of this sigma (s, clipped to a
  // quarter period), and each frame is lost with this probability (the
  // world moves on; the frame is not written).
  double jitter = 0.0;
  double drop_rate = 0.0;
};

// The colour camera's lens (common/lens_model.h; images made by
// sim/sensor/lens.h), all zero = a pinhole.
using LensDistortion = LensCoefficients;

// The scene's light level over time (sim/sensor/light.h).
struct LightSpec {
  double level = 1.0;  // 1 = the scene as lit in its layout
  // [time s since the first frame, level] points, times ascending: the level
  // follows them linearly, held before the first and after the last (two
  // points at one time switch). Multiplies `level`. Empty = constant.
  std::vector<Eigen::Vector2d> events;
  // Mains flicker: the light swings by +-flicker around its level at twice
  // the mains frequency (a lamp on 50 Hz flickers at 100 Hz).
  double flicker = 0.0;
  double mains_hz = 50.0;

  bool constant() const { return level == 1.0 && events.empty() && flicker == 0.0; }
};

// Exposure time and gain under auto-exposure (sim/sensor/auto_exposure.h).
struct ExposureControlSpec {
  bool automatic = false;
  double target = 0.45;         // metered mean output brightness, 0..1 of full scale
  double time_constant = 0.25;  // s, of the loop's first-order response
  double max_exposure = 0.03;   // s, longest exposure before gain is raised
  double min_exposure = 1e-4;   // s
  double max_gain = 8.0;        // analogue gain at most
};

// Optics and the colour sensor's pipeline (sim/sensor/colour_pipeline.h).
struct ColourPipelineSpec {
  double vignetting = 1.0;  // relative illumination at the image's corners (1 = none)
  double lens_blur = 0.0;   // px, sigma of the lens's Gaussian point-spread function
  // Bayer mosaic and the driver's demosaicing: none, bilinear or edge_aware
  // (OpenCV's); `bayer` names the mosaic's top-left 2x2, row by row.
  std::string demosaic = "none";
  std::string bayer = "rggb";  // rggb, grbg, gbrg or bggr
  // Shot and read noise in electrons (full well at gain 1); 0 = the
  // additive `rgb_noise` sigma instead.
  double full_well = 0.0;
  double read_noise = 0.0;
  int jpeg_quality = 0;  // 0 = none, else as the driver's JPEG (1..100)

  bool any() const {
    return vignetting != 1.0 || lens_blur > 0 || demosaic != "none" || full_well > 0 ||
           jpeg_quality > 0;
  }
};

struct SensorSpec {
  bool ideal = false;
  double min_depth = 0.4;
  double max_depth = 4.5;
  double disparity_noise = 0.07;  // px, Kinect-like (noise grows with depth^2)
  double disparity_step = 0.125;  // px quantisation
  double baseline = 0.075;        // m, projector to IR camera (edge shadows)
  double rgb_noise = 2.0;         // grey levels (sigma)
  // The colour camera's shutter (sim/sensor/shutter.h states which instant
  // each row, the depth and the truth belong to): 0 = instant and global.
  double exposure = 0.0;   // s, each row's integration time
  double readout = 0.0;    // s, first row to last (rolling shutter)
  int max_subframes = 15;  // sub-frames per frame at most while either is set
  // How the sub-frames are made: "subframes" renders each (the reference),
  // "field" moves the timestamp's one render along the exact per-pixel
  // motion (sim/sensor/motion_field.h).
  std::string motion_blur = "subframes";
  // Depth artefacts (sim/sensor/depth_artefacts.h), 0 = none.
  double flying_pixels = 0.0;  // share of depth-edge pixels given a mixed depth
  double dark_dropout = 0.0;   // chance of no depth on a black surface (none from grey 64)
  Eigen::Vector2d misregistration{0.0, 0.0};  // px, depth image shifted against colour
  // s: the depth camera's clock runs this far from the colour camera's; the
  // depth image is rendered at its own timestamp (generated timestamps only).
  double depth_offset = 0.0;
  // The colour camera's lens distortion; depth is registered to the colour
  // camera, so it and the labels share it.
  LensDistortion lens;
  // Light, exposure control and the colour pipeline: all off by default, and
  // then the colour image is the render plus `rgb_noise` as before.
  LightSpec light;
  ExposureControlSpec exposure_control;
  ColourPipelineSpec colour;

  bool forms_colour() const {
    return !ideal && (!light.constant() || exposure_control.automatic || colour.any());
  }
  // The longest exposure a frame can have (the shutter's span).
  double longest_exposure() const {
    return exposure_control.automatic ? exposure_control.max_exposure : exposure;
  }
};

// One sample of a walker's simulated track (crowds, sim/actors/crowd.h).
struct TrackPoint {
  double t = 0;  // s since the first frame
  Eigen::Vector2d xy{0, 0};
  double heading = 0;  // rad
  double walked = 0;   // m walked since the start (drives the gait)
};

// `crowds`: groups of walkers moving between goals in an area, avoiding
// each other and the static scene (sim/actors/crowd.h).
struct CrowdSpec {
  std::string name;                       // its walkers are <name>_1 .. <name>_N
  int count = 10;                         // walkers at dynamic load 1 (scaled by the load)
  Eigen::Vector2d lo{0, 0}, hi{0, 0};     // the area, hall coordinates
  double speed_lo = 0.9, speed_hi = 1.4;  // m/s, drawn per walker
  // "ends": to and fro between the area's two short ends (a busy aisle);
  // "anywhere": to goals anywhere in it.
  std::string goals = "ends";
  std::string where;  // its entry (file:line), for errors found later
};

// `doors`: hinged doors that swing open and shut (sim/actors/door.h).
struct DoorSpec {
  std::string name;
  Eigen::Vector2d hinge{0, 0};       // m, hall coordinates: the hinge's foot
  double yaw_deg = 0.0;              // the shut leaf's direction from the hinge
  double width = 1.0, height = 2.1;  // m
  double swing_deg = 90.0;           // open angle, counter-clockwise seen from above
  // [time s, share open 0..1], times ascending, linear between. Empty: seeded
  // timing, shut for a time drawn in `shut`, then open for one drawn in
  // `open` (s), and again; each swing takes kDoorSwing s.
  std::vector<Eigen::Vector2d> events;
  Eigen::Vector2d shut{3.0, 6.0}, open{2.0, 4.0};
  std::string where;  // its entry (file:line), for errors found later
};

struct ActorSpec {
  std::string name;
  std::string type;  // human, dog, cat, pig, bird, chair, cart
  std::string
      action;  // walk, sit, push, carry, crowd (human); walk/fly (animals); "" for pushables
  std::vector<Eigen::Vector2d> path;
  std::string route;  // one of the hall's named routes, which then fills `path`
  bool loop = true;   // closed path; otherwise out and back
  double speed = 1.0;
  double start_offset = 0.0;  // metres along the path at t = 0
  double start_time = 0.0;    // s before it starts moving
  double size = 1.0;
  Eigen::Vector2d position{0, 0};
  double yaw_deg = 0.0;
  std::string target;  // push: pushable name; sit: chair name
  // carry: the goods a person carries out and back along its path
  // (sim/actors/carry.h): crate or sack, resting pick_height / put_height m
  // up at the path's start and end.
  std::string carries;  // forklift: pallet
  double pick_height = 0.0, put_height = 0.0;
  // crowd: the walker's simulated track (action "crowd"), sampled evenly.
  std::vector<TrackPoint> track;
  double height = 0.0;  // bird flight height
  uint64_t appearance = 0;
  bool fixed_appearance = false;  // `appearance` written in the file (not drawn from the seed)
  // Drawn from the world seed (sim/actors/actor_variation.h); zero as written.
  LaneOffset lane;          // sideways shift of the path within its lane
  double gait_phase = 0.0;  // rad, phase of the walking cycle at the start
};

struct Scenario {
  std::string name;
  std::string description;
  std::string source_path;  // the YAML file
  // The hall: `scene:` names a layout file (default scenes/depot.yaml), or
  // is `procedural` (then `hall:` holds the generator's parameters and the
  // world seed draws the hall: sim/scenario/procedural_hall.h).
  SceneLayout layout;
  std::optional<ProceduralHallSpec> procedural;
  std::string classes_path;
  // Asset catalogue the mesh style draws from (assets/catalog.yaml form).
  std::string asset_catalog_path;
  uint64_t seed = 1;
  // `seed_world`: fixes the world (scene fill, textures, actor timing, lanes
  // and variants) independently of `seed`; unset, the seed draws both.
  std::optional<uint64_t> seed_world;
  uint64_t world_seed() const { return seed_world ? *seed_world : seed; }
  int frames = 300;
  bool shadows = false;
  double dynamic_load = 1.0;
  // How living actors are drawn: "mesh" (skinned catalogue models,
  // asset_catalog_path; a class without a model stays primitive) or
  // "primitive" (rigid boxes and capsules). Scenario files default to mesh.
  std::string actors_style = "mesh";
  // How furniture props are drawn: "mesh" (catalogue models: the office
  // chair for pushable chairs, desk/table for desks; physics keeps the
  // primitives) or "primitive". The key `style` sets both.
  std::string props_style = "mesh";
  CameraIntrinsics camera;
  CameraMotionSpec motion;
  TimestampSpec timestamps;
  SensorSpec sensor;
  // `camera_cover`: when the camera sees nothing (sim/scenario/camera_cover.h).
  std::vector<CoverInterval> camera_cover;
  // `lamps`: ceiling lights switched or dimmed on their own (light that
  // differs by place, unlike the sensor's `light`, which scales the whole
  // hall). Each is the scene layout's light nearest `near`; its level
  // follows `events` as `light_events` do (sim/sensor/light.h), and the
  // renderer lights the scene with it, so only what that lamp lit changes.
  struct Lamp {
    Eigen::Vector2d near{0, 0};  // m, hall coordinates
    LightSpec level;             // events only (level 1, no flicker)
  };
  std::vector<Lamp> lamps;
  // `openings`: doorways in the hall's walls to bright daylight (a depot's
  // roller door), sim/sensor/daylight.h. While open (from the floor up, by
  // the share its events give) the outside shows through at `radiance`
  // times the render's white under light 1: it saturates, auto-exposure
  // answers it, and the depth camera gets no return there.
  struct Opening {
    Eigen::Vector2d centre{0, 0};  // m, hall coordinates: a point on a wall's foot
    double width = 3.0;            // m, along the wall
    double height = 3.0;           // m, from the floor
    double radiance = 20.0;        // x the render's white under light 1
    LightSpec open;                // events: [time, share open 0..1]; level 1
    std::string where;             // its entry (file:line), for errors found later
  };
  std::vector<Opening> openings;
  std::vector<CrowdSpec> crowds;  // walkers simulated when the world is built
  std::vector<DoorSpec> doors;
  std::vector<ActorSpec> written_actors;  // as in the file
  std::vector<ActorSpec> actors;          // after dynamic-load scaling
};

// Resizes the image to `width` (height keeps the aspect ratio), scaling the
// intrinsics consistently (pixel centres at integer coordinates).
void scale_camera(CameraIntrinsics& camera, int width);

bool is_living_actor(const std::string& type);    // human and animals
bool is_pushable_actor(const std::string& type);  // chair, cart
bool is_vehicle_actor(const std::string& type);   // forklift

}  // namespace depot::sim
