// The simulated detector on real rendered datasets: perfect mode, the
// measured miss / false-positive / confusion rates and IoU against the
// configuration, difficulty, latency, determinism, errors, and replay of its
// output through a detections file.
#include "slam/detect/sim_detector.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include <unistd.h>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/rng.h"
#include "common/testing/error_of.h"
#include "dataset/boxes.h"
#include "slam/detect/detection_file.h"
#include "tools/perception/sim_detector_fit.h"

namespace depot::slam {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 20;
constexpr int kSeeds = 400;  // repetitions of the 20 frames for the statistics

// Renders `scenario` (20 frames, `width` px wide) with the depot program into
// a new folder under `root` and returns the dataset folder ("" on failure).
std::string render(const std::string& scenario, int width, const std::string& root) {
  const std::string out = root + "/" + scenario;
  const std::string cmd = std::string("\"") + DEPOT_BINARY_DIR +
                          "/tools/depot/depot\" sim render " + scenario + " -o \"" + out +
                          "\" --frames " + std::to_string(kFrames) + " --width " +
                          std::to_string(width) + " -q 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return "";
  std::string output;
  char buf[512];
  while (std::fgets(buf, sizeof(buf), pipe)) output += buf;
  if (pclose(pipe) != 0) {
    std::cerr << cmd << " failed:\n" << output;
    return "";
  }
  return out;
}

double iou(const cv::Rect2f& a, const cv::Rect2f& b) {
  const double inter = (a & b).area();
  const double uni = a.area() + b.area() - inter;
  return uni > 0 ? inter / uni : 0.0;
}

// Greedy one-to-one matching by IoU >= `min_iou`: for each truth box the
// index of its detection, or -1.
std::vector<int> match(const std::vector<TruthBox>& truth, const std::vector<Detection>& dets,
                       double min_iou = 0.3) {
  struct Pair {
    double iou;
    size_t t, d;
  };
  std::vector<Pair> pairs;
  for (size_t t = 0; t < truth.size(); ++t)
    for (size_t d = 0; d < dets.size(); ++d) {
      const double v = iou(truth[t].rect(), dets[d].box);
      if (v >= min_iou) pairs.push_back({v, t, d});
    }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.iou > b.iou; });
  std::vector<int> of_truth(truth.size(), -1);
  std::vector<bool> used(dets.size(), false);
  for (const Pair& p : pairs) {
    if (of_truth[p.t] >= 0 || used[p.d]) continue;
    of_truth[p.t] = static_cast<int>(p.d);
    used[p.d] = true;
  }
  return of_truth;
}

bool same(const Detection& a, const Detection& b) {
  return a.class_name == b.class_name && a.class_id == b.class_id && a.confidence == b.confidence &&
         a.box == b.box;
}

bool same(const std::vector<Detection>& a, const std::vector<Detection>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (!same(a[i], b[i])) return false;
  return true;
}

// A binomial proportion's tolerance: 4 standard deviations plus `slack`.
double tolerance(double p, double n, double slack = 0.0) {
  return 4.0 * std::sqrt(std::max(p * (1 - p), 1e-4) / n) + slack;
}

class SimDetectorTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new std::string(::testing::TempDir() + "/sim_detector_test_" +
                            std::to_string(static_cast<long>(::getpid())));
    fs::remove_all(*root_);
    fs::create_directories(*root_);
    dataset_ = new std::string(render("depot_walking_xyz", 160, *root_));
    // Far objects (a cat, monitors, a bird): the small boxes, at 320 px so
    // they stay above the simulator's minimum box size.
    patrol_ = new std::string(render("depot_patrol", 320, *root_));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
    delete dataset_;
    delete patrol_;
  }
  void SetUp() override {
    if (dataset_->empty()) FAIL() << "could not render depot_walking_xyz";
    if (patrol_->empty()) FAIL() << "could not render depot_patrol";
  }

  static SimDetectorConfig with_seed(SimDetectorConfig c, uint64_t seed) {
    c.seed = seed;
    return c;
  }

  static std::string* root_;
  static std::string* dataset_;  // depot_walking_xyz, 160 x 120
  static std::string* patrol_;   // depot_patrol, 320 x 240
};
std::string* SimDetectorTest::root_ = nullptr;
std::string* SimDetectorTest::dataset_ = nullptr;
std::string* SimDetectorTest::patrol_ = nullptr;

