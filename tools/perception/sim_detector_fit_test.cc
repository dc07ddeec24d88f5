// The fit of the simulated detector's error model: on boxes drawn from the
// model itself with known parameters (the way the simulated detector draws
// them, with the IoU >= 0.5 cut of the matching), the fit recovers them; and
// a parameter with nothing to be fitted on is one clear error.
#include "tools/perception/sim_detector_fit.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "common/rng.h"
#include "common/testing/error_of.h"
#include "slam/detect/sim_detector.h"

namespace depot::perception {
namespace {

constexpr double kImageArea = 640.0 * 480.0;

double iou_of_unit_box(double cx, double cy, double w, double h) {
  const double ix = std::max(0.0, std::min(0.5, cx + 0.5 * w) - std::max(-0.5, cx - 0.5 * w));
  const double iy = std::max(0.0, std::min(0.5, cy + 0.5 * h) - std::max(-0.5, cy - 0.5 * h));
  return ix * iy / (1.0 + w * h - ix * iy);
}

// `n` boxes of classes person, dog and chair drawn from `truth`'s model
// (dogs are confused with cats), as a detector with this error model would
// leave them after matching at IoU >= 0.5.
FitData draw(const slam::SimDetectorConfig& truth, int n, uint64_t seed) {
  Rng rng(seed);
  FitData data;
  data.min_confidence = truth.min_confidence;
  const char* classes[] = {"person", "dog", "chair"};
  for (int i = 0; i < n; ++i) {
    FitBox b;
    b.truth_class = classes[rng.below(3)];
    b.image_area = kImageArea;
    b.area = kImageArea * std::exp(rng.uniform(std::log(0.001), std::log(0.5)));
    b.occlusion = rng.uniform() < 0.3 ? 0.0 : rng.uniform(0.0, 0.9);
    const double s = slam::model_smallness(b.area, b.image_area, truth.small_area);
    double d = slam::model_difficulty(s, b.occlusion);
    const auto rate = truth.class_miss_rate.find(b.truth_class);
    const double m = rate == truth.class_miss_rate.end() ? truth.miss_rate : rate->second;
    const double p_miss = 1.0 - (1.0 - m) * (1.0 - truth.small_miss_boost * s) *
                                    (1.0 - truth.occlusion_miss * b.occlusion);
    if (rng.uniform() >= p_miss) {
      std::string called = b.truth_class;
      if (b.truth_class == "dog" && rng.uniform() < truth.class_confusion_rate.at("dog")) {
        called = "cat";
        d = std::max(d, 0.5);
      }
      const double g = 1.0 + truth.hard_jitter_gain * d;
      b.dx = rng.normal() * truth.jitter * g;
      b.dy = rng.normal() * truth.jitter * g;
      b.log_w = rng.normal() * truth.scale_error * g;
      b.log_h = rng.normal() * truth.scale_error * g;
      const double mean = truth.max_confidence -
                          (truth.max_confidence - truth.min_confidence) * truth.confidence_drop * d;
      b.confidence = std::min(
          1.0, std::max(truth.min_confidence, mean + truth.confidence_noise * rng.normal()));
      if (iou_of_unit_box(b.dx, b.dy, std::exp(b.log_w), std::exp(b.log_h)) >= 0.5)
        b.detected_class = called;
      else
        data.false_positive_confidences.push_back(b.confidence);  // found, but too far off
    }
    data.boxes.push_back(b);
  }
  data.frames = n / 5;
  for (long f = 0; f < data.frames; ++f)
    if (rng.uniform() < truth.false_positive_rate)
      data.false_positive_confidences.push_back(
          rng.uniform(truth.min_confidence, truth.false_positive_max_confidence));
  return data;
}

slam::SimDetectorConfig known() {
  slam::SimDetectorConfig c;
  c.miss_rate = 0.2;
  c.class_miss_rate = {{"person", 0.05}, {"chair", 0.6}};
  c.small_miss_boost = 0.7;
  c.small_area = 0.03;
  c.occlusion_miss = 0.5;
  c.jitter = 0.05;
  c.scale_error = 0.1;
  c.hard_jitter_gain = 1.5;
  c.min_confidence = 0.3;
  c.max_confidence = 0.9;
  c.confidence_drop = 0.5;
  c.confidence_noise = 0.08;
  c.false_positive_rate = 0.4;
  c.false_positive_max_confidence = 0.6;
  c.class_confusion_rate = {{"dog", 0.3}};
  return c;
}

TEST(SimDetectorFit, RecoversTheParametersItsBoxesWereDrawnWith) {
  const slam::SimDetectorConfig truth = known();
  const FitData data = draw(truth, 30000, 7);
  const SimDetectorFit fit = fit_sim_detector(data, slam::SimDetectorConfig{}, "synthetic");
  const slam::SimDetectorConfig& c = fit.config;
  std::printf(
      "[fit] miss person %.3f dog %.3f chair %.3f, boost %.3f, small_area %.4f, occlusion %.3f, "
      "jitter %.4f, scale %.4f, gain %.2f, max conf %.3f, drop %.3f, noise %.3f, fp %.3f "
      "(max conf %.3f), dog confusion %.3f\n",
      c.class_miss_rate.at("person"), c.class_miss_rate.at("dog"), c.class_miss_rate.at("chair"),
      c.small_miss_boost, c.small_area, c.occlusion_miss, c.jitter, c.scale_error,
      c.hard_jitter_gain, c.max_confidence, c.confidence_drop, c.confidence_noise,
      c.false_positive_rate, c.false_positive_max_confidence, c.class_confusion_rate.at("dog"));
  EXPECT_NEAR(c.class_miss_rate.at("person"), 0.05, 0.03);
  EXPECT_NEAR(c.class_miss_rate.at("dog"), 0.2, 0.04);
  EXPECT_NEAR(c.class_miss_rate.at("chair"), 0.6, 0.04);
  EXPECT_NEAR(c.small_miss_boost, 0.7, 0.08);
  EXPECT_NEAR(c.small_area, 0.03, 0.006);
  EXPECT_NEAR(c.occlusion_miss, 0.5, 0.05);
  EXPECT_NEAR(c.jitter, 0.05, 0.004);
  EXPECT_NEAR(c.scale_error, 0.1, 0.008);
  EXPECT_NEAR(c.hard_jitter_gain, 1.5, 0.3);
  EXPECT_DOUBLE_EQ(c.min_confidence, 0.3);
  EXPECT_NEAR(c.max_confidence, 0.9, 0.01);
  EXPECT_NEAR(c.confidence_drop, 0.5, 0.05);
  EXPECT_NEAR(c.confidence_noise, 0.08, 0.01);
  // The boxes that fell below IoU 0.5 come back as false positives.
  EXPECT_NEAR(c.false_positive_rate, 0.4, 0.08);
  EXPECT_NEAR(c.false_positive_max_confidence, 0.6, 0.05);
  // Only the pair that happened, at its rate.
  ASSERT_EQ(c.confusions.size(), 1u);
  EXPECT_EQ(c.confusions.at("dog"), std::vector<std::string>{"cat"});
  EXPECT_NEAR(c.class_confusion_rate.at("dog"), 0.3, 0.03);
  EXPECT_NO_THROW(validate(c, "fit"));
}

TEST(SimDetectorFit, ADetectorThatFindsEverythingFitsToNoMisses) {
  slam::SimDetectorConfig truth = known();
  truth.class_miss_rate = {{"person", 0.0}, {"dog", 0.0}, {"chair", 0.0}};
  truth.small_miss_boost = 0.0;
  truth.occlusion_miss = 0.0;
  truth.jitter = 0.01;
  truth.scale_error = 0.01;
  const SimDetectorFit fit = fit_sim_detector(draw(truth, 5000, 3), slam::SimDetectorConfig{}, "x");
  for (const char* c : {"person", "dog", "chair"})
    EXPECT_LT(fit.config.class_miss_rate.at(c), 0.01) << c;
  EXPECT_LT(fit.config.occlusion_miss, 0.02);
}

TEST(SimDetectorFit, IouRetentionFallsWithTheErrors) {
  EXPECT_EQ(iou_retention(0.0, 0.0), 1.0);
  EXPECT_GT(iou_retention(0.03, 0.05), 0.99);
  const double mid = iou_retention(0.1, 0.2);
  EXPECT_LT(mid, 0.99);
  EXPECT_GT(mid, 0.5);
  EXPECT_LT(iou_retention(0.3, 0.5), mid);
  EXPECT_EQ(iou_retention(0.1, 0.2), mid) << "a fixed sample: the same value every time";
}

TEST(SimDetectorFit, NothingToFitOnIsOneError) {
  FitData empty;
  empty.frames = 3;
  EXPECT_EQ(error_of([&] { fit_sim_detector(empty, {}, "d1"); }),
            "d1: no ground-truth box in the scored frames: nothing to fit the miss model on");
  FitData none = empty;
  none.boxes.resize(4);
  for (FitBox& b : none.boxes) {
    b.truth_class = "person";
    b.area = 1000;
    b.image_area = kImageArea;
    b.occlusion = 0.3;
  }
  EXPECT_EQ(error_of([&] { fit_sim_detector(none, {}, "d1, d2"); }),
            "d1, d2: the detector matched none of the 4 ground-truth boxes (IoU >= 0.5): nothing "
            "to fit jitter, scale_error and the confidences on");
  FitData unoccluded = none;
  for (FitBox& b : unoccluded.boxes) {
    b.occlusion = 0.0;
    b.detected_class = "person";
    b.confidence = 0.8;
  }
  EXPECT_EQ(error_of([&] { fit_sim_detector(unoccluded, {}, "d1"); }),
            "d1: no partly occluded box of a class the detector matched: nothing to fit "
            "occlusion_miss on");
  FitData no_frames = unoccluded;
  no_frames.frames = 0;
  EXPECT_EQ(error_of([&] { fit_sim_detector(no_frames, {}, "d1"); }),
            "d1: no frame was scored: nothing to fit the detector on");
}

}  // namespace
}  // namespace depot::perception
