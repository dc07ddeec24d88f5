#include "common/tum_association.h"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "common/error.h"

namespace depot {
namespace {

std::vector<std::pair<size_t, size_t>> pairs_of(const std::vector<TimestampMatch>& m) {
  std::vector<std::pair<size_t, size_t>> out;
  for (const TimestampMatch& x : m) out.emplace_back(x.reference_index, x.estimate_index);
  return out;
}

TEST(Association, DropsUnmatchedStampsAndUsesEachStampOnce) {
  const std::vector<double> reference = {0.0, 1.0, 2.0, 3.0};
  // 1.01 competes with 0.995 for reference 1.0 and loses (0.01 > 0.005);
  // 2.5 is too far from everything.
  const std::vector<double> estimate = {0.005, 0.995, 1.01, 2.5, 3.019};
  const auto m = pairs_of(associate(reference, estimate));
  const std::vector<std::pair<size_t, size_t>> expected = {{0, 0}, {1, 1}, {3, 4}};
  EXPECT_EQ(m, expected);
}

TEST(Association, BoundIsStrict) {
  AssociationOptions options;
  options.max_difference = 0.25;  // exactly representable, so the edge is exact
  EXPECT_TRUE(associate({1.0}, {1.25}, options).empty());
  EXPECT_TRUE(associate({1.0}, {0.75}, options).empty());
  EXPECT_EQ(associate({1.0}, {1.125}, options).size(), 1u);
}

TEST(Association, ClosestCandidateWinsGreedily) {
  // Estimate 1.012 is 0.012 from reference 1.0 but 0.003 from 1.015.
  const auto m = pairs_of(associate({1.0, 1.015}, {1.012}));
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0], std::make_pair(size_t{1}, size_t{0}));
}

TEST(Association, GreedyOrderMayCrossLikeAssociatePy) {
  // With a wide window TUM's greedy matching takes (10, 9) first (|dt| 1),
  // then (0, 12) (|dt| 12): the pairs cross. We reproduce that exactly.
  AssociationOptions options;
  options.max_difference = 15.0;
  const auto m = pairs_of(associate({0.0, 10.0}, {9.0, 12.0}, options));
  const std::vector<std::pair<size_t, size_t>> expected = {{0, 1}, {1, 0}};
  EXPECT_EQ(m, expected);
}

TEST(Association, OffsetIsAddedToEstimateStamps) {
  const std::vector<double> reference = {10.0, 10.1, 10.2};
  const std::vector<double> estimate = {5.001, 5.101, 5.199};
  EXPECT_TRUE(associate(reference, estimate).empty());
  AssociationOptions options;
  options.offset = 5.0;
  EXPECT_EQ(associate(reference, estimate, options).size(), 3u);
}

TEST(Association, EveryIndexAppearsAtMostOnce) {
  std::vector<double> reference, estimate;
  for (int k = 0; k < 300; ++k) reference.push_back(0.01 * k);          // 100 Hz
  for (int k = 0; k < 90; ++k) estimate.push_back(0.0333 * k + 0.004);  // ~30 Hz
  const auto m = associate(reference, estimate);
  std::set<size_t> r, e;
  for (const TimestampMatch& x : m) {
    EXPECT_TRUE(r.insert(x.reference_index).second);
    EXPECT_TRUE(e.insert(x.estimate_index).second);
    EXPECT_LT(std::abs(reference[x.reference_index] - estimate[x.estimate_index]), 0.02);
  }
  EXPECT_EQ(m.size(), estimate.size());
}

TEST(Association, RejectsInvalidOptions) {
  AssociationOptions options;
  options.max_difference = 0.0;
  EXPECT_THROW(associate({1.0}, {1.0}, options), Error);
  options.max_difference = NAN;
  EXPECT_THROW(associate({1.0}, {1.0}, options), Error);
  options = {};
  options.offset = INFINITY;
  EXPECT_THROW(associate({1.0}, {1.0}, options), Error);
}

// The first column of the numeric lines of a TUM text file.
std::vector<double> stamps_in(const std::string& path) {
  std::ifstream in(path);
  std::vector<double> out;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    double t = 0.0;
    if (!line.empty() && line[0] != '#' && fields >> t) out.push_back(t);
  }
  return out;
}

TEST(Association, RealFr1XyzStampsMatchAssociatePy) {
  const std::string dir = std::string(DEPOT_SHARED_DATA) + "/tum/fr1_xyz_trajectory/";
  const std::vector<double> groundtruth = stamps_in(dir + "groundtruth.txt");
  const std::vector<double> rgb = stamps_in(dir + "rgb.txt");
  if (groundtruth.empty() || rgb.empty()) GTEST_SKIP() << "shared TUM fr1_xyz data not found";
  ASSERT_EQ(groundtruth.size(), 3000u);
  ASSERT_EQ(rgb.size(), 798u);

  // Expected figures from TUM's associate() algorithm run in python3 on the
  // same files (first = groundtruth, second = rgb, offset 0).
  const auto m = associate(groundtruth, rgb);
  ASSERT_EQ(m.size(), 796u);
  size_t sum_reference = 0, sum_estimate = 0;
  for (const TimestampMatch& x : m) {
    sum_reference += x.reference_index;
    sum_estimate += x.estimate_index;
  }
  EXPECT_EQ(sum_reference, 1332441u);
  EXPECT_EQ(sum_estimate, 317600u);
  EXPECT_EQ(m.front().reference_index, 351u);
  EXPECT_EQ(m.back().reference_index, 2998u);

  AssociationOptions tight;
  tight.max_difference = 0.005;
  const auto m2 = associate(groundtruth, rgb, tight);
  EXPECT_EQ(m2.size(), 794u);
}

}  // namespace
}  // namespace depot