TEST_F(SimDetectorTest, PerfectModeReturnsExactlyTheGroundTruth) {
  SimDetectorConfig config;
  config.perfect = true;
  SimDetector detector(*dataset_, config);
  EXPECT_EQ(detector.name(), "sim-perfect");
  ASSERT_EQ(detector.frame_count(), static_cast<size_t>(kFrames));
  // boxes.txt as the dataset library reads it, without the detector.
  const std::vector<dataset::BoxRecord> boxes = dataset::read_boxes(*dataset_);
  ASSERT_FALSE(boxes.empty());
  size_t seen = 0;
  for (size_t i = 0; i < detector.frame_count(); ++i) {
    const double t = detector.frame_timestamp(i);
    const auto dets = detector.detect(cv::Mat(), t, static_cast<long>(i));
    std::vector<dataset::BoxRecord> expected;
    for (const dataset::BoxRecord& b : boxes)
      if (std::abs(b.timestamp - t) < 1e-4) expected.push_back(b);
    ASSERT_EQ(dets.size(), expected.size()) << "frame " << i;
    for (size_t k = 0; k < dets.size(); ++k) {
      const dataset::BoxRecord& e = expected[k];
      EXPECT_EQ(dets[k].class_name, e.class_name);
      EXPECT_EQ(detector.class_names().at(dets[k].class_id), e.class_name);
      EXPECT_EQ(dets[k].box, cv::Rect2f(e.x1, e.y1, e.x2 - e.x1, e.y2 - e.y1));
      EXPECT_EQ(dets[k].confidence, 1.0f);
    }
    seen += dets.size();
  }
  EXPECT_EQ(seen, boxes.size());
  // The image, when given, must have the dataset's size.
  const cv::Mat right(detector.image_size(), CV_8UC3, cv::Scalar::all(0));
  EXPECT_EQ(detector.detect(right, detector.frame_timestamp(0), 0).size(),
            detector.truth(0).size());
  const cv::Mat wrong(480, 640, CV_8UC3, cv::Scalar::all(0));
  EXPECT_NE(error_of([&] {
              detector.detect(wrong, detector.frame_timestamp(0), 0);
            }).find("image is 640x480 but the dataset's frames are 160x120"),
            std::string::npos);
}

TEST_F(SimDetectorTest, BaseMissRateMatchesTheConfiguration) {
  SimDetectorConfig config;
  config.miss_rate = 0.2;
  config.small_miss_boost = 0.0;
  config.occlusion_miss = 0.0;
  config.false_positive_rate = 0.0;
  double truth = 0, detected = 0;
  for (int s = 0; s < kSeeds; ++s) {
    SimDetector detector(*dataset_, with_seed(config, 1000 + s));
    for (size_t i = 0; i < detector.frame_count(); ++i) {
      truth += detector.truth(i).size();
      detected += detector.detect_frame(i).size();
    }
  }
  const double measured = 1.0 - detected / truth;
  std::cout << "[sim] base miss rate: configured 0.2, measured " << measured << " over " << truth
            << " boxes\n";
  EXPECT_NEAR(measured, 0.2, tolerance(0.2, truth));
}

