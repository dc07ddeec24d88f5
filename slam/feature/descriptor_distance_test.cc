#include "slam/feature/descriptor_distance.h"

#include <cstdint>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

namespace depot::slam {
namespace {

TEST(DescriptorDistance, ExtremesAndSingleBits) {
  std::uint8_t a[kDescriptorBytes] = {};
  std::uint8_t b[kDescriptorBytes] = {};
  EXPECT_EQ(descriptor_distance(a, b), 0);
  for (int bit = 0; bit < 256; ++bit) {
    b[bit / 8] = static_cast<std::uint8_t>(1u << (bit % 8));
    EXPECT_EQ(descriptor_distance(a, b), 1) << "bit " << bit;
    b[bit / 8] = 0;
  }
  for (auto& x : b) x = 0xff;
  EXPECT_EQ(descriptor_distance(a, b), 256);
}

TEST(DescriptorDistance, AgreesWithOpenCvHammingNormOnRandomRows) {
  cv::RNG rng(12345);
  cv::Mat d(200, kDescriptorBytes, CV_8UC1);
  rng.fill(d, cv::RNG::UNIFORM, 0, 256);
  // Unaligned rows too: a view starting one byte into a wider matrix.
  cv::Mat wide(200, kDescriptorBytes + 1, CV_8UC1);
  rng.fill(wide, cv::RNG::UNIFORM, 0, 256);
  const cv::Mat shifted = wide.colRange(1, kDescriptorBytes + 1);
  for (int i = 0; i < d.rows; ++i) {
    for (int j = 0; j < d.rows; j += 7) {
      const int expected = static_cast<int>(cv::norm(d.row(i), d.row(j), cv::NORM_HAMMING));
      ASSERT_EQ(descriptor_distance(d.row(i), d.row(j)), expected) << i << "," << j;
      ASSERT_EQ(descriptor_distance(d.ptr<std::uint8_t>(i), d.ptr<std::uint8_t>(j)), expected);
      const int expected_shifted =
          static_cast<int>(cv::norm(shifted.row(i), d.row(j), cv::NORM_HAMMING));
      ASSERT_EQ(descriptor_distance(shifted.ptr<std::uint8_t>(i), d.ptr<std::uint8_t>(j)),
                expected_shifted);
    }
  }
}

}  // namespace
}  // namespace depot::slam
