#include "sim/scenario/scenario_loader.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <set>
#include <sstream>

#include "common/config_path.h"
#include "common/error.h"
#include "common/image_size.h"
#include "common/yaml_fields.h"
#include "common/yaml_file.h"

namespace fs = std::filesystem;

namespace depot::sim {

bool is_living_actor(const std::string& type) {
  return type == "human" || type == "dog" || type == "cat" || type == "pig" || type == "bird";
}
bool is_pushable_actor(const std::string& type) {
  return type == "chair" || type == "cart";
}
bool is_vehicle_actor(const std::string& type) {
  return type == "forklift";
}

void scale_camera(CameraIntrinsics& c, int width) {
  const double s = static_cast<double>(width) / c.width;
  check_image_size(width, static_cast<int>(std::lround(c.height * s)),
                   "--width " + std::to_string(width));
  c.height = static_cast<int>(std::lround(c.height * s));
  c.width = width;
  c.f *= s;
  c.fy *= s;  // 0 (square pixels) stays 0
  c.cx = (c.cx + 0.5) * s - 0.5;
  c.cy = (c.cy + 0.5) * s - 0.5;
}

namespace {

using Source = YamlSource;

// A scenario's maps (common/yaml_fields.h) with its two own kinds of field:
// a ground path and a file that must exist.
class Fields : public YamlFields {
 public:
  using YamlFields::YamlFields;