TEST_F(SimDetectorTest, PerClassRatesReplaceTheGlobalOnes) {
  SimDetectorConfig config;
  config.miss_rate = 0.0;
  config.small_miss_boost = 0.0;
  config.occlusion_miss = 0.0;
  config.false_positive_rate = 0.0;
  config.jitter = config.scale_error = 0.0;
  config.class_miss_rate = {{"person", 1.0}, {"horse", 0.5}};  // not a class here: ignored
  config.class_confusion = 0.0;
  config.class_confusion_rate = {{"chair", 1.0}};
  double people = 0, chairs = 0, carts = 0, others = 0;
  for (int s = 0; s < 20; ++s) {
    SimDetector detector(*dataset_, with_seed(config, 8000 + s));
    EXPECT_EQ(detector.class_miss_rate("person"), 1.0);
    EXPECT_EQ(detector.class_miss_rate("desk"), 0.0);
    for (size_t i = 0; i < detector.frame_count(); ++i) {
      const auto& t = detector.truth(i);
      const auto dets = detector.detect_frame(i);
      const auto m = match(t, dets, 0.999);
      for (size_t k = 0; k < t.size(); ++k) {
        if (t[k].class_name == "person") {
          people += m[k] >= 0;
        } else if (t[k].class_name == "chair") {
          ASSERT_GE(m[k], 0);
          chairs += 1;
          carts += dets[m[k]].class_name == "cart";
        } else {
          ASSERT_GE(m[k], 0) << t[k].class_name;
          others += dets[m[k]].class_name != t[k].class_name;
        }
      }
    }
  }
  EXPECT_EQ(people, 0) << "person's own miss rate 1";
  EXPECT_GT(chairs, 0);
  EXPECT_EQ(carts, chairs) << "chair's own confusion rate 1";
  EXPECT_EQ(others, 0) << "the global confusion rate 0";
}

TEST_F(SimDetectorTest, DefaultMissRateMatchesTheModel) {
  const SimDetectorConfig config;  // realistic defaults
  double truth = 0, missed = 0, expected = 0;
  for (int s = 0; s < kSeeds; ++s) {
    SimDetector detector(*dataset_, with_seed(config, 2000 + s));
    for (size_t i = 0; i < detector.frame_count(); ++i) {
      const auto& t = detector.truth(i);
      const auto m = match(t, detector.detect_frame(i));
      for (size_t k = 0; k < t.size(); ++k) {
        truth += 1;
        missed += m[k] < 0;
        expected += detector.miss_probability(t[k]);
      }
    }
  }
  const double rate = missed / truth, model = expected / truth;
  std::cout << "[sim] default miss rate: model " << model << ", measured " << rate << "\n";
  EXPECT_NEAR(rate, model, tolerance(model, truth, 0.005));
  EXPECT_GE(rate, SimDetectorConfig{}.miss_rate - 0.01);
}

TEST_F(SimDetectorTest, FalsePositiveRateMatchesAndLeavesRealDetectionsAlone) {
  for (const double rate : {SimDetectorConfig{}.false_positive_rate, 0.8}) {
    SimDetectorConfig with, without;
    with.false_positive_rate = rate;
    without.false_positive_rate = 0.0;
    double frames = 0, extra = 0;
    for (int s = 0; s < kSeeds; ++s) {
      SimDetector a(*dataset_, with_seed(with, 3000 + s));
      SimDetector b(*dataset_, with_seed(without, 3000 + s));
      const cv::Size size = a.image_size();
      for (size_t i = 0; i < a.frame_count(); ++i) {
        const auto da = a.detect_frame(i), db = b.detect_frame(i);
        ASSERT_GE(da.size(), db.size());
        // Real objects first, unchanged; the false positives after them.
        ASSERT_TRUE(same(std::vector<Detection>(da.begin(), da.begin() + db.size()), db));
        for (size_t k = db.size(); k < da.size(); ++k) {
          const Detection& fp = da[k];
          EXPECT_GE(fp.confidence, with.min_confidence);
          EXPECT_LE(fp.confidence, with.false_positive_max_confidence);
          EXPECT_EQ(a.class_names().at(fp.class_id), fp.class_name);
          EXPECT_GE(fp.box.x, 0.f);
          EXPECT_GE(fp.box.y, 0.f);
          EXPECT_LE(fp.box.x + fp.box.width, size.width);
          EXPECT_LE(fp.box.y + fp.box.height, size.height);
          EXPECT_GT(fp.box.area(), 0.f);
        }
        frames += 1;
        extra += static_cast<double>(da.size() - db.size());
      }
    }
    const double measured = extra / frames;
    std::cout << "[sim] false positives per frame: configured " << rate << ", measured " << measured
              << " over " << frames << " frames\n";
    EXPECT_NEAR(measured, rate, 4.0 * std::sqrt(rate / frames));
  }
}

