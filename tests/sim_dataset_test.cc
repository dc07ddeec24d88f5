// Dataset-level properties: TUM layout that existing tools read, determinism,
// replay of a real hand-held trajectory, and real association timestamps.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/tum_io.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace fs = std::filesystem;

namespace depot::test {
namespace {

const std::string kShared = DEPOT_SHARED_DATA;

TEST(SimDataset, WritesAStandardTumFolder) {
  std::string root = render_small({"depot_walking_xyz", 8, 160, false});
  for (const char* f :
       {"rgb.txt", "depth.txt", "associations.txt", "groundtruth.txt", "calibration.yaml",
        "labels.txt", "objects.json", "object_poses.txt", "boxes.txt", "classes.txt"})
    EXPECT_TRUE(fs::is_regular_file(fs::path(root) / f)) << f;
  Dataset d = read_dataset(root);
  ASSERT_EQ(d.frames.size(), 8u);
  ASSERT_EQ(d.groundtruth.size(), 8u);
  auto rgb_list = read_file_list(root + "/rgb.txt");
  auto depth_list = read_file_list(root + "/depth.txt");
  for (size_t i = 0; i < d.frames.size(); ++i) {
    EXPECT_EQ(rgb_list[i].path, d.frames[i].rgb_path);
    EXPECT_EQ(depth_list[i].path, d.frames[i].depth_path);
    EXPECT_NEAR(d.groundtruth[i].timestamp, d.frames[i].rgb_timestamp, 1e-6);
    cv::Mat rgb = d.rgb(i);
    EXPECT_EQ(rgb.type(), CV_8UC3);
    EXPECT_EQ(rgb.cols, 160);
    cv::Mat depth = cv::imread(root + "/" + d.frames[i].depth_path, cv::IMREAD_UNCHANGED);
    EXPECT_EQ(depth.type(), CV_16UC1);
  }
  // Timestamps come from the real fr3/walking_xyz association file (with its
  // real rgb/depth jitter).
  auto real = read_associations(kShared + "/tum/fr3_associations/fr3_walking_xyz.txt");
  for (size_t i = 0; i < d.frames.size(); ++i) {
    EXPECT_NEAR(d.frames[i].rgb_timestamp, real[i].rgb_timestamp, 1e-6);
    EXPECT_NEAR(d.frames[i].depth_timestamp, real[i].depth_timestamp, 1e-6);
  }
}

TEST(SimDataset, SensorModelDropsFarDepthAndAddsNoise) {
  std::string noisy = render_small({"depot_static", 2, 320, false});
  std::string ideal = render_small({"depot_static", 2, 320, true});
  Dataset n = read_dataset(noisy), i = read_dataset(ideal);
  cv::Mat dn = n.depth_metres(0), di = i.depth_metres(0);
  int far_valid = 0, near_total = 0, near_changed = 0;
  double sum_sq_near = 0, sum_sq_far = 0;
  int count_near = 0, count_far = 0;
  for (int y = 0; y < dn.rows; ++y)
    for (int x = 0; x < dn.cols; ++x) {
      const float zi = di.at<float>(y, x), zn = dn.at<float>(y, x);
      if (zi > 4.6f && zn > 0) ++far_valid;
      if (zi > 1.5f && zi < 2.2f && zn > 0) {
        ++near_total;
        near_changed += std::abs(zn - zi) > 1e-4f;
        sum_sq_near += (zn - zi) * (zn - zi), ++count_near;
      }
      if (zi > 3.4f && zi < 4.2f && zn > 0) sum_sq_far += (zn - zi) * (zn - zi), ++count_far;
    }
  EXPECT_EQ(far_valid, 0) << "no depth beyond the sensor range";
  ASSERT_GT(count_near, 100);
  ASSERT_GT(count_far, 100);
  EXPECT_GT(near_changed, near_total / 2);
  const double sigma_near = std::sqrt(sum_sq_near / count_near),
               sigma_far = std::sqrt(sum_sq_far / count_far);
  // Noise grows with depth squared: ~(3.8 / 1.85)^2 = 4x between the bands.
  EXPECT_GT(sigma_far / sigma_near, 2.5) << sigma_near << " " << sigma_far;
  EXPECT_LT(sigma_near, 0.01);
}

TEST(SimDataset, SameSeedGivesByteIdenticalDatasets) {
  std::string a = render_small({"depot_walking_xyz", 12, 160, false, 42});
  std::string b = render_small({"depot_walking_xyz", 12, 160, false, 42});
  EXPECT_EQ(compare_trees(a, b), "");
  std::string c = render_small({"depot_walking_xyz", 12, 160, false, 43});
  EXPECT_NE(compare_trees(a, c), "") << "a different seed must change the data";
}

// #27's worlds: a generated hall, carried goods and a crowd (its simulated
// tracks) are drawn from the seed alone.
TEST(SimDataset, GeneratedHallsCarriersAndCrowdsAreByteIdenticalForOneSeed) {
  for (const char* scenario : {"depot_procedural_patrol", "depot_carry", "depot_crowd"}) {
    const std::string a = render_small({scenario, 8, 96, false, 5});
    const std::string b = render_small({scenario, 8, 96, false, 5});
    EXPECT_EQ(compare_trees(a, b), "") << scenario;
    const std::string c = render_small({scenario, 8, 96, false, 6});
    EXPECT_NE(compare_trees(a, c), "") << scenario << ": a different seed must change the data";
  }
}

TEST(SimDataset, ReplayingARealTrajectoryReproducesIt) {
  const std::string gt = kShared + "/tum/fr1_xyz_trajectory/groundtruth.txt";
  if (!fs::exists(gt)) GTEST_SKIP() << "shared data missing: " << gt;
  const std::string yaml = temp_path("replay") + ".yaml";
  std::ofstream(yaml) << "name: replay_fr1_xyz\n"
                      << "scene: " << DEPOT_SOURCE_DIR << "/scenes/depot.yaml\n"
                      << "classes: " << DEPOT_SOURCE_DIR << "/scenes/classes.yaml\n"
                      << "frames: 40\n"
                      << "timestamps: {file: " << gt << "}\n"
                      << "motion: {type: file, file: " << gt
                      << ", position: [0.0, 0.9, 1.35], look_at: [0.0, 4.5, 0.9]}\n";
  std::string root = render_small({yaml, 40, 64, true});
  auto written = read_tum_trajectory(root + "/groundtruth.txt");
  auto input = read_tum_trajectory(gt);
  ASSERT_EQ(written.size(), 40u);
  for (size_t i = 0; i < written.size(); ++i) {
    EXPECT_NEAR(written[i].timestamp, input[i].timestamp, 1e-6);
    EXPECT_LT(translation_between(written[i].pose, input[i].pose), 1e-6) << i;
    EXPECT_LT(rotation_angle_between(written[i].pose, input[i].pose), 1e-6) << i;
  }
}

}  // namespace
}  // namespace depot::test