  std::vector<Eigen::Vector2d> path(const char* key) const {
    YAML::Node n = node(key);
    std::vector<Eigen::Vector2d> out;
    if (!n) return out;
    if (!n.IsSequence()) fail(where(n), "'" + std::string(key) + "' must be a list of [x, y]");
    for (const auto& p : n) {
      std::vector<double> v;
      try {
        v = p.as<std::vector<double>>();
      } catch (const YAML::Exception&) {
        fail(where(p), "path point must be [x, y]");
      }
      if (v.size() != 2 || !std::isfinite(v[0]) || !std::isfinite(v[1]))
        fail(where(p), "path point must be [x, y]");
      out.emplace_back(v[0], v[1]);
    }
    return out;
  }
  // A path relative to the scenario's folder (or to the shared data,
  // common/config_path.h), which must exist.
  std::string existing_file(const char* key) const {
    YAML::Node n = node(key);
    if (!n) return "";
    const std::string value = str(key);
    const std::string p =
        resolve_config_path(value, fs::path(source().file).parent_path().string());
    std::error_code ec;
    if (!fs::is_regular_file(p, ec))
      fail(where(n), "file '" + value + "' not found (" + p +
                         (names_shared_data(value) || fs::path(value).is_absolute()
                              ? ""
                              : ", relative to the scenario's folder") +
                         ")" +
                         (names_shared_data(value) ? "; set " + std::string(kSharedDataVariable) +
                                                         " to the shared data folder"
                                                   : ""));
    return p;
  }
};

const std::set<std::string> kMotionTypes = {"xyz",    "halfsphere", "rpy",
                                            "static", "waypoints",  "file"};

void read_camera(const Fields& f, CameraIntrinsics& cam) {
  f.allow_only({"width", "height", "f", "fy", "cx", "cy", "depth_factor"});
  cam.width = static_cast<int>(f.number("width", cam.width, kMinImageSide, kMaxImageSide));
  cam.height = static_cast<int>(f.number("height", cam.height, kMinImageSide, kMaxImageSide));
  // Scale the default principal point and focal length with the image size.
  double sx = cam.width / 640.0;
  cam.f = f.number("f", 539.2 * sx, 1.0, 1e5);
  if (f.has("fy")) cam.fy = f.number("fy", cam.f, 1.0, 1e5);
  cam.cx = f.number("cx", 320.1 * sx, 0.0, cam.width);
  cam.cy = f.number("cy", 247.6 * cam.height / 480.0, 0.0, cam.height);
  cam.depth_factor = f.number("depth_factor", cam.depth_factor, 1.0, 1e5);
}

void read_motion(const Fields& f, CameraMotionSpec& m) {
  f.allow_only({"type", "position", "look_at", "amplitude", "period", "tremor", "path", "route",
                "height", "speed", "pitch_deg", "loop", "file", "anchor_first_pose", "clearance",
                "allow_close"});
  m.type = f.str("type", "static");
  if (!kMotionTypes.count(m.type))
    fail(f.where(f.node("type")), "unknown camera motion '" + m.type +
                                      "' (expected xyz, halfsphere, rpy, static, waypoints, file)");
  m.position = f.vec3("position", m.position);
  m.look_at = f.vec3("look_at", m.look_at);
  if ((m.look_at - m.position).norm() < 1e-3 && m.type != "waypoints")
    fail(f.where(), "camera look_at must differ from position");
  m.amplitude = f.number("amplitude", 0.0, 0.0, 90.0);
  m.period = f.number("period", 0.0, 0.0, 1000.0);
  m.tremor = f.number("tremor", 1.0, 0.0, 10.0);
  m.path = f.path("path");
  m.route = f.str("route");
  if (!m.route.empty() && m.type != "waypoints")
    fail(f.where(f.node("route")), "a 'route' is followed by waypoints motion only");
  if (!m.route.empty() && !m.path.empty())
    fail(f.where(f.node("route")), "motion takes a 'path' or a 'route', not both");
  m.height = f.number("height", m.height, 0.05, 4.0);
  m.speed = f.number("speed", m.speed, 0.01, 3.0);
  m.pitch_deg = f.number("pitch_deg", m.pitch_deg, -60.0, 60.0);
  m.loop = f.get<bool>("loop", true);
  m.file = f.existing_file("file");
  m.anchor_first_pose = f.get<bool>("anchor_first_pose", true);
  if (f.has("clearance")) m.clearance = f.number("clearance", 0.0, 0.0, 10.0);
  m.allow_close = f.get<bool>("allow_close", false);
  if (m.type == "waypoints" && m.path.size() < 2 && m.route.empty())
    fail(f.where(), "waypoints motion needs a 'path' of at least two points or a 'route'");
  if (m.type == "file" && m.file.empty()) fail(f.where(), "file motion needs 'file'");
}

void read_timestamps(const Fields& f, TimestampSpec& t) {
  f.allow_only({"rate", "start", "file", "jitter", "drop_rate"});
  t.rate = f.number("rate", t.rate, 0.1, 1000.0);
  t.start = f.number("start", t.start, 0.0, 1e11);
  t.file = f.existing_file("file");
  t.jitter = f.number("jitter", t.jitter, 0.0, 0.1);
  t.drop_rate = f.number("drop_rate", t.drop_rate, 0.0, 0.9);
  if (!t.file.empty() && (t.jitter > 0 || t.drop_rate > 0))
    fail(f.where(f.node(t.jitter > 0 ? "jitter" : "drop_rate")),
         "jitter and drop_rate apply to generated timestamps, not to a timestamps file (its "
         "times are a real driver's already)");
}

// Events [time, value], times ascending, each value within [0, most]. The
// errors name an event `event` ("a light event must be [time, level]") and
// its value `value` ("a light level must be within [0, 10]").
std::vector<Eigen::Vector2d> read_events(const Fields& f, const char* key, const std::string& event,
                                         const std::string& value, const std::string& value_name,
                                         double most) {
  const YAML::Node n = f.node(key);
  if (!n.IsSequence())
    fail(f.where(n), "'" + std::string(key) + "' must be a list of [time, " + value_name + "]");
  std::vector<Eigen::Vector2d> events;
  for (const auto& e : n) {
    std::vector<double> v;
    try {
      v = e.as<std::vector<double>>();
    } catch (const YAML::Exception&) {
    }
    if (v.size() != 2 || !std::isfinite(v[0]) || !std::isfinite(v[1]))
      fail(f.where(e), event + " must be [time, " + value_name + "]");
    if (v[1] < 0 || v[1] > most) {
      std::ostringstream bound;
      bound << most;  // 10, 1: as the bound reads
      fail(f.where(e), value + " must be within [0, " + bound.str() + "]");
    }
    if (!events.empty() && v[0] < events.back().x())
      fail(f.where(e), std::string(key) + " must be in time order");
    events.emplace_back(v[0], v[1]);
  }
  return events;
}

// `light_events: [[t, level], ...]` (or a lamp's `events`), times ascending.
std::vector<Eigen::Vector2d> read_light_events(const Fields& f, const char* key = "light_events") {
  return read_events(f, key, "a light event", "a light level", "level", 10.0);
}

void read_light_and_colour(const Fields& f, SensorSpec& s) {
  LightSpec& l = s.light;
  l.level = f.number("light", l.level, 0.0, 10.0);
  if (f.has("light_events")) l.events = read_light_events(f);
  l.flicker = f.number("flicker", l.flicker, 0.0, 1.0);
  l.mains_hz = f.number("mains", l.mains_hz, 1.0, 1000.0);
  ExposureControlSpec& e = s.exposure_control;
  e.automatic = f.get<bool>("auto_exposure", e.automatic);
  e.target = f.number("ae_target", e.target, 0.05, 0.95);
  e.time_constant = f.number("ae_time_constant", e.time_constant, 0.001, 10.0);
  e.max_exposure = f.number("max_exposure", e.max_exposure, 1e-4, 0.5);
  e.max_gain = f.number("max_gain", e.max_gain, 1.0, 64.0);
  ColourPipelineSpec& c = s.colour;
  c.vignetting = f.number("vignetting", c.vignetting, 0.05, 1.0);
  c.lens_blur = f.number("lens_blur", c.lens_blur, 0.0, 10.0);
  c.demosaic = f.str("demosaic", c.demosaic);
  if (c.demosaic != "none" && c.demosaic != "bilinear" && c.demosaic != "edge_aware")
    fail(f.where(f.node("demosaic")), "unknown demosaic '" + printable(c.demosaic) +
                                          "' (expected none, bilinear or edge_aware)");
  c.bayer = f.str("bayer", c.bayer);
  if (c.bayer != "rggb" && c.bayer != "grbg" && c.bayer != "gbrg" && c.bayer != "bggr")
    fail(f.where(f.node("bayer")),
         "unknown bayer pattern '" + printable(c.bayer) + "' (expected rggb, grbg, gbrg or bggr)");
  c.full_well = f.number("full_well", c.full_well, 0.0, 1e6);
  if (c.full_well > 0 && c.full_well < 100)
    fail(f.where(f.node("full_well")),
         "'full_well' must be 0 (no sensor noise model) or at least "
         "100 electrons");
  c.read_noise = f.number("read_noise", c.read_noise, 0.0, 1000.0);
  c.jpeg_quality = static_cast<int>(f.number("jpeg_quality", c.jpeg_quality, 0, 100));
}

const std::initializer_list<const char*> kSensorKeys = {"model",
                                                        "profile",
                                                        "min_depth",
                                                        "max_depth",
                                                        "disparity_noise",
                                                        "disparity_step",
                                                        "baseline",
                                                        "rgb_noise",
                                                        "exposure",
                                                        "readout",
                                                        "max_subframes",
                                                        "motion_blur",
                                                        "flying_pixels",
                                                        "dark_dropout",
                                                        "misregistration",
                                                        "depth_offset",
                                                        "k1",
                                                        "k2",
                                                        "p1",
                                                        "p2",
                                                        "k3",
                                                        "light",
                                                        "light_events",
                                                        "flicker",
                                                        "mains",
                                                        "auto_exposure",
                                                        "ae_target",
                                                        "ae_time_constant",
                                                        "max_exposure",
                                                        "max_gain",
                                                        "vignetting",
                                                        "lens_blur",
                                                        "demosaic",
                                                        "bayer",
                                                        "full_well",
                                                        "read_noise",
                                                        "jpeg_quality"};

void read_sensor_keys(const Fields& f, SensorSpec& s);

// `profile: NAME` (scenarios/sensors/NAME.yaml) or a YAML file: a real
// camera's sensor keys, read first; the scenario's own keys override them.
void read_sensor_profile(const Fields& f, SensorSpec& s) {
  const std::string value = f.str("profile");
  const bool is_file =
      value.find('/') != std::string::npos || fs::path(value).extension() == ".yaml";
  const std::string path =
      is_file ? f.existing_file("profile") : project_file("scenarios/sensors/" + value + ".yaml");
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    fail(f.where(f.node("profile")),
         "unknown sensor profile '" + printable(value) + "' (no " + path + ")");
  const YAML::Node root = load_yaml_file(path, "sensor profile");
  const Source source{path, {}};
  Fields top(root, source, "sensor profile");
  top.allow_only({"sensor"});
  if (!top.has("sensor")) fail(path, "a sensor profile is a 'sensor:' map");
  Fields profile(top.node("sensor"), source, "sensor");
  if (profile.has("profile"))
    fail(profile.where(profile.node("profile")), "a profile cannot name another profile");
  read_sensor_keys(profile, s);
}

void read_sensor(const Fields& f, SensorSpec& s) {
  if (f.has("profile")) read_sensor_profile(f, s);
  read_sensor_keys(f, s);
}

void read_sensor_keys(const Fields& f, SensorSpec& s) {
  f.allow_only(kSensorKeys);
  std::string model = f.str("model", "kinect");
  if (model != "kinect" && model != "ideal")
    fail(f.where(f.node("model")),
         "unknown sensor model '" + model + "' (expected kinect or ideal)");
  s.ideal = model == "ideal";
  s.min_depth = f.number("min_depth", s.min_depth, 0.0, 10.0);
  s.max_depth = f.number("max_depth", s.max_depth, 0.5, 50.0);
  s.disparity_noise = f.number("disparity_noise", s.disparity_noise, 0.0, 5.0);
  s.disparity_step = f.number("disparity_step", s.disparity_step, 0.0, 2.0);
  s.baseline = f.number("baseline", s.baseline, 0.0, 1.0);
  s.rgb_noise = f.number("rgb_noise", s.rgb_noise, 0.0, 50.0);
  if (s.min_depth >= s.max_depth) fail(f.where(), "sensor min_depth must be below max_depth");
  s.exposure = f.number("exposure", s.exposure, 0.0, 0.5);
  s.readout = f.number("readout", s.readout, 0.0, 0.5);
  s.max_subframes = static_cast<int>(f.number("max_subframes", s.max_subframes, 3, 99));
  s.motion_blur = f.str("motion_blur", s.motion_blur);
  if (s.motion_blur != "subframes" && s.motion_blur != "field")
    fail(f.where(f.node("motion_blur")),
         "unknown motion_blur '" + printable(s.motion_blur) + "' (expected subframes or field)");
  s.flying_pixels = f.number("flying_pixels", s.flying_pixels, 0.0, 1.0);
  s.dark_dropout = f.number("dark_dropout", s.dark_dropout, 0.0, 1.0);
  s.misregistration = f.vec2("misregistration", s.misregistration);
  if (s.misregistration.cwiseAbs().maxCoeff() > 50)
    fail(f.where(f.node("misregistration")), "'misregistration' must be within 50 px");
  s.depth_offset = f.number("depth_offset", s.depth_offset, -0.1, 0.1);
  // Whether the lens folds the image is checked where the sequence is made
  // (sim/sensor/lens.h), before anything is rendered.
  s.lens.k1 = f.number("k1", s.lens.k1, -1.0, 1.0);
  s.lens.k2 = f.number("k2", s.lens.k2, -1.0, 1.0);
  s.lens.p1 = f.number("p1", s.lens.p1, -0.1, 0.1);
  s.lens.p2 = f.number("p2", s.lens.p2, -0.1, 0.1);
  s.lens.k3 = f.number("k3", s.lens.k3, -1.0, 1.0);
  read_light_and_colour(f, s);
  if (s.exposure_control.automatic && !s.ideal) {
    if (s.exposure <= 0)
      fail(f.where(f.node("auto_exposure")),
           "auto_exposure starts from the sensor's 'exposure' (the exposure the render stands "
           "for): set exposure > 0");
    if (s.exposure > s.exposure_control.max_exposure)
      fail(f.where(f.node("exposure") ? f.node("exposure") : f.node("auto_exposure")),
           "sensor exposure = " + std::to_string(s.exposure) + " s is longer than max_exposure = " +
               std::to_string(s.exposure_control.max_exposure) + " s");
  }
}

std::string format_ms(double seconds) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(1) << seconds * 1e3 << " ms";
  return o.str();
}

std::string format_hz(double rate) {
  std::ostringstream o;
  o << rate << " Hz";
  return o.str();
}

// A row's exposure may not reach into the next frame's: the world is
// rendered forward in time, one frame after the other.
void check_shutter_fits_frame(const Fields& top, const Scenario& s) {
  const YAML::Node n = top.node("sensor");
  // The depth camera's own instant stays within its frame's slot, beside
  // the colour camera's.
  if (n["depth_offset"] && !s.timestamps.file.empty() && s.sensor.depth_offset != 0)
    fail(top.where(n["depth_offset"]),
         "depth_offset applies to generated timestamps (a timestamps file gives the depth "
         "stamps itself)");
  if (std::abs(s.sensor.depth_offset) > 0.25 / s.timestamps.rate)
    fail(top.where(n["depth_offset"]), "sensor depth_offset = " + format_ms(s.sensor.depth_offset) +
                                           " is more than a quarter frame (" +
                                           format_ms(0.25 / s.timestamps.rate) + ")");
  if (!s.timestamps.file.empty()) return;
  // A row integrates once per frame and the rows are read out once per
  // frame; together they may span more than a frame (the world is then
  // stepped again from a saved state).
  const double period = 1.0 / s.timestamps.rate;
  const bool automatic = s.sensor.exposure_control.automatic;
  const char* key = automatic ? "max_exposure" : "exposure";
  for (const auto& [name, value] :
       {std::pair<const char*, double>{key, s.sensor.longest_exposure()},
        std::pair<const char*, double>{"readout", s.sensor.readout}}) {
    if (value <= period + 1e-12) continue;
    fail(top.where(n[name] ? n[name] : n),
         std::string("sensor ") + name + " = " + format_ms(value) + " is longer than a frame (" +
             format_ms(period) + " at " + format_hz(s.timestamps.rate) + ")");
  }
}

// `lamps: [{near: [x, y], events: [[t, level], ...]}, ...]`.
// `doors:` entries (sim/actors/door.h).
std::vector<DoorSpec> read_doors(const Fields& top, const Source& source) {
  const YAML::Node n = top.node("doors");
  if (!n.IsSequence())
    fail(top.where(n),
         "'doors' must be a list of {name, hinge, yaw_deg, width, height, "
         "swing_deg, events | shut, open}");
  std::vector<DoorSpec> doors;
  for (const auto& node : n) {
    Fields f(node, source, "a door");
    f.allow_only(
        {"name", "hinge", "yaw_deg", "width", "height", "swing_deg", "events", "shut", "open"});
    DoorSpec d;
    d.where = f.where();
    d.name = f.str("name", "door_" + std::to_string(doors.size() + 1));
    if (!f.has("hinge")) fail(d.where, "door '" + d.name + "' needs 'hinge: [x, y]'");
    d.hinge = f.vec2("hinge", d.hinge);
    d.yaw_deg = f.number("yaw_deg", d.yaw_deg, -360.0, 360.0);
    d.width = f.number("width", d.width, 0.4, 4.0);
    d.height = f.number("height", d.height, 1.0, 4.0);
    d.swing_deg = f.number("swing_deg", d.swing_deg, -180.0, 180.0);
    if (f.has("events")) {
      if (f.has("shut") || f.has("open"))
        fail(f.where(f.node("events")),
             "door '" + d.name + "' takes 'events' or seeded 'shut' and 'open' times, not both");
      d.events = read_events(f, "events", "a door event", "a door's share open", "share", 1.0);
      if (d.events.empty()) fail(f.where(f.node("events")), "door '" + d.name + "': no events");
    }
    for (const char* key : {"shut", "open"}) {
      Eigen::Vector2d& r = std::string(key) == "shut" ? d.shut : d.open;
      r = f.vec2(key, r);
      if (!(r.x() >= 0.2 && r.x() <= r.y() && r.y() <= 600))
        fail(f.where(f.node(key)),
             "door '" + d.name + "': '" + key + "' must be [low, high] s within [0.2, 600]");
    }
    doors.push_back(d);
  }
  return doors;
}

// `crowds:` entries (sim/actors/crowd.h simulates them with the world).
std::vector<CrowdSpec> read_crowds(const Fields& top, const Source& source) {
  const YAML::Node n = top.node("crowds");
  if (!n.IsSequence())
    fail(top.where(n), "'crowds' must be a list of {name, count, area, speed, goals}");
  std::vector<CrowdSpec> crowds;
  for (const auto& node : n) {
    Fields f(node, source, "a crowd");
    f.allow_only({"name", "count", "area", "speed", "goals"});
    CrowdSpec c;
    c.where = f.where();
    c.name = f.str("name", "crowd_" + std::to_string(crowds.size() + 1));
    c.count = f.number<int>("count", c.count, 1, 200);
    const std::vector<Eigen::Vector2d> area = f.path("area");
    if (area.size() != 2 || !(area[0].x() < area[1].x()) || !(area[0].y() < area[1].y()))
      fail(f.where(f.node("area")),
           "crowd '" + c.name + "': 'area' must be [[x_min, y_min], [x_max, y_max]]");
    c.lo = area[0], c.hi = area[1];
    if (f.has("speed")) {
      const Eigen::Vector2d v = f.vec2("speed", {c.speed_lo, c.speed_hi});
      if (!(v.x() >= 0.2 && v.x() <= v.y() && v.y() <= 2.5))
        fail(f.where(f.node("speed")),
             "crowd '" + c.name + "': 'speed' must be [low, high] m/s within [0.2, 2.5]");
      c.speed_lo = v.x(), c.speed_hi = v.y();
    }
    c.goals = f.str("goals", c.goals);
    if (c.goals != "ends" && c.goals != "anywhere")
      fail(f.where(f.node("goals")),
           "crowd '" + c.name + "': unknown goals '" + c.goals + "' (expected ends or anywhere)");
    crowds.push_back(c);
  }
  return crowds;
}

std::vector<Scenario::Lamp> read_lamps(const Fields& top, const Source& source) {
  const YAML::Node n = top.node("lamps");
  if (!n.IsSequence()) fail(top.where(n), "'lamps' must be a list of {near, events}");
  std::vector<Scenario::Lamp> lamps;
  for (const auto& node : n) {
    Fields f(node, source, "a lamp");
    f.allow_only({"near", "events"});
    if (!f.has("near") || !f.has("events"))
      fail(f.where(), "a lamp needs 'near: [x, y]' (which ceiling light) and 'events'");
    Scenario::Lamp lamp;
    lamp.near = f.vec2("near", lamp.near);
    lamp.level.events = read_light_events(f, "events");
    if (lamp.level.events.empty()) fail(f.where(f.node("events")), "a lamp's events are empty");
    lamps.push_back(lamp);
  }
  return lamps;
}

// `openings: [{centre: [x, y], width, height, radiance, events: [[t, open],
// ...]}, ...]`; whether the centre lies on a wall is checked against the
// scene's hall (sim/sensor/daylight.h place_openings).
std::vector<Scenario::Opening> read_openings(const Fields& top, const Source& source) {
  const YAML::Node n = top.node("openings");
  if (!n.IsSequence())
    fail(top.where(n), "'openings' must be a list of {centre, width, height, radiance, events}");
  std::vector<Scenario::Opening> openings;
  for (const auto& node : n) {
    Fields f(node, source, "an opening");
    f.allow_only({"centre", "width", "height", "radiance", "events"});
    if (!f.has("centre") || !f.has("events"))
      fail(f.where(), "an opening needs 'centre: [x, y]' (on a wall) and 'events' ([time, open])");
    Scenario::Opening o;
    o.where = f.where();
    o.centre = f.vec2("centre", o.centre);
    o.width = f.number("width", o.width, 0.1, 100.0);
    o.height = f.number("height", o.height, 0.1, 100.0);
    o.radiance = f.number("radiance", o.radiance, 1.0, 1e4);
    o.open.events =
        read_events(f, "events", "an opening's event", "the share of an opening open", "open", 1.0);
    if (o.open.events.empty()) fail(f.where(f.node("events")), "an opening's events are empty");
    openings.push_back(o);
  }
  return openings;
}

// `camera_cover: [[start, end], ...]`, seconds since the first frame. Every
// problem is one error naming the file, the line and the key.
std::vector<CoverInterval> read_camera_cover(const Fields& top, const Scenario& s) {
  const YAML::Node n = top.node("camera_cover");
  const std::string key = "'camera_cover'";
  if (!n.IsSequence())
    fail(top.where(n), key + " must be a list of [start, end] intervals in seconds");
  std::vector<CoverInterval> out;
  for (const auto& item : n) {
    std::vector<double> v;
    try {
      v = item.as<std::vector<double>>();
    } catch (const YAML::Exception&) {
      v.clear();
    }
    if (v.size() != 2)
      fail(top.where(item), key + " interval " + std::to_string(out.size() + 1) +
                                " must be [start, end] in seconds");
    out.push_back({v[0], v[1]});
  }
  // Generated timestamps fix the sequence's length; a timestamps file's is
  // only known when it is read (the frames are then bounded by it).
  const double duration = s.timestamps.file.empty() ? s.frames / s.timestamps.rate : 0.0;
  const std::string problem = camera_cover_problem(out, duration);
  if (!problem.empty()) fail(top.where(n), key + " " + problem);
  return out;
}

ActorSpec read_actor(const Fields& f, size_t index, uint64_t seed) {
  f.allow_only({"name", "type", "action", "path", "route", "loop", "speed", "start_offset",
                "start_time", "size", "position", "yaw_deg", "pushes", "sit_on", "carries",
                "pick_height", "put_height", "height", "appearance"});
  ActorSpec a;
  a.type = f.str("type");
  if (!is_living_actor(a.type) && !is_pushable_actor(a.type) && !is_vehicle_actor(a.type))
    fail(f.where(f.node("type") ? f.node("type") : YAML::Node()),
         "unknown actor type '" + a.type +
             "' (expected human, dog, cat, pig, bird, chair, cart, forklift)");
  a.name = f.str("name", a.type + "_" + std::to_string(index));
  a.path = f.path("path");
  a.route = f.str("route");
  if (!a.route.empty() && !a.path.empty())
    fail(f.where(f.node("route")), "actor '" + a.name + "' takes a 'path' or a 'route', not both");
  a.loop = f.get<bool>("loop", true);
  a.speed = f.number("speed", a.type == "human" ? 1.1 : 0.9, 0.0, 5.0);
  a.start_offset = f.number("start_offset", 0.0, 0.0, 1e4);
  a.start_time = f.number("start_time", 0.0, 0.0, 1e4);
  a.size = f.number("size", 1.0, 0.3, 3.0);
  a.position = f.vec2("position", a.position);
  a.yaw_deg = f.number("yaw_deg", 0.0, -720.0, 720.0);
  a.height = f.number("height", a.type == "bird" ? 1.6 : 0.0, 0.0, 4.0);
  a.appearance = f.get<uint64_t>("appearance", seed * 7919 + index);
  a.fixed_appearance = f.has("appearance");
  if (f.has("pushes")) {
    a.action = "push";
    a.target = f.str("pushes");
  } else if (f.has("sit_on")) {
    a.action = "sit";
    a.target = f.str("sit_on");
  } else if (f.has("carries")) {
    a.action = "carry";
    a.carries = f.str("carries");
    const bool forklift = a.type == "forklift";
    if (forklift ? a.carries != "pallet" : a.carries != "crate" && a.carries != "sack")
      fail(f.where(f.node("carries")), "actor '" + a.name + "' carries '" + a.carries +
                                           "' (expected " +
                                           (forklift ? "pallet" : "crate or sack") + ")");
    a.pick_height = f.number("pick_height", 0.0, 0.0, 2.0);
    a.put_height = f.number("put_height", 0.0, 0.0, 2.0);
    // Out and back: the goods go to the path's end and come back.
    if (f.has("loop") && a.loop)
      fail(f.where(f.node("loop")),
           "actor '" + a.name + "' carries its goods out and back: 'loop' must be false");
    a.loop = false;
  } else if (is_living_actor(a.type)) {
    a.action = f.str("action", a.type == "bird" ? "fly" : "walk");
  }
  if (a.action != "carry" && (f.has("pick_height") || f.has("put_height")))
    fail(f.where(f.node(f.has("pick_height") ? "pick_height" : "put_height")),
         "actor '" + a.name + "': pick_height and put_height go with 'carries'");
  static const std::set<std::string> kActions = {"walk", "fly", "sit", "push", "carry", ""};
  if (!kActions.count(a.action)) fail(f.where(), "unknown action '" + a.action + "'");
  if ((a.action == "push" || a.action == "sit" || (a.action == "carry" && a.type != "forklift")) &&
      a.type != "human")
    fail(f.where(), "only humans can " + a.action);
  if (is_vehicle_actor(a.type) && a.action != "carry")
    fail(f.where(), "forklift '" + a.name + "' needs 'carries: pallet' and a 'path'");
  if ((a.action == "walk" || a.action == "fly" || a.action == "push" || a.action == "carry") &&
      a.path.size() < 2 && a.route.empty())
    fail(f.where(), "actor '" + a.name + "' needs a 'path' of at least two points or a 'route'");
  return a;
}

// `hall:` of a procedural scene: each key a number or [low, high].
ProceduralHallSpec read_procedural_hall(const Fields& f) {
  f.allow_only({"length", "width", "height", "rack_rows", "aisle_width", "rack_length",
                "rack_levels", "cross_aisle", "clutter", "robot_width"});
  ProceduralHallSpec spec;
  spec.where = f.where();
  auto range = [&](const char* key, HallRange& r) {
    const YAML::Node n = f.node(key);
    r.where = f.where(n);
    if (!n) return;
    std::vector<double> v;
    try {
      v = n.IsSequence() ? n.as<std::vector<double>>() : std::vector<double>{n.as<double>()};
    } catch (const YAML::Exception&) {
      v.clear();
    }
    if (v.size() == 1) v.push_back(v[0]);
    if (v.size() != 2)
      fail(r.where, "hall." + std::string(key) + " must be a number or a range [low, high]");
    r.low = v[0], r.high = v[1];
  };
  range("length", spec.length);
  range("width", spec.width);
  range("height", spec.height);
  range("rack_rows", spec.rack_rows);
  range("aisle_width", spec.aisle_width);
  range("rack_length", spec.rack_length);
  range("rack_levels", spec.rack_levels);
  range("cross_aisle", spec.cross_aisle);
  range("clutter", spec.clutter);
  spec.robot_width = f.get<double>("robot_width", spec.robot_width);
  spec.robot_width_where = f.where(f.node("robot_width"));
  check_procedural_hall(spec);
  return spec;
}

// The hall's route a motion or actor names, or one error line listing the
// routes this hall has.
const std::vector<Eigen::Vector2d>& route_of(const Scenario& s, const std::string& route,
                                             const std::string& who) {
  const auto it = s.layout.routes.find(route);
  if (it != s.layout.routes.end()) return it->second;
  std::string names;
  for (const auto& [name, points] : s.layout.routes) names += (names.empty() ? "" : ", ") + name;
  fail(s.source_path, who + " follows route '" + route + "', which " + s.layout.path +
                          (names.empty() ? " does not have (it has no routes)"
                                         : " does not have (its routes: " + names + ")"));
}

void follow_routes(Scenario& s) {
  if (!s.motion.route.empty()) s.motion.path = route_of(s, s.motion.route, "the camera motion");
  for (ActorSpec& a : s.written_actors)
    if (!a.route.empty()) a.path = route_of(s, a.route, "actor '" + a.name + "'");
}

}  // namespace