TEST_F(SimDetectorTest, MeanIouMatchesTheJitterAndScaleError) {
  SimDetectorConfig config;
  config.hard_jitter_gain = 0.0;  // the plain sigmas, for a closed-form check
  config.false_positive_rate = 0.0;
  config.class_confusion = 0.0;
  // The IoU the model gives an unclipped box (Monte Carlo on a unit box).
  Rng rng(99);
  double model = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double cx = rng.normal() * config.jitter, cy = rng.normal() * config.jitter;
    const double w = std::exp(rng.normal() * config.scale_error);
    const double h = std::exp(rng.normal() * config.scale_error);
    const cv::Rect2d a(-0.5, -0.5, 1, 1), b(cx - w / 2, cy - h / 2, w, h);
    const double inter = (a & b).area();
    model += inter / (a.area() + b.area() - inter);
  }
  model /= n;
  double sum = 0, count = 0, sum_all = 0, count_all = 0;
  for (int s = 0; s < kSeeds; ++s) {
    SimDetector detector(*dataset_, with_seed(config, 4000 + s));
    const cv::Size size = detector.image_size();
    for (size_t i = 0; i < detector.frame_count(); ++i) {
      const auto& t = detector.truth(i);
      const auto dets = detector.detect_frame(i);
      const auto m = match(t, dets, 0.1);
      for (size_t k = 0; k < t.size(); ++k) {
        if (m[k] < 0) continue;
        const double v = iou(t[k].rect(), dets[m[k]].box);
        sum_all += v;
        count_all += 1;
        // Boxes clear of the image border are never clipped.
        const double mx = 0.2 * (t[k].x2 - t[k].x1), my = 0.2 * (t[k].y2 - t[k].y1);
        if (t[k].x1 >= mx && t[k].y1 >= my && t[k].x2 <= size.width - mx &&
            t[k].y2 <= size.height - my) {
          sum += v;
          count += 1;
        }
      }
    }
  }
  std::cout << "[sim] mean IoU (jitter " << config.jitter << ", scale " << config.scale_error
            << "): model " << model << ", measured " << sum / count << " on " << count
            << " unclipped boxes, " << sum_all / count_all << " on all " << count_all << "\n";
  ASSERT_GT(count, 1000);
  EXPECT_NEAR(sum / count, model, 0.01);
  EXPECT_GT(sum_all / count_all, model - 0.01);  // clipping only helps
}

TEST_F(SimDetectorTest, WithoutJitterAndScaleErrorDetectedBoxesAreExact) {
  SimDetectorConfig config;
  config.jitter = 0.0;
  config.scale_error = 0.0;
  config.false_positive_rate = 0.0;
  size_t detected = 0;
  for (int s = 0; s < 20; ++s) {
    SimDetector detector(*dataset_, with_seed(config, 5000 + s));
    for (size_t i = 0; i < detector.frame_count(); ++i) {
      const auto& t = detector.truth(i);
      const auto dets = detector.detect_frame(i);
      const auto m = match(t, dets, 0.999);
      EXPECT_EQ(
          static_cast<size_t>(std::count_if(m.begin(), m.end(), [](int v) { return v >= 0; })),
          dets.size());
      for (size_t k = 0; k < t.size(); ++k)
        if (m[k] >= 0) {
          EXPECT_EQ(iou(t[k].rect(), dets[m[k]].box), 1.0);
        }
      detected += dets.size();
    }
  }
  EXPECT_GT(detected, 1000u);
}

