#include "slam/feature/orb_extractor.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iostream>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "slam/feature/descriptor_distance.h"

namespace depot::slam {
namespace {

namespace fs = std::filesystem;

const fs::path kFrameDir = fs::path(DEPOT_SHARED_DATA) / "tum/fr3_walking_xyz_frame/rgb";

// The real TUM fr3/walking_xyz RGB frame (640x480) as grayscale, or empty.
cv::Mat load_frame() {
  if (!fs::is_directory(kFrameDir)) return {};
  std::vector<fs::path> pngs;
  for (const auto& e : fs::directory_iterator(kFrameDir)) {
    if (e.path().extension() == ".png") pngs.push_back(e.path());
  }
  if (pngs.empty()) return {};
  std::sort(pngs.begin(), pngs.end());
  return cv::imread(pngs.front().string(), cv::IMREAD_GRAYSCALE);
}

class OrbExtractorTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { frame_ = new cv::Mat(load_frame()); }
  static void TearDownTestSuite() {
    delete frame_;
    frame_ = nullptr;
  }
  void SetUp() override {
    if (frame_->empty()) {
      GTEST_SKIP() << "real frame absent: no readable *.png in " << kFrameDir
                   << " (set DEPOT_SHARED_DATA to the shared data directory)";
    }
  }
  static const cv::Mat& frame() { return *frame_; }
  static cv::Mat* frame_;
};
cv::Mat* OrbExtractorTest::frame_ = nullptr;

struct Features {
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
};

Features extract(const cv::Mat& img, const OrbParams& params = {}, const cv::Mat& mask = {}) {
  OrbExtractor orb(params);
  Features f;
  orb.extract(img, mask, f.kps, f.desc);
  return f;
}

// Brute-force Hamming matching a -> b with Lowe's ratio test; pairs (ia, ib).
std::vector<std::pair<int, int>> match_ratio(const cv::Mat& a, const cv::Mat& b, double ratio) {
  std::vector<std::pair<int, int>> out;
  for (int i = 0; i < a.rows; ++i) {
    int best = 257;
    int second = 257;
    int best_j = -1;
    for (int j = 0; j < b.rows; ++j) {
      const int d = descriptor_distance(a.ptr<std::uint8_t>(i), b.ptr<std::uint8_t>(j));
      if (d < best) {
        second = best;
        best = d;
        best_j = j;
      } else if (d < second) {
        second = d;
      }
    }
    if (best_j >= 0 && best < ratio * second) out.emplace_back(i, best_j);
  }
  return out;
}

// Fraction of matches whose keypoint in b lies within tol px of where the known
// map sends its keypoint in a.
double inlier_fraction(const Features& a, const Features& b,
                       const std::vector<std::pair<int, int>>& matches,
                       const std::function<cv::Point2f(cv::Point2f)>& map, double tol,
                       std::vector<std::pair<int, int>>* inliers = nullptr) {
  int good = 0;
  for (const auto& [i, j] : matches) {
    const cv::Point2f d = map(a.kps[i].pt) - b.kps[j].pt;
    if (std::hypot(d.x, d.y) < tol) {
      ++good;
      if (inliers) inliers->emplace_back(i, j);
    }
  }
  return matches.empty() ? 0.0 : double(good) / matches.size();
}

// Keypoint counts on a cols x rows grid over the image.
std::vector<int> grid_counts(const std::vector<cv::KeyPoint>& kps, cv::Size img, int cols,
                             int rows) {
  std::vector<int> counts(static_cast<size_t>(cols) * rows, 0);
  for (const auto& kp : kps) {
    const int cx = std::clamp(static_cast<int>(kp.pt.x * cols / img.width), 0, cols - 1);
    const int cy = std::clamp(static_cast<int>(kp.pt.y * rows / img.height), 0, rows - 1);
    ++counts[static_cast<size_t>(cy) * cols + cx];
  }
  return counts;
}

double coefficient_of_variation(const std::vector<int>& v) {
  const double mean = std::accumulate(v.begin(), v.end(), 0.0) / v.size();
  double var = 0;
  for (int x : v) var += (x - mean) * (x - mean);
  return std::sqrt(var / v.size()) / mean;
}

// Message of the depot::Error thrown by f, or "" when none is thrown.
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST_F(OrbExtractorTest, CountIsWithinTenPercentOfTheBudget) {
  for (int n : {500, 1000, 2000}) {
    OrbParams p;
    p.n_features = n;
    const Features f = extract(frame(), p);
    EXPECT_GE(static_cast<int>(f.kps.size()), 0.9 * n) << "n_features " << n;
    EXPECT_LE(static_cast<int>(f.kps.size()), n) << "n_features " << n;
    EXPECT_EQ(f.desc.rows, static_cast<int>(f.kps.size()));
    EXPECT_EQ(f.desc.cols, kDescriptorBytes);
    EXPECT_EQ(f.desc.type(), CV_8UC1);
  }
}

TEST_F(OrbExtractorTest, KeypointsAreWellFormed) {
  OrbExtractor orb(OrbParams{});
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  orb.extract(frame(), cv::Mat(), kps, desc);
  ASSERT_FALSE(kps.empty());
  int prev_octave = 0;
  for (const auto& kp : kps) {
    ASSERT_GE(kp.octave, prev_octave) << "keypoints are grouped by level";
    prev_octave = kp.octave;
    ASSERT_LT(kp.octave, orb.n_levels());
    // Centres stay kEdgeThreshold level pixels inside the level image.
    const float margin = (OrbExtractor::kEdgeThreshold - 1) * orb.scale_factors()[kp.octave];
    EXPECT_GE(kp.pt.x, margin);
    EXPECT_GE(kp.pt.y, margin);
    EXPECT_LE(kp.pt.x, frame().cols - 1 - margin);
    EXPECT_LE(kp.pt.y, frame().rows - 1 - margin);
    EXPECT_FLOAT_EQ(kp.size, OrbExtractor::kPatchSize * orb.scale_factors()[kp.octave]);
    EXPECT_GE(kp.angle, 0.f);
    EXPECT_LT(kp.angle, 360.f);
    EXPECT_GE(kp.response, static_cast<float>(orb.params().min_fast));
  }
  // Deterministic, also when the same instance runs again.
  std::vector<cv::KeyPoint> again;
  cv::Mat desc_again;
  orb.extract(frame(), cv::Mat(), again, desc_again);
  ASSERT_EQ(again.size(), kps.size());
  for (size_t i = 0; i < kps.size(); ++i) {
    EXPECT_EQ(again[i].pt, kps[i].pt);
    EXPECT_EQ(again[i].angle, kps[i].angle);
  }
  EXPECT_EQ(cv::norm(desc, desc_again, cv::NORM_HAMMING), 0.0);
  // The pyramid of the last call is exposed with the expected level sizes.
  ASSERT_EQ(static_cast<int>(orb.pyramid().size()), orb.n_levels());
  EXPECT_EQ(orb.pyramid()[0].size(), frame().size());
  EXPECT_EQ(orb.pyramid()[3].cols, cvRound(frame().cols / std::pow(1.2f, 3)));
}

TEST_F(OrbExtractorTest, NonContinuousRoiGivesTheSameResultAsItsCopy) {
  const cv::Rect roi(40, 30, 500, 400);
  const Features a = extract(frame()(roi));
  const Features b = extract(frame()(roi).clone());
  ASSERT_EQ(a.kps.size(), b.kps.size());
  for (size_t i = 0; i < a.kps.size(); ++i) EXPECT_EQ(a.kps[i].pt, b.kps[i].pt);
  EXPECT_EQ(cv::norm(a.desc, b.desc, cv::NORM_HAMMING), 0.0);
}

TEST_F(OrbExtractorTest, SpreadsKeypointsMoreEvenlyThanPlainOrb) {
  constexpr int kCols = 8;
  constexpr int kRows = 6;
  const Features ours = extract(frame());
  std::vector<cv::KeyPoint> plain;
  cv::ORB::create(1000)->detect(frame(), plain);

  // Textured cells: cells with FAST corners on the full-resolution image.
  std::vector<cv::KeyPoint> fast;
  cv::FAST(frame(), fast, 20, true);
  const std::vector<int> texture = grid_counts(fast, frame().size(), kCols, kRows);
  const std::vector<int> c_ours = grid_counts(ours.kps, frame().size(), kCols, kRows);
  const std::vector<int> c_plain = grid_counts(plain, frame().size(), kCols, kRows);
  int textured = 0;
  int covered = 0;
  int covered_plain = 0;
  for (size_t i = 0; i < texture.size(); ++i) {
    if (texture[i] == 0) continue;
    ++textured;
    covered += c_ours[i] > 0;
    covered_plain += c_plain[i] > 0;
  }
  const double share_ours =
      double(*std::max_element(c_ours.begin(), c_ours.end())) / ours.kps.size();
  const double share_plain =
      double(*std::max_element(c_plain.begin(), c_plain.end())) / plain.size();
  const double cv_ours = coefficient_of_variation(c_ours);
  const double cv_plain = coefficient_of_variation(c_plain);
  std::cout << "textured cells " << textured << "/" << texture.size() << ", covered: ours "
            << covered << ", cv::ORB " << covered_plain << "; largest cell share: ours "
            << share_ours << ", cv::ORB " << share_plain << "; CV of cell counts: ours " << cv_ours
            << ", cv::ORB " << cv_plain << "\n";

  ASSERT_GT(textured, kCols * kRows / 2) << "the real frame is textured almost everywhere";
  EXPECT_GE(covered, 0.8 * textured);
  EXPECT_LT(cv_ours, 0.75 * cv_plain);
  EXPECT_LT(share_ours, 0.6 * share_plain);
}

TEST_F(OrbExtractorTest, MatchesUnderThirtyDegreeRotation) {
  const cv::Point2f centre((frame().cols - 1) / 2.f, (frame().rows - 1) / 2.f);
  const cv::Mat m = cv::getRotationMatrix2D(centre, 30.0, 1.0);  // CV_64F 2x3
  cv::Mat rotated;
  cv::warpAffine(frame(), rotated, m, frame().size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  const Features a = extract(frame());
  const Features b = extract(rotated);
  const auto matches = match_ratio(a.desc, b.desc, 0.8);
  auto map = [&](cv::Point2f p) {
    return cv::Point2f(static_cast<float>(m.at<double>(0, 0) * p.x + m.at<double>(0, 1) * p.y +
                                          m.at<double>(0, 2)),
                       static_cast<float>(m.at<double>(1, 0) * p.x + m.at<double>(1, 1) * p.y +
                                          m.at<double>(1, 2)));
  };
  std::vector<std::pair<int, int>> inliers;
  const double frac = inlier_fraction(a, b, matches, map, 3.0, &inliers);
  // Steered orientation: image content turned by +30 deg (counter-clockwise on
  // screen, y down) lowers the keypoint angle by 30 deg.
  std::vector<double> angle_err;
  for (const auto& [i, j] : inliers) {
    const double d = std::remainder(b.kps[j].angle - a.kps[i].angle + 30.0, 360.0);
    angle_err.push_back(std::abs(d));
  }
  std::sort(angle_err.begin(), angle_err.end());
  const double median_angle_err = angle_err.empty() ? 180.0 : angle_err[angle_err.size() / 2];
  std::cout << "rotation 30 deg: " << matches.size() << " ratio-test matches, " << inliers.size()
            << " within 3 px (" << 100 * frac << " %), median angle error " << median_angle_err
            << " deg\n";
  EXPECT_GE(matches.size(), 150u);
  EXPECT_GE(frac, 0.5);
  EXPECT_LT(median_angle_err, 5.0);
}

TEST_F(OrbExtractorTest, MatchesUnderOneAndAHalfScale) {
  cv::Mat big;
  cv::resize(frame(), big, cv::Size(), 1.5, 1.5, cv::INTER_LINEAR);
  const Features a = extract(frame());
  const Features b = extract(big);
  const auto matches = match_ratio(a.desc, b.desc, 0.8);
  auto map = [](cv::Point2f p) {
    return (p + cv::Point2f(0.5f, 0.5f)) * 1.5f - cv::Point2f(0.5f, 0.5f);
  };
  std::vector<std::pair<int, int>> inliers;
  const double frac = inlier_fraction(a, b, matches, map, 3.0, &inliers);
  // 1.5 = 1.2^2.2: a corner found at level l shows up about two levels higher.
  double octave_shift = 0;
  for (const auto& [i, j] : inliers) octave_shift += b.kps[j].octave - a.kps[i].octave;
  if (!inliers.empty()) octave_shift /= inliers.size();
  std::cout << "scale 1.5x: " << matches.size() << " ratio-test matches, " << inliers.size()
            << " within 3 px (" << 100 * frac << " %), mean octave shift " << octave_shift << "\n";
  EXPECT_GE(matches.size(), 150u);
  EXPECT_GE(frac, 0.5);
  EXPECT_GT(octave_shift, 1.5);
  EXPECT_LT(octave_shift, 3.0);
}

TEST_F(OrbExtractorTest, DescriptorsAgreeWithOpenCvOrbOnTheSameKeypoints) {
  // Same test pairs, steering and 7x7 sigma-2 smoothing as cv::ORB: computing
  // cv::ORB's descriptor on our level-0 keypoints (with our angles) must give the
  // same bits up to float rounding of the rotated test points.
  const Features ours = extract(frame());
  std::vector<cv::KeyPoint> level0;
  std::vector<int> rows;
  for (size_t i = 0; i < ours.kps.size(); ++i) {
    if (ours.kps[i].octave != 0) continue;
    level0.push_back(ours.kps[i]);
    level0.back().class_id = static_cast<int>(i);  // survives cv::ORB's border filter
  }
  ASSERT_GT(level0.size(), 100u);
  cv::Mat theirs;
  cv::ORB::create(1000, 1.2f, 8, OrbExtractor::kEdgeThreshold, 0, 2, cv::ORB::HARRIS_SCORE,
                  OrbExtractor::kPatchSize)
      ->compute(frame(), level0, theirs);
  ASSERT_GT(level0.size(), 100u);
  int identical = 0;
  double bits = 0;
  for (size_t k = 0; k < level0.size(); ++k) {
    const int d = descriptor_distance(ours.desc.ptr<std::uint8_t>(level0[k].class_id),
                                      theirs.ptr<std::uint8_t>(static_cast<int>(k)));
    identical += d == 0;
    bits += d;
  }
  bits /= level0.size();
  std::cout << "vs cv::ORB descriptor: " << identical << "/" << level0.size() << " identical, mean "
            << bits << " differing bits\n";
  EXPECT_LT(bits, 2.0);
  EXPECT_GE(identical, 0.6 * level0.size());
}

TEST_F(OrbExtractorTest, OctavesFollowTheGeometricSeries) {
  OrbExtractor orb(OrbParams{});
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  orb.extract(frame(), cv::Mat(), kps, desc);
  std::vector<int> per_level(orb.n_levels(), 0);
  for (const auto& kp : kps) ++per_level[kp.octave];
  const std::vector<int>& budget = orb.features_per_level();
  for (int l = 0; l < orb.n_levels(); ++l) {
    std::cout << "level " << l << ": " << per_level[l] << " / " << budget[l] << "\n";
    EXPECT_LE(per_level[l], budget[l]) << "level " << l;
    EXPECT_GE(per_level[l], 0.85 * budget[l]) << "level " << l;
  }
  // Budget itself: ratio 1/1.2 between levels, summing to n_features.
  EXPECT_EQ(std::accumulate(budget.begin(), budget.end(), 0), 1000);
  for (int l = 0; l + 2 < orb.n_levels(); ++l) {
    EXPECT_NEAR(double(budget[l + 1]) / budget[l], 1 / 1.2, 0.02) << "level " << l;
  }
  EXPECT_EQ(budget[0], 217);
}

TEST_F(OrbExtractorTest, MaskExcludesKeypointsButKeepsTheBudget) {
  cv::Mat mask(frame().size(), CV_8UC1, cv::Scalar(255));
  mask(cv::Rect(0, 0, frame().cols / 2, frame().rows)).setTo(0);
  const Features f = extract(frame(), OrbParams{}, mask);
  ASSERT_FALSE(f.kps.empty());
  for (const auto& kp : f.kps) {
    ASSERT_NE(mask.at<std::uint8_t>(cvRound(kp.pt.y), cvRound(kp.pt.x)), 0)
        << "keypoint at " << kp.pt << " in the masked half";
  }
  // The budget moves to the allowed half (the right half alone is textured enough).
  EXPECT_GE(static_cast<int>(f.kps.size()), 800);
}

TEST_F(OrbExtractorTest, HandlesPortraitImagesAndOtherPyramids) {
  // Portrait: the quadtree's initial boxes stack vertically (ORB-SLAM2 would
  // divide by zero there).
  cv::Mat portrait;
  cv::rotate(frame(), portrait, cv::ROTATE_90_CLOCKWISE);
  const Features p = extract(portrait);
  EXPECT_GE(p.kps.size(), 900u);
  EXPECT_LE(p.kps.size(), 1000u);
  for (const auto& kp : p.kps) {
    ASSERT_TRUE(cv::Rect(0, 0, portrait.cols, portrait.rows).contains(kp.pt));
  }

  OrbParams single;
  single.n_levels = 1;
  const Features s = extract(frame(), single);
  EXPECT_GE(s.kps.size(), 900u);
  for (const auto& kp : s.kps) ASSERT_EQ(kp.octave, 0);

  OrbParams coarse;
  coarse.scale_factor = 2.f;
  coarse.n_levels = 4;
  coarse.n_features = 600;
  const Features c = extract(frame(), coarse);
  EXPECT_GE(c.kps.size(), 540u);
  EXPECT_LE(c.kps.size(), 600u);
}

TEST(OrbExtractor, AccessorsFollowTheScaleFactor) {
  OrbParams p;
  p.scale_factor = 1.5f;
  p.n_levels = 4;
  OrbExtractor orb(p);
  ASSERT_EQ(orb.scale_factors().size(), 4u);
  for (int l = 0; l < 4; ++l) {
    const float s = std::pow(1.5f, static_cast<float>(l));
    EXPECT_FLOAT_EQ(orb.scale_factors()[l], s);
    EXPECT_FLOAT_EQ(orb.inv_scale_factors()[l], 1 / s);
    EXPECT_FLOAT_EQ(orb.level_sigma2()[l], s * s);
    EXPECT_FLOAT_EQ(orb.inv_level_sigma2()[l], 1 / (s * s));
  }
  EXPECT_EQ(std::accumulate(orb.features_per_level().begin(), orb.features_per_level().end(), 0),
            1000);
}

TEST(OrbExtractor, TinyAndFlatImagesGiveNoKeypoints) {
  OrbExtractor orb(OrbParams{});
  std::vector<cv::KeyPoint> kps{cv::KeyPoint(1, 1, 1)};
  cv::Mat desc(3, 32, CV_8UC1);
  orb.extract(cv::Mat(20, 30, CV_8UC1, cv::Scalar(7)), cv::Mat(), kps, desc);
  EXPECT_TRUE(kps.empty());
  EXPECT_TRUE(desc.empty());
  orb.extract(cv::Mat(480, 640, CV_8UC1, cv::Scalar(7)), cv::Mat(), kps, desc);
  EXPECT_TRUE(kps.empty());
  EXPECT_TRUE(desc.empty());
}

TEST(OrbExtractor, RejectsBadParameters) {
  auto with = [](const std::function<void(OrbParams&)>& edit) {
    return error_of([&] {
      OrbParams p;
      edit(p);
      OrbExtractor orb(p);
    });
  };
  EXPECT_EQ(with([](OrbParams&) {}), "");
  EXPECT_EQ(with([](OrbParams& p) { p.n_levels = 1; }), "");
  EXPECT_EQ(with([](OrbParams& p) { p.n_levels = 16; }), "");
  EXPECT_EQ(with([](OrbParams& p) { p.scale_factor = 2.f; }), "");

  EXPECT_EQ(with([](OrbParams& p) { p.n_levels = 0; }),
            "OrbExtractor: n_levels must be in [1, 16], got 0");
  EXPECT_EQ(with([](OrbParams& p) { p.n_levels = 17; }),
            "OrbExtractor: n_levels must be in [1, 16], got 17");
  EXPECT_EQ(with([](OrbParams& p) { p.scale_factor = 1.f; }),
            "OrbExtractor: scale_factor must be in (1, 2], got 1");
  EXPECT_EQ(with([](OrbParams& p) { p.scale_factor = 2.5f; }),
            "OrbExtractor: scale_factor must be in (1, 2], got 2.5");
  EXPECT_EQ(with([](OrbParams& p) {
              p.scale_factor = std::nanf("");
            }).rfind("OrbExtractor: scale_factor must be in (1, 2]", 0),
            0u);
  EXPECT_EQ(with([](OrbParams& p) { p.n_features = 0; }),
            "OrbExtractor: n_features must be > 0, got 0");
  EXPECT_EQ(with([](OrbParams& p) { p.min_fast = 0; }),
            "OrbExtractor: min_fast must be in [1, 254], got 0");
  EXPECT_EQ(with([](OrbParams& p) { p.ini_fast = 5; }),
            "OrbExtractor: ini_fast must be in [min_fast, 254] = [7, 254], got 5");
}

TEST(OrbExtractor, RejectsBadImagesAndMasks) {
  OrbExtractor orb(OrbParams{});
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  auto run = [&](const cv::Mat& img, const cv::Mat& mask) {
    return error_of([&] { orb.extract(img, mask, kps, desc); });
  };
  const cv::Mat gray(120, 160, CV_8UC1, cv::Scalar(0));
  EXPECT_EQ(run(cv::Mat(), cv::Mat()), "OrbExtractor::extract: image is empty");
  EXPECT_EQ(run(cv::Mat(120, 160, CV_8UC3), cv::Mat()),
            "OrbExtractor::extract: image must be CV_8UC1 (8-bit grayscale), got type CV_8UC3");
  EXPECT_EQ(run(cv::Mat(120, 160, CV_16UC1), cv::Mat()),
            "OrbExtractor::extract: image must be CV_8UC1 (8-bit grayscale), got type CV_16UC1");
  EXPECT_EQ(run(gray, cv::Mat(100, 160, CV_8UC1)),
            "OrbExtractor::extract: mask must be empty or CV_8UC1 of the image size 160x120, got "
            "CV_8UC1 160x100");
  EXPECT_EQ(run(gray, cv::Mat(120, 160, CV_32FC1)),
            "OrbExtractor::extract: mask must be empty or CV_8UC1 of the image size 160x120, got "
            "CV_32FC1 160x120");
  EXPECT_EQ(run(gray, cv::Mat(120, 160, CV_8UC1, cv::Scalar(1))), "");
}

}  // namespace
}  // namespace depot::slam