Scenario load_scenario(const std::string& path, const std::vector<YamlOverride>& overrides) {
  YAML::Node root = load_yaml_file(path, "scenario file");
  if (!root || root.IsNull()) fail(path, "empty scenario file");
  Source source{path, {}};
  for (const auto& o : overrides) {
    const std::string option = path + ": --set " + o.key + "=" + o.value;
    apply_yaml_override(root, o, option);
    // The value node the override put in (reset, not assignment, walks
    // yaml-cpp nodes without overwriting them).
    YAML::Node node(root);
    size_t start = 0;
    while (node.IsMap()) {
      const size_t dot = o.key.find('.', start);
      const std::string part = o.key.substr(start, dot == std::string::npos ? dot : dot - start);
      const YAML::Node child = node[part];
      if (!child) break;
      node.reset(child);
      if (dot == std::string::npos) {
        // Every node of the value (a --set list or map) names the option.
        std::function<void(const YAML::Node&)> name = [&](const YAML::Node& n) {
          source.overrides.emplace_back(n, option);
          if (n.IsMap())
            for (const auto& kv : n) name(kv.first), name(kv.second);
          else if (n.IsSequence())
            for (const auto& e : n) name(e);
        };
        name(node);
        break;
      }
      start = dot + 1;
    }
  }
  Fields top(root, source, "scenario");
  top.allow_only({"name",         "description", "scene",         "classes",      "seed",
                  "seed_world",   "frames",      "shadows",       "dynamic_load", "style",
                  "actors_style", "props_style", "asset_catalog", "camera",       "motion",
                  "timestamps",   "sensor",      "camera_cover",  "lamps",        "openings",
                  "actors",       "hall",        "crowds",        "doors"});

  Scenario s;
  s.source_path = path;
  s.name = top.str("name", fs::path(path).stem().string());
  s.description = top.str("description");
  // Paths the scenario writes are relative to its own folder; the defaults
  // are the project's shipped files wherever the scenario was copied to.
  std::string scene_file;
  if (top.str("scene") == "procedural")
    s.procedural = read_procedural_hall(Fields(top.node("hall"), source, "hall"));
  else if (top.has("hall"))
    fail(top.where(top.node("hall")),
         "'hall' sets a generated hall's parameters: it needs "
         "'scene: procedural'");
  else
    scene_file = top.has("scene") ? top.existing_file("scene") : project_file("scenes/depot.yaml");
  s.classes_path =
      top.has("classes") ? top.existing_file("classes") : project_file("scenes/classes.yaml");
  s.asset_catalog_path = top.has("asset_catalog") ? top.existing_file("asset_catalog")
                                                  : project_file("assets/catalog.yaml");
  s.seed = top.get<uint64_t>("seed", 1);
  if (top.has("seed_world")) s.seed_world = top.get<uint64_t>("seed_world", 0);
  s.frames = static_cast<int>(top.number("frames", 300, 1, 1e6));
  s.shadows = top.get<bool>("shadows", false);
  s.dynamic_load = top.number("dynamic_load", 1.0, 0.0, 4.0);
  // `style` draws everything one way (default mesh: the catalogue's models
  // where one plays the class); actors_style and props_style, where written,
  // override it for their part.
  auto style = [&](const char* key, const std::string& fallback) {
    const std::string v = top.str(key, fallback);
    if (v != "primitive" && v != "mesh")
      fail(top.where(top.node(key)),
           "unknown " + std::string(key) + " '" + v + "' (expected primitive or mesh)");
    return v;
  };
  const std::string all = style("style", "mesh");
  s.actors_style = style("actors_style", all);
  s.props_style = style("props_style", all);

  if (top.has("camera"))
    read_camera(Fields(top.node("camera"), source, "camera"), s.camera);
  else
    read_camera(Fields(YAML::Node(YAML::NodeType::Map), source, "camera"), s.camera);
  if (!top.has("motion")) fail(top.where(), "missing 'motion'");
  read_motion(Fields(top.node("motion"), source, "motion"), s.motion);
  if (top.has("timestamps"))
    read_timestamps(Fields(top.node("timestamps"), source, "timestamps"), s.timestamps);
  if (top.has("sensor")) {
    read_sensor(Fields(top.node("sensor"), source, "sensor"), s.sensor);
    check_shutter_fits_frame(top, s);
  }
  if (top.has("camera_cover")) s.camera_cover = read_camera_cover(top, s);
  if (top.has("lamps")) s.lamps = read_lamps(top, source);
  if (top.has("openings")) s.openings = read_openings(top, source);

  if (YAML::Node actors = top.node("actors")) {
    if (!actors.IsSequence()) fail(top.where(actors), "'actors' must be a list");
    size_t i = 0;
    for (const auto& node : actors)
      s.written_actors.push_back(read_actor(Fields(node, source, "actor"), i++, s.seed));
  }
  if (top.has("crowds")) s.crowds = read_crowds(top, source);
  if (top.has("doors")) s.doors = read_doors(top, source);
  // Cross-references: unique names, push/sit targets exist and are pushables.
  std::set<std::string> names;
  for (const auto& a : s.written_actors) {
    if (!names.insert(a.name).second) fail(path, "duplicate actor name '" + a.name + "'");
  }
  for (const auto& d : s.doors)
    if (!names.insert(d.name).second) fail(d.where, "door name '" + d.name + "' is taken");
  for (const auto& c : s.crowds) {
    if (!names.insert(c.name).second) fail(c.where, "crowd name '" + c.name + "' is taken");
    for (const auto& a : s.written_actors)
      if (a.name.rfind(c.name + "_", 0) == 0)
        fail(c.where, "crowd '" + c.name + "' would name its walkers like actor '" + a.name + "'");
  }
  std::set<std::string> claimed;
  for (const auto& a : s.written_actors) {
    if (a.target.empty()) continue;
    auto it = std::find_if(s.written_actors.begin(), s.written_actors.end(),
                           [&](const ActorSpec& b) { return b.name == a.target; });
    if (it == s.written_actors.end() || !is_pushable_actor(it->type))
      fail(path,
           "actor '" + a.name + "' refers to '" + a.target + "', which is not a chair or cart");
    if (a.action == "sit" && it->type != "chair")
      fail(path, "actor '" + a.name + "' can only sit on a chair");
    if (!claimed.insert(a.target).second)
      fail(path, "'" + a.target + "' is used by more than one actor");
  }
  s.layout = s.procedural ? generate_procedural_hall(*s.procedural, s.world_seed())
                          : load_scene_layout(scene_file);
  follow_routes(s);
  for (const auto& c : s.crowds)
    if (!s.layout.contains(c.lo) || !s.layout.contains(c.hi))
      fail(c.where, "crowd '" + c.name + "': its area is not inside the hall");
  for (const auto& d : s.doors)
    if (!s.layout.contains(d.hinge) || d.height > s.layout.height)
      fail(d.where, "door '" + d.name + "' is not inside the hall");
  apply_dynamic_load(s, s.dynamic_load);
  return s;
}

