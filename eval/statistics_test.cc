#include "eval/statistics.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/error.h"

namespace depot::eval {
namespace {

TEST(Statistics, EvenCountByHand) {
  const ErrorStatistics s = compute_statistics({4.0, 1.0, 3.0, 2.0});
  EXPECT_EQ(s.count, 4u);
  EXPECT_DOUBLE_EQ(s.sse, 30.0);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(7.5));
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);           // mean of the two middle values
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));  // population std, as numpy.std
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
}

TEST(Statistics, OddCountMedianIsTheMiddleValue) {
  const ErrorStatistics s = compute_statistics({0.5, 0.1, 0.9});
  EXPECT_DOUBLE_EQ(s.median, 0.5);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt((0.25 + 0.01 + 0.81) / 3.0));
}

TEST(Statistics, SingleValueHasZeroSpread) {
  const ErrorStatistics s = compute_statistics({0.25});
  EXPECT_DOUBLE_EQ(s.rmse, 0.25);
  EXPECT_DOUBLE_EQ(s.std, 0.0);
}

TEST(Statistics, RejectsEmptyAndNonFinite) {
  EXPECT_THROW(compute_statistics({}), Error);
  EXPECT_THROW(compute_statistics({1.0, NAN}), Error);
  EXPECT_THROW(compute_statistics({INFINITY}), Error);
}

}  // namespace
}  // namespace depot::eval
