// The simulated detector's YAML config: defaults, every key, range checks and
// error messages naming file and line.
#include "slam/detect/sim_detector_config.h"

#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "common/error.h"
#include "common/testing/error_of.h"

namespace depot::slam {
namespace {

SimDetectorConfig from(const std::string& yaml) {
  return load_sim_detector_config(YAML::Load(yaml), "cfg.yaml");
}

TEST(SimDetectorConfig, DefaultsAreRealisticAndValid) {
  const SimDetectorConfig c;
  EXPECT_FALSE(c.perfect);
  EXPECT_GT(c.miss_rate, 0.0);
  EXPECT_GT(c.jitter, 0.0);
  EXPECT_GT(c.false_positive_rate, 0.0);
  EXPECT_EQ(c.latency_frames, 0);
  EXPECT_NO_THROW(validate(c, "defaults"));
  // An empty or null node keeps the defaults.
  EXPECT_EQ(from("{}").miss_rate, c.miss_rate);
  EXPECT_EQ(load_sim_detector_config(YAML::Node(), "x").jitter, c.jitter);
}

TEST(SimDetectorConfig, ReadsEveryKey) {
  const SimDetectorConfig c = from(
      "seed: 42\nperfect: true\nmiss_rate: 0.1\nsmall_miss_boost: 0.2\nsmall_area: 0.02\n"
      "occlusion_miss: 0.3\ndefault_fill: 0.4\njitter: 0.05\nscale_error: 0.06\n"
      "hard_jitter_gain: 2\nmin_confidence: 0.25\nmax_confidence: 0.9\nconfidence_noise: 0.1\n"
      "false_positive_rate: 1.5\nfalse_positive_max_confidence: 0.45\nclass_confusion: 0.07\n"
      "confusions: {dog: [cat, pig], chair: cart}\nlatency_frames: 3\n"
      "class_miss_rate: {desk: 0.95, person: 0.02}\nconfidence_drop: 0.4\n"
      "class_confusion_rate: {dog: 0.6}\n");
  EXPECT_EQ(c.seed, 42u);
  EXPECT_TRUE(c.perfect);
  EXPECT_DOUBLE_EQ(c.miss_rate, 0.1);
  EXPECT_DOUBLE_EQ(c.small_miss_boost, 0.2);
  EXPECT_DOUBLE_EQ(c.small_area, 0.02);
  EXPECT_DOUBLE_EQ(c.occlusion_miss, 0.3);
  EXPECT_DOUBLE_EQ(c.default_fill, 0.4);
  EXPECT_DOUBLE_EQ(c.jitter, 0.05);
  EXPECT_DOUBLE_EQ(c.scale_error, 0.06);
  EXPECT_DOUBLE_EQ(c.hard_jitter_gain, 2.0);
  EXPECT_DOUBLE_EQ(c.min_confidence, 0.25);
  EXPECT_DOUBLE_EQ(c.max_confidence, 0.9);
  EXPECT_DOUBLE_EQ(c.confidence_noise, 0.1);
  EXPECT_DOUBLE_EQ(c.false_positive_rate, 1.5);
  EXPECT_DOUBLE_EQ(c.false_positive_max_confidence, 0.45);
  EXPECT_DOUBLE_EQ(c.class_confusion, 0.07);
  ASSERT_EQ(c.confusions.size(), 2u);
  EXPECT_EQ(c.confusions.at("dog"), (std::vector<std::string>{"cat", "pig"}));
  EXPECT_EQ(c.confusions.at("chair"), (std::vector<std::string>{"cart"}));
  EXPECT_EQ(c.latency_frames, 3);
  EXPECT_EQ(c.class_miss_rate, (std::map<std::string, double>{{"desk", 0.95}, {"person", 0.02}}));
  EXPECT_DOUBLE_EQ(c.confidence_drop, 0.4);
  EXPECT_EQ(c.class_confusion_rate, (std::map<std::string, double>{{"dog", 0.6}}));
}

TEST(SimDetectorConfig, PerClassRatesAndTheCalibrationBlock) {
  // Defaults: one rate for all classes, the full confidence drop.
  EXPECT_TRUE(SimDetectorConfig{}.class_miss_rate.empty());
  EXPECT_TRUE(SimDetectorConfig{}.class_confusion_rate.empty());
  EXPECT_EQ(SimDetectorConfig{}.confidence_drop, 1.0);
  // The calibration block is read by people, not checked, but must be a map.
  const SimDetectorConfig c = from(
      "miss_rate: 0.3\nclass_miss_rate: {desk: 1}\nclass_confusion: 0.1\n"
      "class_confusion_rate: {dog: 0.5}\n"
      "calibration:\n  detector: darknet\n  datasets:\n    - {path: a, seed: 1}\n");
  EXPECT_DOUBLE_EQ(c.miss_rate, 0.3);
  EXPECT_EQ(c.class_miss_rate.at("desk"), 1.0);
  EXPECT_EQ(error_of([] { from("calibration: darknet"); }),
            "cfg.yaml:1: 'calibration' must be a map (what the values were fitted on)");
  // Over such a config, a map that sets one rate drops the per-class rates
  // (a sweep's miss_rate levels mean every class); with both, both count.
  const SimDetectorConfig one = load_sim_detector_config(YAML::Load("miss_rate: 0.2"), "x", c);
  EXPECT_DOUBLE_EQ(one.miss_rate, 0.2);
  EXPECT_TRUE(one.class_miss_rate.empty());
  EXPECT_EQ(one.class_confusion_rate.at("dog"), 0.5) << "confusion rates untouched";
  const SimDetectorConfig both = load_sim_detector_config(
      YAML::Load("miss_rate: 0.2\nclass_miss_rate: {cat: 0.4}\nclass_confusion: 0"), "x", c);
  EXPECT_EQ(both.class_miss_rate, (std::map<std::string, double>{{"cat", 0.4}}));
  EXPECT_TRUE(both.class_confusion_rate.empty());
  EXPECT_EQ(load_sim_detector_config(YAML::Load("jitter: 0.1"), "x", c).class_miss_rate.at("desk"),
            1.0);
  // Errors name the line, the key and the class.
  EXPECT_EQ(error_of([] { from("jitter: 0.1\nclass_miss_rate: {desk: 1.5}"); }),
            "cfg.yaml:2: 'class_miss_rate' of 'desk' = 1.5 is outside [0, 1]");
  EXPECT_EQ(error_of([] { from("class_confusion_rate: [dog]"); }),
            "cfg.yaml:1: 'class_confusion_rate' must be a map: class -> probability");
  EXPECT_EQ(error_of([] { from("class_miss_rate: {desk: lots}"); }),
            "cfg.yaml:1: bad value for 'class_miss_rate: desk'");
  EXPECT_EQ(error_of([] { from("confidence_drop: 2"); }),
            "cfg.yaml:1: 'confidence_drop' = 2 is outside [0, 1]");
  SimDetectorConfig bad;
  bad.class_confusion_rate[""] = 0.5;
  EXPECT_EQ(error_of([&] { validate(bad, "here"); }),
            "here: 'class_confusion_rate' has an empty class name");
}

TEST(SimDetectorConfig, RangeErrorsNameTheLineAndTheKey) {
  EXPECT_EQ(error_of([] { from("jitter: 0.01\nmiss_rate: 1.5\n"); }),
            "cfg.yaml:2: 'miss_rate' = 1.5 is outside [0, 1]");
  EXPECT_EQ(error_of([] { from("class_confusion: -0.1"); }),
            "cfg.yaml:1: 'class_confusion' = -0.1 is outside [0, 1]");
  EXPECT_EQ(error_of([] { from("latency_frames: 31"); }),
            "cfg.yaml:1: 'latency_frames' = 31 is outside [0, 30]");
  EXPECT_EQ(error_of([] { from("latency_frames: -1"); }),
            "cfg.yaml:1: 'latency_frames' = -1 is outside [0, 30]");
  EXPECT_EQ(error_of([] { from("small_area: 0"); }),
            "cfg.yaml:1: 'small_area' = 0 is outside (0, 1]");
  EXPECT_EQ(error_of([] { from("false_positive_rate: 11"); }),
            "cfg.yaml:1: 'false_positive_rate' = 11 is outside [0, 10]");
  EXPECT_EQ(error_of([] { from("min_confidence: 0.6\nfalse_positive_max_confidence: 0.5"); }),
            "cfg.yaml: 'min_confidence' (0.6) exceeds 'false_positive_max_confidence' (0.5)");
  // Order does not matter for checks between fields.
  EXPECT_NO_THROW(
      from("min_confidence: 0.97\nmax_confidence: 0.99\n"
           "false_positive_max_confidence: 0.98"));
}

TEST(SimDetectorConfig, BadKeysAndValuesAreErrors) {
  EXPECT_EQ(error_of([] { from("miss_rate: 0.1\nmis_rate: 0.2"); }),
            "cfg.yaml:2: unknown key 'mis_rate'");
  // Found by fuzzing (tests/fuzz/fuzz_detector_config): a key with a
  // newline made a two-line error, a map as a key a yaml-cpp exception.
  EXPECT_EQ(error_of([] { from("miss_rate: 0.1\n\"class_co\\nx\": 0.2"); }),
            "cfg.yaml:2: unknown key 'class_co\\nx'");
  EXPECT_EQ(error_of([] { from("{a: 1}: 0.2"); }), "cfg.yaml:1: a key must be a plain name");
  EXPECT_EQ(error_of([] { from("jitter: lots"); }), "cfg.yaml:1: bad value for 'jitter'");
  EXPECT_EQ(error_of([] { from("perfect: maybe"); }), "cfg.yaml:1: bad value for 'perfect'");
  EXPECT_EQ(error_of([] { from("latency_frames: 1.5"); }),
            "cfg.yaml:1: bad value for 'latency_frames'");
  EXPECT_EQ(error_of([] { from("[1, 2]"); }),
            "cfg.yaml:1: the simulated detector config must be a YAML map");
  EXPECT_EQ(error_of([] { from("confusions: [dog, cat]"); }),
            "cfg.yaml:1: 'confusions' must be a map: class -> [classes it is mistaken for]");
  EXPECT_EQ(error_of([] { from("confusions: {dog: [dog]}"); }),
            "cfg.yaml:1: 'confusions' of 'dog' lists the class itself");
  SimDetectorConfig c;
  c.scale_error = std::nan("");
  EXPECT_EQ(error_of([&] { validate(c, "here"); }), "here: 'scale_error' = nan is outside [0, 1]");
}

TEST(SimDetectorConfig, LoadsFilesWithClearErrors) {
  const std::string dir = ::testing::TempDir() + "/sim_detector_config_test";
  std::filesystem::create_directories(dir);
  const std::string good = dir + "/good.yaml", bad = dir + "/bad.yaml";
  std::ofstream(good) << "# a detector lagging two frames\nlatency_frames: 2\nseed: 7\n";
  std::ofstream(bad) << "miss_rate: 0.1\njitter: [0.1\n";
  const SimDetectorConfig c = load_sim_detector_config_file(good);
  EXPECT_EQ(c.latency_frames, 2);
  EXPECT_EQ(c.seed, 7u);
  EXPECT_EQ(error_of([&] { load_sim_detector_config_file(dir + "/none.yaml"); }),
            dir + "/none.yaml: cannot open the simulated detector config");
  EXPECT_EQ(error_of([&] { load_sim_detector_config_file(bad); }).rfind(bad + ":", 0), 0u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace depot::slam