TEST_F(SimDetectorTest, SmallAndOccludedBoxesAreMissedMoreAndScoreLower) {
  SimDetectorConfig config;
  config.false_positive_rate = 0.0;
  struct Bin {
    double n = 0, missed = 0, model = 0, conf = 0, detected = 0, iou = 0;
  } easy, small, occluded;
  for (int s = 0; s < kSeeds; ++s) {
    for (const std::string* dataset : {dataset_, patrol_}) {
      SimDetector detector(*dataset, with_seed(config, 6000 + s));
      for (size_t i = 0; i < detector.frame_count(); ++i) {
        const auto& t = detector.truth(i);
        const auto dets = detector.detect_frame(i);
        const auto m = match(t, dets, 0.1);
        for (size_t k = 0; k < t.size(); ++k) {
          const double sm = detector.smallness(t[k]), oc = detector.occlusion(t[k]);
          Bin* bin = nullptr;
          if (sm >= 0.3) {
            bin = &small;
          } else if (oc >= 0.4) {
            bin = &occluded;
          } else if (sm == 0.0 && oc < 0.1) {
            bin = &easy;
          }
          if (!bin) continue;
          bin->n += 1;
          bin->model += detector.miss_probability(t[k]);
          if (m[k] < 0) {
            bin->missed += 1;
          } else {
            bin->detected += 1;
            bin->conf += dets[m[k]].confidence;
            bin->iou += iou(t[k].rect(), dets[m[k]].box);
          }
        }
      }
    }
  }
  for (auto [name, bin] :
       {std::pair<const char*, Bin*>{"easy", &easy}, {"small", &small}, {"occluded", &occluded}}) {
    std::cout << "[sim] " << name << " boxes: " << bin->n / kSeeds << " per run, miss rate "
              << bin->missed / bin->n << " (model " << bin->model / bin->n << "), mean confidence "
              << bin->conf / bin->detected << ", mean IoU " << bin->iou / bin->detected << "\n";
    ASSERT_GT(bin->n, 1000) << name;
  }
  const double easy_miss = easy.missed / easy.n;
  for (const Bin* bin : {&easy, &small, &occluded}) {
    const double model = bin->model / bin->n;
    EXPECT_NEAR(bin->missed / bin->n, model, tolerance(model, bin->n, 0.005));
  }
  EXPECT_LT(easy_miss, config.miss_rate + 0.05 * config.occlusion_miss + 0.01);
  EXPECT_GT(small.missed / small.n, easy_miss + 0.1);
  EXPECT_GT(occluded.missed / occluded.n, easy_miss + 0.1);
  EXPECT_LT(small.conf / small.detected, easy.conf / easy.detected - 0.1);
  EXPECT_LT(occluded.conf / occluded.detected, easy.conf / easy.detected - 0.1);
  EXPECT_LT(small.iou / small.detected, easy.iou / easy.detected);
}

TEST_F(SimDetectorTest, ClassConfusionMatchesTheConfiguration) {
  SimDetectorConfig config;
  config.class_confusion = 0.25;
  config.false_positive_rate = 0.0;
  config.jitter = 0.0;
  config.scale_error = 0.0;
  double chairs = 0, carts = 0, others = 0, others_changed = 0;
  for (int s = 0; s < kSeeds / 4; ++s) {
    SimDetector detector(*dataset_, with_seed(config, 7000 + s));
    for (size_t i = 0; i < detector.frame_count(); ++i) {
      const auto& t = detector.truth(i);
      const auto dets = detector.detect_frame(i);
      const auto m = match(t, dets, 0.999);
      for (size_t k = 0; k < t.size(); ++k) {
        if (m[k] < 0) continue;
        const Detection& d = dets[m[k]];
        EXPECT_EQ(detector.class_names().at(d.class_id), d.class_name);
        if (t[k].class_name == "chair") {
          chairs += 1;
          carts += d.class_name == "cart";
          EXPECT_TRUE(d.class_name == "chair" || d.class_name == "cart");
        } else if (t[k].class_name == "person" || t[k].class_name == "monitor") {
          others += 1;  // classes without confusion partners
          others_changed += d.class_name != t[k].class_name;
        }
      }
    }
  }
  std::cout << "[sim] chair -> cart confusion: configured 0.25, measured " << carts / chairs
            << " over " << chairs << " detections\n";
  EXPECT_NEAR(carts / chairs, 0.25, tolerance(0.25, chairs));
  EXPECT_GT(others, 0);
  EXPECT_EQ(others_changed, 0);
}

