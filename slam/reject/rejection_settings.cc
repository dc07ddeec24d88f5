#include "slam/reject/rejection_settings.h"

#include <yaml-cpp/yaml.h>

#include "common/error.h"
#include "common/yaml_fields.h"

namespace depot::slam {
namespace {

using Kind = RejectionSetting::Kind;

RejectionSetting flag(const char* key, bool in_full, bool in_masked, const char* help,
                      bool& (*field)(RejectionParams&)) {
  RejectionSetting s{key, Kind::kFlag};
  s.in_full = in_full;
  s.in_masked = in_masked;
  s.help = help;
  s.flag = field;
  return s;
}

RejectionSetting integer(const char* key, int lo, int hi, const char* unit, bool in_full,
                         bool in_masked, const char* help, int& (*field)(RejectionParams&)) {
  RejectionSetting s{key, Kind::kInteger, static_cast<double>(lo), static_cast<double>(hi), unit};
  s.in_full = in_full;
  s.in_masked = in_masked;
  s.help = help;
  s.integer = field;
  return s;
}

RejectionSetting real(const char* key, float lo, float hi, const char* unit, bool in_full,
                      bool in_masked, const char* help, float& (*field)(RejectionParams&)) {
  RejectionSetting s{key, Kind::kReal, lo, hi, unit};
  s.in_full = in_full;
  s.in_masked = in_masked;
  s.help = help;
  s.real = field;
  return s;
}

// Which modes: the depth split of boxes acts in full alone, the object
// masks' own keys (mask., tracking., person_mask) in masked alone, the flow
// test's extensions in both.
constexpr bool kFull = true, kMasked = true, kNotFull = false, kNotMasked = false;

std::vector<RejectionSetting> make_table() {
  using P = RejectionParams;
  std::vector<RejectionSetting> t = {
      real("background_margin", 0.0f, 10.0f, "m", kFull, kNotMasked,
           "Our extension of full: boxed points without depth, or this far (m) behind a "
           "dynamic box's object, are background and go to P (0 = the paper exactly)",
           [](P& p) -> float& { return p.background_depth_margin; }),
      flag("ego_flow", kFull, kMasked,
           "Our extension of full and masked: test flow against the camera's motion fitted to P "
           "(by PnP on depth) instead of P's mean flow",
           [](P& p) -> bool& { return p.ego_motion_flow; }),
      flag("test_static", kFull, kMasked,
           "Our extension of full and masked: apply the flow test to P's points too",
           [](P& p) -> bool& { return p.test_static_points; }),
      flag("motion", kFull, kMasked,
           "masked with ego_flow: reject movers no detector names (slam/reject/motion_objects.h)",
           [](P& p) -> bool& { return p.motion.enabled; }),
      flag("motion.first_sight", kFull, kMasked,
           "a mover found without a detection is rejected on the frame it is first seen",
           [](P& p) -> bool& { return p.motion.reject_on_first_sight; }),
  };
  RejectionSetting person_mask{"person_mask", Kind::kPersonMask};
  person_mask.in_masked = true;
  person_mask.help = "masked: person masks from depth, a person segmenter, or both";
  t.push_back(person_mask);
  t.push_back(flag("mask.plane", kNotFull, kMasked, "remove the support plane from object masks",
                   [](P& p) -> bool& { return p.mask.remove_plane; }));
  t.push_back(flag("tracking.by_flow", kNotFull, kMasked,
                   "move tracked boxes by their keypoints' optical flow (else by the velocity of "
                   "past detections)",
                   [](P& p) -> bool& { return p.carry_by_flow; }));
  const RejectionSetting integers[] = {
      integer("motion.min_seeds", 1, 10000, "keypoints", kFull, kMasked,
              "keypoints failing the flow test that seed a mover",
              [](P& p) -> int& { return p.motion.min_seeds; }),
      integer("tracking.max_missed", 0, 1000, "frames", kNotFull, kMasked,
              "frames a box is carried without its detection",
              [](P& p) -> int& { return p.tracking.max_missed; }),
      integer("tracking.max_missed_seen", 0, 1000, "frames", kNotFull, kMasked,
              "frames a box is carried while its object is still found at its depth",
              [](P& p) -> int& { return p.tracking.max_missed_seen; }),
      integer("tracking.min_hits", 1, 1000, "detections", kNotFull, kMasked,
              "detections before a missed box is carried",
              [](P& p) -> int& { return p.tracking.min_hits; }),
      integer("still.min_points", 1, 10000, "keypoints", kFull, kMasked,
              "tracked keypoints a dynamic object needs to be judged still",
              [](P& p) -> int& { return p.still_object_min_points; }),
      integer("mask.stride", 1, 16, "px", kNotFull, kMasked, "object masks' sampling step",
              [](P& p) -> int& { return p.mask.stride; }),
  };
  t.insert(t.end(), std::begin(integers), std::end(integers));
  const RejectionSetting reals[] = {
      real("mask.grow", 0.0f, 2.0f, "", kNotFull, kMasked, "how far a mask grows past its box",
           [](P& p) -> float& { return p.mask.grow; }),
      real("mask.extent", 0.01f, 10.0f, "", kNotFull, kMasked, "an object's depth extent (m)",
           [](P& p) -> float& { return p.mask.extent_m; }),
      real("mask.edge_step", 0.0f, 10.0f, "", kNotFull, kMasked,
           "the depth step (m) that ends an object at its edge",
           [](P& p) -> float& { return p.mask.edge_step_m; }),
      real("mask.edge_step_per_m", 0.0f, 1.0f, "", kNotFull, kMasked,
           "the edge step's growth per metre of depth",
           [](P& p) -> float& { return p.mask.edge_step_per_m; }),
      real("mask.reach", 0.0f, 3.0f, "", kNotFull, kMasked,
           "a keypoint's FAST circle, scaled, touching a mask goes with its object",
           [](P& p) -> float& { return p.mask_reach; }),
      real("mask.top_min_share", 0.0f, 1.0f, "", kNotFull, kMasked,
           "the occluder test's share (0 = no occluder test)",
           [](P& p) -> float& { return p.mask.top_min_share; }),
      real("mask.max_spill", 0.0f, 1.0f, "", kNotFull, kMasked,
           "the occluded object's spill past its box",
           [](P& p) -> float& { return p.mask.max_spill; }),
      real("mask.max_occluder_gap", 0.0f, 100.0f, "", kNotFull, kMasked,
           "how far (m) behind its occluder the object may be",
           [](P& p) -> float& { return p.mask.max_occluder_gap_m; }),
      real("tracking.min_iou", 0.0f, 1.0f, "", kNotFull, kMasked,
           "the overlap that continues a tracked box",
           [](P& p) -> float& { return p.tracking.min_iou; }),
      real("still.max_moving", 0.0f, 1.0f, "", kFull, kMasked,
           "the share of a dynamic object's keypoints failing the flow test below which it is "
           "still (0 = off)",
           [](P& p) -> float& { return p.still_object_max_moving; }),
      real("motion.link_px", 1.0f, 640.0f, "", kFull, kMasked,
           "how near (px) two failing keypoints are one mover",
           [](P& p) -> float& { return p.motion.link_px; }),
      real("motion.link_depth", 0.0f, 10.0f, "", kFull, kMasked,
           "how near in depth (m) two failing keypoints are one mover",
           [](P& p) -> float& { return p.motion.link_depth_m; }),
      real("motion.link_depth_per_m", 0.0f, 1.0f, "", kFull, kMasked,
           "the depth link's growth per metre",
           [](P& p) -> float& { return p.motion.link_depth_per_m; }),
      real("motion.min_moving_share", 0.0f, 1.0f, "", kFull, kMasked,
           "the share of a mover's keypoints that must fail the test",
           [](P& p) -> float& { return p.motion.min_moving_share; }),
      real("motion.grow", 0.0f, 5.0f, "", kFull, kMasked, "how far a mover's region grows",
           [](P& p) -> float& { return p.motion.grow; }),
      real("motion.max_frame_moving_share", 0.0f, 1.0f, "", kFull, kMasked,
           "above this share of a frame moving, movers are not rejected",
           [](P& p) -> float& { return p.motion.max_frame_moving_share; }),
      real("ego.threshold", 0.1f, 100.0f, "", kFull, kMasked,
           "the camera-motion flow test's threshold (px at 640)",
           [](P& p) -> float& { return p.ego.threshold_px; }),
  };
  t.insert(t.end(), std::begin(reals), std::end(reals));
  return t;
}

std::string range_text(const RejectionSetting& s) {
  std::string text = std::string(s.key) + " must be in [" + shortest_number(s.lo) + ", " +
                     shortest_number(s.hi) + "]";
  if (*s.unit) text += std::string(" ") + s.unit;
  return text;
}

}  // namespace

const std::vector<RejectionSetting>& rejection_settings() {
  static const std::vector<RejectionSetting> table = make_table();
  return table;
}

const RejectionSetting* find_rejection_setting(const std::string& key) {
  for (const RejectionSetting& s : rejection_settings())
    if (key == s.key) return &s;
  return nullptr;
}

std::string rejection_setting_keys() {
  std::string keys;
  for (const RejectionSetting& s : rejection_settings())
    keys += (keys.empty() ? "" : ", ") + std::string(s.key);
  return keys;
}

void apply_rejection_setting(RejectionParams& params, const YamlOverride& setting,
                             const std::string& where) {
  const RejectionSetting* s = find_rejection_setting(setting.key);
  if (!s)
    fail(where, "unknown rejection setting '" + setting.key + "' (expected " +
                    rejection_setting_keys() + ")");
  try {
    const YAML::Node value = YAML::Load(setting.value);
    switch (s->kind) {
      case Kind::kFlag:
        s->flag(params) = value.as<bool>();
        return;
      case Kind::kPersonMask:
        params.person_mask = parse_person_mask(setting.value, where);
        return;
      case Kind::kInteger: {
        const int n = value.as<int>();
        if (n < s->lo || n > s->hi) fail(where, range_text(*s));
        s->integer(params) = n;
        return;
      }
      case Kind::kReal: {
        // Compared as floats, as the field holds them (0.01 is 0.00999999978f).
        const float v = value.as<float>();
        if (!(v >= static_cast<float>(s->lo) && v <= static_cast<float>(s->hi)))
          fail(where, range_text(*s));
        s->real(params) = v;
        return;
      }
    }
  } catch (const YAML::Exception&) {
    fail(where, "bad value '" + setting.value + "' for rejection setting '" + setting.key + "'");
  }
}

}  // namespace depot::slam
