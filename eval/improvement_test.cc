#include "eval/improvement.h"

#include <gtest/gtest.h>

namespace depot::eval {
namespace {

TEST(Improvement, PaperEq9OnWalkingXyz) {
  // ORB-SLAM2 0.2991 m vs the full method 0.0185 m (paper Table 2).
  EXPECT_NEAR(improvement_percent(0.2991, 0.0185), 93.8148, 1e-4);
}

TEST(Improvement, PaperMeanOverTheFourWalkingSequences) {
  // The paper claims a 91.47 % mean ATE-RMSE improvement over ORB-SLAM2.
  const double mean = (improvement_percent(0.2991, 0.0185) + improvement_percent(0.4754, 0.0381) +
                       improvement_percent(0.0925, 0.0094) + improvement_percent(0.3575, 0.0349)) /
                      4.0;
  EXPECT_NEAR(mean, 91.47, 0.005);
}

TEST(Improvement, WorseThanBaselineIsNegative) {
  EXPECT_DOUBLE_EQ(improvement_percent(0.0122, 0.0244), -100.0);
}

TEST(Improvement, RejectsAZeroBaseline) {
  EXPECT_THROW(improvement_percent(0.0, 0.01), Error);
  EXPECT_THROW(improvement_percent(0.1, -1.0), Error);
}

}  // namespace
}  // namespace depot::eval