TEST_F(SimDetectorTest, LatencyReturnsAnEarlierFramesDetections) {
  SimDetectorConfig lagging;
  lagging.latency_frames = 3;
  lagging.false_positive_rate = 0.5;
  SimDetectorConfig prompt = lagging;
  prompt.latency_frames = 0;
  SimDetector now(*dataset_, prompt), late(*dataset_, lagging);
  SimDetectorConfig perfect_late = lagging;
  perfect_late.perfect = true;
  SimDetector perfect(*dataset_, perfect_late);
  for (size_t i = 0; i < late.frame_count(); ++i) {
    const double t = late.frame_timestamp(i);
    const auto d = late.detect(cv::Mat(), t, static_cast<long>(i));
    const auto p = perfect.detect(cv::Mat(), t, static_cast<long>(i));
    if (i < 3) {
      EXPECT_TRUE(d.empty()) << i;
      EXPECT_TRUE(p.empty()) << i;
      continue;
    }
    const double t_lag = late.frame_timestamp(i - 3);
    EXPECT_TRUE(same(d, now.detect_frame(i - 3))) << i;
    EXPECT_TRUE(same(d, now.detect(cv::Mat(), t_lag, static_cast<long>(i - 3)))) << i;
    ASSERT_EQ(p.size(), late.truth(i - 3).size());
    for (size_t k = 0; k < p.size(); ++k) EXPECT_EQ(p[k].box, late.truth(i - 3)[k].rect());
  }
}

TEST_F(SimDetectorTest, SameSeedSameDetectionsOtherSeedDifferent) {
  SimDetectorConfig config;
  config.false_positive_rate = 0.3;
  SimDetector a(*dataset_, config), b(*dataset_, config), c(*dataset_, with_seed(config, 2));
  size_t differ = 0, total = 0;
  // Any call order: frames are independent.
  for (size_t i = a.frame_count(); i-- > 0;) {
    const double t = a.frame_timestamp(i);
    const auto da = a.detect(cv::Mat(), t, static_cast<long>(i));
    EXPECT_TRUE(same(da, b.detect_frame(i))) << i;
    EXPECT_TRUE(same(da, a.detect(cv::Mat(), t + 5e-5, static_cast<long>(i)))) << i;
    differ += !same(da, c.detect_frame(i));
    total += da.size();
  }
  EXPECT_GT(total, 0u);
  EXPECT_GE(differ, a.frame_count() / 2);
  EXPECT_NE(error_of([&] { a.detect(cv::Mat(), 12.0, 0); }).find("rgb.txt: no frame at timestamp"),
            std::string::npos);
}

TEST_F(SimDetectorTest, MissingOrMalformedFilesAreClearErrors) {
  // A copy of the dataset's text files only.
  const std::string dir = *root_ + "/broken";
  auto reset = [&] {
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const char* f : {"rgb.txt", "boxes.txt", "classes.txt", "calibration.yaml"})
      fs::copy_file(*dataset_ + "/" + f, dir + "/" + f);
  };
  reset();
  EXPECT_NO_THROW(SimDetector{dir});
  fs::remove(dir + "/boxes.txt");
  EXPECT_EQ(error_of([&] { SimDetector{dir}; }),
            dir + "/boxes.txt: cannot open file (the ground-truth boxes)");
  reset();
  fs::remove(dir + "/classes.txt");
  EXPECT_EQ(error_of([&] { SimDetector{dir}; }),
            dir + "/classes.txt: missing (the detectable classes, one a line)");
  reset();
  std::ofstream(dir + "/classes.txt") << "\n";
  EXPECT_EQ(error_of([&] { SimDetector{dir}; }),
            dir + "/classes.txt: class names file lists no class");
  reset();
  std::ofstream(dir + "/classes.txt") << "person\ndog\nperson\n";
  EXPECT_EQ(error_of([&] { SimDetector{dir}; }),
            dir + "/classes.txt: class 'person' is listed twice");

  // Malformed lines of boxes.txt: each error names the file and line 4 (the
  // first data line after the three comment lines).
  const double t0 = SimDetector(*dataset_).frame_timestamp(0);
  const std::string s = fmt::format("{:.6f}", t0);
  const struct {
    std::string line, problem;
  } cases[] = {
      {s + " 22 desk 1 2 3 4 5",
       "expected 9 fields (timestamp id class x1 y1 x2 y2 "
       "visible_pixels moving), found 8"},
      {s + " 22 horse 1 2 30 40 5 0", "class 'horse' is not in classes.txt"},
      {s + " 22 desk 1 2 3.5 4 5 0", "x2 '3.5' is not an integer"},
      {s + " 22 desk 10 2 3 40 5 0", "box 10 2 3 40 is empty or outside the image"},
      {s + " 22 desk 10 2 300 40 5 0", "box 10 2 300 40 is outside the 160x120 image"},
      {s + " 22 desk 1 2 3 4 5 0", "visible_pixels 5 is not in [1, box area 4]"},
      {s + " 22 desk 1 2 3 4 2 7", "moving '7' is not 0 or 1"},
      {"12.5 22 desk 1 2 3 4 2 0", "timestamp 12.500000 is not a frame of rgb.txt"},
      {"nan 22 desk 1 2 3 4 2 0", "timestamp 'nan' is not a number"},
  };
  for (const auto& c : cases) {
    reset();
    std::ofstream(dir + "/boxes.txt") << "# a\n# b\n# c\n" << c.line << "\n";
    EXPECT_EQ(error_of([&] { SimDetector{dir}; }), dir + "/boxes.txt:4: " + c.problem) << c.line;
  }
  reset();
  fs::remove(dir + "/calibration.yaml");
  EXPECT_NE(error_of([&] { SimDetector{dir}; }).find(dir + "/calibration.yaml: cannot open file"),
            std::string::npos);
  reset();
  fs::remove(dir + "/rgb.txt");
  EXPECT_THAT(error_of([&] { SimDetector{dir}; }), ::testing::HasSubstr(dir + "/rgb.txt"));
  EXPECT_EQ(error_of([&] { SimDetector{*root_ + "/nowhere"}; }),
            *root_ + "/nowhere: not a dataset folder");
  SimDetectorConfig bad;
  bad.miss_rate = 2;
  EXPECT_EQ(error_of([&] { SimDetector(*dataset_, bad); }),
            "simulated detector config: 'miss_rate' = 2 is outside [0, 1]");
}