void set_scenario_seed(Scenario& s, uint64_t seed) {
  s.seed = seed;
  if (!s.procedural || s.seed_world) return;
  s.layout = generate_procedural_hall(*s.procedural, s.world_seed());
  follow_routes(s);
  apply_dynamic_load(s, s.dynamic_load);
}

void apply_dynamic_load(Scenario& s, double load) {
  if (!std::isfinite(load) || load < 0.0 || load > 4.0)
    fail(s.source_path, "dynamic load " + std::to_string(load) + " is out of range [0, 4]");
  // Always scale from the actors as written, so calls do not compound.
  s.dynamic_load = load;
  s.actors = s.written_actors;
  if (std::abs(load - 1.0) < 1e-12) return;

  std::vector<ActorSpec> living;
  for (const auto& a : s.actors)
    if (is_living_actor(a.type)) living.push_back(a);
  const size_t target_count = static_cast<size_t>(std::lround(load * living.size()));
  const double speed_scale = std::clamp(0.6 + 0.4 * load, 0.5, 2.0);
  const double size_scale = std::clamp(0.85 + 0.15 * load, 0.7, 1.3);

  // Keep the first `target_count` living actors (in file order); a removed
  // pusher leaves its cart standing; a removed sitter leaves the chair empty.
  std::vector<ActorSpec> kept;
  size_t living_seen = 0;
  for (const auto& a : s.actors) {
    if (is_living_actor(a.type) && living_seen++ >= target_count) continue;
    kept.push_back(a);
  }
  // Add clones of moving (walking/flying) actors, offset along their path.
  std::vector<ActorSpec> movers;
  for (const auto& a : living)
    if (a.action == "walk" || a.action == "fly") movers.push_back(a);
  for (size_t i = living.size(); i < target_count && !movers.empty(); ++i) {
    ActorSpec c = movers[(i - living.size()) % movers.size()];
    size_t round = (i - living.size()) / movers.size() + 1;
    c.name += "_c" + std::to_string(i);
    c.start_offset += 2.3 * round + 0.7 * (i % 3);
    c.appearance = c.appearance * 31 + i;
    if (round % 2 == 1) std::reverse(c.path.begin(), c.path.end());
    kept.push_back(c);
  }
  for (auto& a : kept) {
    if (!is_living_actor(a.type)) continue;
    a.speed *= speed_scale;
    // A pusher keeps its size: a bigger one would start with its hands in
    // its chair or cart (build_scene refuses that).
    if (a.action != "push") a.size *= size_scale;
  }
  s.actors = kept;
}

std::vector<std::string> list_scenarios(const std::string& folder) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  }
  if (ec) fail(folder, "cannot list scenarios folder");
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace depot::sim
