#include "slam/detect/sim_detector_config.h"

#include <yaml-cpp/yaml.h>

#include <cmath>

#include "common/error.h"
#include "common/yaml_fields.h"
#include "common/yaml_file.h"

namespace depot::slam {
namespace {

std::string at(const std::string& where, const YAML::Node& n) {
  return YamlSource{where, {}}.where(n);
}

// The real-valued fields and their ranges: [lo, hi], or (lo, hi] when
// `open_lo`.
struct DoubleField {
  const char* key;
  double SimDetectorConfig::*field;
  double lo, hi;
  bool open_lo;
};

const DoubleField kDoubles[] = {
    {"miss_rate", &SimDetectorConfig::miss_rate, 0, 1, false},
    {"small_miss_boost", &SimDetectorConfig::small_miss_boost, 0, 1, false},
    {"small_area", &SimDetectorConfig::small_area, 0, 1, true},
    {"occlusion_miss", &SimDetectorConfig::occlusion_miss, 0, 1, false},
    {"default_fill", &SimDetectorConfig::default_fill, 0, 1, true},
    {"jitter", &SimDetectorConfig::jitter, 0, 1, false},
    {"scale_error", &SimDetectorConfig::scale_error, 0, 1, false},
    {"hard_jitter_gain", &SimDetectorConfig::hard_jitter_gain, 0, 10, false},
    {"min_confidence", &SimDetectorConfig::min_confidence, 0, 1, false},
    {"max_confidence", &SimDetectorConfig::max_confidence, 0, 1, false},
    {"confidence_drop", &SimDetectorConfig::confidence_drop, 0, 1, false},
    {"confidence_noise", &SimDetectorConfig::confidence_noise, 0, 1, false},
    {"false_positive_rate", &SimDetectorConfig::false_positive_rate, 0, 10, false},
    {"false_positive_max_confidence", &SimDetectorConfig::false_positive_max_confidence, 0, 1,
     false},
    {"class_confusion", &SimDetectorConfig::class_confusion, 0, 1, false},
};

void check(const DoubleField& f, double v, const std::string& where) {
  const bool low = f.open_lo ? v <= f.lo : v < f.lo;
  if (!std::isfinite(v) || low || v > f.hi)
    fail(where, std::string("'") + f.key + "' = " + shortest_number(v) + " is outside " +
                    (f.open_lo ? "(" : "[") + shortest_number(f.lo) + ", " + shortest_number(f.hi) +
                    "]");
}

void check_latency(int latency, const std::string& where) {
  if (latency < 0 || latency > 30)
    fail(where, "'latency_frames' = " + std::to_string(latency) + " is outside [0, 30]");
}

void check_confusions(const std::map<std::string, std::vector<std::string>>& confusions,
                      const std::string& where) {
  for (const auto& [cls, partners] : confusions) {
    if (cls.empty()) fail(where, "'confusions' has an empty class name");
    for (const std::string& p : partners) {
      if (p.empty()) fail(where, "'confusions' of '" + cls + "' has an empty class name");
      if (p == cls) fail(where, "'confusions' of '" + cls + "' lists the class itself");
    }
  }
}

// A class -> probability map (class_miss_rate, class_confusion_rate).
void check_class_rates(const char* key, const std::map<std::string, double>& rates,
                       const std::string& where) {
  for (const auto& [cls, rate] : rates) {
    if (cls.empty()) fail(where, std::string("'") + key + "' has an empty class name");
    if (!std::isfinite(rate) || rate < 0 || rate > 1)
      fail(where, std::string("'") + key + "' of '" + cls + "' = " + shortest_number(rate) +
                      " is outside [0, 1]");
  }
}

// Reads a class -> probability map into `rates`.
void read_class_rates(const char* key, const YAML::Node& v, const std::string& where,
                      std::map<std::string, double>& rates) {
  if (!v.IsMap() && !v.IsNull())
    fail(at(where, v), std::string("'") + key + "' must be a map: class -> probability");
  rates.clear();
  if (!v.IsMap()) return;
  const YamlSource source{where, {}};
  for (const auto& entry : v) {
    const std::string cls = yaml_value<std::string>(entry.first, key, source);
    const double rate = yaml_value<double>(entry.second, std::string(key) + ": " + cls, source);
    check_class_rates(key, {{cls, rate}}, at(where, entry.second));
    rates[cls] = rate;
  }
}

// Checks between fields, once all are read.
void check_consistency(const SimDetectorConfig& c, const std::string& where) {
  if (c.min_confidence > c.max_confidence)
    fail(where, "'min_confidence' (" + shortest_number(c.min_confidence) +
                    ") exceeds 'max_confidence' (" + shortest_number(c.max_confidence) + ")");
  if (c.min_confidence > c.false_positive_max_confidence)
    fail(where, "'min_confidence' (" + shortest_number(c.min_confidence) +
                    ") exceeds 'false_positive_max_confidence' (" +
                    shortest_number(c.false_positive_max_confidence) + ")");
}

}  // namespace

void validate(const SimDetectorConfig& c, const std::string& where) {
  for (const DoubleField& f : kDoubles) check(f, c.*f.field, where);
  check_latency(c.latency_frames, where);
  check_class_rates("class_miss_rate", c.class_miss_rate, where);
  check_class_rates("class_confusion_rate", c.class_confusion_rate, where);
  check_confusions(c.confusions, where);
  check_consistency(c, where);
}

SimDetectorConfig load_sim_detector_config(const YAML::Node& node, const std::string& where,
                                           const SimDetectorConfig& defaults) {
  SimDetectorConfig c = defaults;
  if (!node || node.IsNull()) return c;
  if (!node.IsMap()) fail(at(where, node), "the simulated detector config must be a YAML map");
  const YamlSource source{where, {}};
  bool sets_miss_rate = false, sets_class_miss_rate = false;
  bool sets_confusion = false, sets_class_confusion_rate = false;
  for (const auto& kv : node) {
    if (!kv.first.IsScalar()) fail(at(where, kv.first), "a key must be a plain name");
    const std::string key = kv.first.Scalar();
    sets_miss_rate |= key == "miss_rate";
    sets_class_miss_rate |= key == "class_miss_rate";
    sets_confusion |= key == "class_confusion";
    sets_class_confusion_rate |= key == "class_confusion_rate";
    const YAML::Node& v = kv.second;
    const std::string here = at(where, v);
    if (key == "seed") {
      c.seed = yaml_value<uint64_t>(v, key, source);
    } else if (key == "perfect") {
      c.perfect = yaml_value<bool>(v, key, source);
    } else if (key == "latency_frames") {
      c.latency_frames = yaml_value<int>(v, key, source);
      check_latency(c.latency_frames, here);
    } else if (key == "calibration") {
      // The measurement the values came from: for people, not checked.
      if (!v.IsMap()) fail(here, "'calibration' must be a map (what the values were fitted on)");
    } else if (key == "class_miss_rate") {
      read_class_rates("class_miss_rate", v, where, c.class_miss_rate);
    } else if (key == "class_confusion_rate") {
      read_class_rates("class_confusion_rate", v, where, c.class_confusion_rate);
    } else if (key == "confusions") {
      if (!v.IsMap() && !v.IsNull())
        fail(here, "'confusions' must be a map: class -> [classes it is mistaken for]");
      c.confusions.clear();
      if (v.IsMap()) {
        for (const auto& entry : v) {
          const std::string cls = yaml_value<std::string>(entry.first, key, source);
          c.confusions[cls] =
              entry.second.IsScalar()
                  ? std::vector<std::string>{yaml_value<std::string>(entry.second, key, source)}
                  : yaml_value<std::vector<std::string>>(entry.second, key + ": " + cls, source);
        }
      }
      check_confusions(c.confusions, here);
    } else {
      const DoubleField* f = nullptr;
      for (const DoubleField& d : kDoubles)
        if (key == d.key) f = &d;
      if (!f) fail(at(where, kv.first), "unknown key '" + printable(key) + "'");
      c.*f->field = yaml_value<double>(v, key, source);
      check(*f, c.*f->field, here);
    }
  }
  // One rate for every class, unless the node gives per-class rates too.
  if (sets_miss_rate && !sets_class_miss_rate) c.class_miss_rate.clear();
  if (sets_confusion && !sets_class_confusion_rate) c.class_confusion_rate.clear();
  check_consistency(c, where);
  return c;
}

SimDetectorConfig load_sim_detector_config_file(const std::string& path,
                                                const SimDetectorConfig& defaults) {
  YAML::Node root = load_yaml_file(path, "the simulated detector config");
  return load_sim_detector_config(root, path, defaults);
}

}  // namespace depot::slam