TEST_F(SimDetectorTest, FitRecoversTheConfigurationFromItsOwnDetections) {
  // What `depot eval calibrate` does, on the simulated detector with known
  // parameters: match its detections to the boxes at IoU >= 0.5, fit.
  SimDetectorConfig known;
  known.miss_rate = 0.15;
  known.class_miss_rate = {{"person", 0.05}};
  known.small_miss_boost = 0.6;
  known.small_area = 0.02;
  known.occlusion_miss = 0.4;
  known.jitter = 0.05;
  known.scale_error = 0.08;
  known.hard_jitter_gain = 1.0;
  known.max_confidence = 0.9;
  known.confidence_drop = 0.5;
  known.confidence_noise = 0.05;
  known.false_positive_rate = 0.3;
  known.false_positive_max_confidence = 0.6;
  known.class_confusion = 0.0;
  known.class_confusion_rate = {{"cat", 0.2}};
  known.confusions = {{"cat", {"dog"}}};
  perception::FitData data;
  data.min_confidence = known.min_confidence;
  for (int s = 0; s < 100; ++s) {
    for (const std::string* dataset : {dataset_, patrol_}) {
      SimDetector detector(*dataset, with_seed(known, 9000 + s));
      const double image_area = detector.image_size().area();
      for (size_t i = 0; i < detector.frame_count(); ++i) {
        const auto& t = detector.truth(i);
        const auto dets = detector.detect_frame(i);
        const auto m = match(t, dets, 0.5);
        std::vector<bool> used(dets.size(), false);
        for (size_t k = 0; k < t.size(); ++k) {
          perception::FitBox b;
          b.truth_class = t[k].class_name;
          b.area = t[k].area();
          b.image_area = image_area;
          b.occlusion = detector.occlusion(t[k]);
          if (m[k] >= 0) {
            const Detection& d = dets[m[k]];
            used[m[k]] = true;
            const cv::Rect2f r = t[k].rect();
            b.detected_class = d.class_name;
            b.dx = (d.box.x + d.box.width / 2 - r.x - r.width / 2) / r.width;
            b.dy = (d.box.y + d.box.height / 2 - r.y - r.height / 2) / r.height;
            b.log_w = std::log(d.box.width / r.width);
            b.log_h = std::log(d.box.height / r.height);
            b.confidence = d.confidence;
          }
          data.boxes.push_back(b);
        }
        for (size_t d = 0; d < dets.size(); ++d)
          if (!used[d]) data.false_positive_confidences.push_back(dets[d].confidence);
        ++data.frames;
      }
    }
  }
  const perception::SimDetectorFit fit =
      perception::fit_sim_detector(data, SimDetectorConfig{}, "sim");
  const SimDetectorConfig& c = fit.config;
  std::cout << "[sim] fit on " << fit.boxes << " boxes: miss person "
            << c.class_miss_rate.at("person") << " (0.05), pig " << c.class_miss_rate.at("pig")
            << " (0.15), boost " << c.small_miss_boost << " (0.6), small_area " << c.small_area
            << " (0.02), occlusion " << c.occlusion_miss << " (0.4), jitter " << c.jitter
            << " (0.05), scale " << c.scale_error << " (0.08), gain " << c.hard_jitter_gain
            << " (1), max conf " << c.max_confidence << " (0.9), drop " << c.confidence_drop
            << " (0.5), noise " << c.confidence_noise << " (0.05), fp " << c.false_positive_rate
            << " (0.3), fp max conf " << c.false_positive_max_confidence << " (0.6), miss_rate "
            << c.miss_rate << ", desk " << c.class_miss_rate.at("desk") << ", cat confusion "
            << c.class_confusion_rate.at("cat") << " (0.2)\n";
  EXPECT_NEAR(c.class_miss_rate.at("person"), 0.05, 0.03);
  EXPECT_NEAR(c.class_miss_rate.at("pig"), 0.15, 0.05);
  EXPECT_NEAR(c.class_miss_rate.at("desk"), 0.15, 0.05);
  EXPECT_NEAR(c.small_miss_boost, 0.6, 0.1);
  EXPECT_NEAR(c.small_area, 0.02, 0.006);
  EXPECT_NEAR(c.occlusion_miss, 0.4, 0.08);
  EXPECT_NEAR(c.jitter, 0.05, 0.005);
  EXPECT_NEAR(c.scale_error, 0.08, 0.008);
  EXPECT_NEAR(c.hard_jitter_gain, 1.0, 0.35);
  EXPECT_NEAR(c.max_confidence, 0.9, 0.02);
  EXPECT_NEAR(c.confidence_drop, 0.5, 0.06);
  EXPECT_NEAR(c.confidence_noise, 0.05, 0.01);
  EXPECT_NEAR(c.false_positive_rate, 0.3, 0.05);
  EXPECT_NEAR(c.false_positive_max_confidence, 0.6, 0.05);
  ASSERT_EQ(c.confusions.size(), 1u);
  EXPECT_EQ(c.confusions.at("cat"), std::vector<std::string>{"dog"});
  EXPECT_NEAR(c.class_confusion_rate.at("cat"), 0.2, 0.05);
}

