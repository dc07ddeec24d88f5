// Paths: a lane offset shifts the smoothed path sideways by at most its
// bound, keeps a closed path closed, and none leaves the path as it was.
#include "sim/scenario/path.h"

#include <gtest/gtest.h>

#include <cmath>

namespace depot::sim {
namespace {

const std::vector<Eigen::Vector2d> kLoop = {{-3, 0}, {3, 0}, {3, 2}, {-3, 2}};

TEST(Path2D, NoLaneOffsetKeepsThePath) {
  const Path2D a(kLoop, true), b(kLoop, true, 0.5, LaneOffset());
  ASSERT_EQ(a.points().size(), b.points().size());
  for (size_t i = 0; i < a.points().size(); ++i) EXPECT_EQ(a.points()[i], b.points()[i]);
}

TEST(Path2D, ConstantLaneOffsetShiftsLeftOfTravel) {
  LaneOffset lane;
  lane.constant = 0.2;
  const Path2D plain(kLoop, true), shifted(kLoop, true, 0.5, lane);
  // The bottom edge runs east (+x): left is +y. Mid-edge point, s = 3 m from (-3, 0).
  EXPECT_NEAR(plain.position(3.0).y(), 0.0, 1e-9);
  EXPECT_NEAR(shifted.position(3.0).y(), 0.2, 1e-6);
  // Counter-clockwise loop shifted left (inwards): shorter by about 2 pi 0.2.
  EXPECT_NEAR(plain.length() - shifted.length(), 2 * M_PI * 0.2, 0.1);
}

TEST(Path2D, WavingLaneOffsetStaysWithinItsBoundAndClosed) {
  LaneOffset lane;
  lane.constant = -0.05;
  lane.amplitude = 0.1;
  lane.cycles = 2;
  lane.phase = 0.3;
  EXPECT_DOUBLE_EQ(lane.bound(), 0.15);
  const Path2D plain(kLoop, true), shifted(kLoop, true, 0.5, lane);
  ASSERT_EQ(plain.points().size(), shifted.points().size());
  double widest = 0;
  for (size_t i = 0; i < plain.points().size(); ++i)
    widest = std::max(widest, (plain.points()[i] - shifted.points()[i]).norm());
  EXPECT_LE(widest, 0.15 + 1e-12);
  EXPECT_GT(widest, 0.14);
  EXPECT_NEAR((shifted.points().front() - shifted.points().back()).norm(), 0.0, 1e-12);
  // Continuous, at the seam too: the shift changes little from one point
  // to the next.
  for (size_t i = 1; i < shifted.points().size(); ++i) {
    const Eigen::Vector2d before = shifted.points()[i - 1] - plain.points()[i - 1];
    const Eigen::Vector2d after = shifted.points()[i] - plain.points()[i];
    EXPECT_LT((after - before).norm(), 0.04) << "point " << i;
  }
}

}  // namespace
}  // namespace depot::sim