TEST_F(SimDetectorTest, PrecomputedDetectionsReplayThroughAFile) {
  SimDetector detector(*dataset_);
  std::vector<DetectionFrame> frames;
  for (size_t i = 0; i < detector.frame_count(); ++i)
    frames.push_back({detector.frame_timestamp(i), detector.detect_frame(i)});
  const std::string path = *root_ + "/detections.txt";
  write_detections_file(path, frames);
  FileDetector replay(path, detector.class_names());
  for (size_t i = 0; i < detector.frame_count(); ++i) {
    const auto want = detector.detect(cv::Mat(), detector.frame_timestamp(i), static_cast<long>(i));
    const auto got = replay.detect(cv::Mat(), detector.frame_timestamp(i), static_cast<long>(i));
    ASSERT_EQ(got.size(), want.size()) << i;
    for (size_t k = 0; k < got.size(); ++k) {
      EXPECT_EQ(got[k].class_name, want[k].class_name);
      EXPECT_EQ(got[k].class_id, want[k].class_id);
      EXPECT_EQ(got[k].confidence, want[k].confidence);
      EXPECT_EQ(got[k].box.x, want[k].box.x);
      EXPECT_EQ(got[k].box.y, want[k].box.y);
      EXPECT_NEAR(got[k].box.width, want[k].box.width, 1e-4);
      EXPECT_NEAR(got[k].box.height, want[k].box.height, 1e-4);
    }
  }
}

}  // namespace
}  // namespace depot::slam
