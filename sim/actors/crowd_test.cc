// The crowd simulation on its own, in an empty 10 x 4 m room: the same seed
// gives the same tracks, walkers keep their spacing and the walls' clearance
// at every step, go to and fro between the ends, and an area too small for
// its walkers is one error naming the crowd.
#include "sim/actors/crowd.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/testing/error_of.h"

namespace depot::sim {
namespace {

// Walls at x = +-5 and y = +-2.
double room_clearance(const Eigen::Vector2d& p, double, double) {
  return std::min(std::min(5.0 - std::abs(p.x()), 2.0 - std::abs(p.y())), 10.0);
}

CrowdSpec corridor(int count) {
  CrowdSpec c;
  c.name = "c";
  c.count = count;
  c.lo = {-4.8, -1.8};
  c.hi = {4.8, 1.8};
  c.where = "test.yaml:3";
  return c;
}

TEST(CrowdSimulation, WalkersKeepApartAndClearOfTheWallsAndGoToAndFro) {
  const std::vector<ActorSpec> walkers =
      simulate_crowds({corridor(14)}, 1.0, 30.0, 5, room_clearance);
  ASSERT_EQ(walkers.size(), 14u);
  const std::vector<ActorSpec> again =
      simulate_crowds({corridor(14)}, 1.0, 30.0, 5, room_clearance);
  for (size_t i = 0; i < walkers.size(); ++i) {
    EXPECT_EQ(walkers[i].name, "c_" + std::to_string(i + 1));
    EXPECT_EQ(walkers[i].action, "crowd");
    ASSERT_EQ(walkers[i].track.size(), again[i].track.size());
    EXPECT_EQ(walkers[i].track.back().xy, again[i].track.back().xy) << "not deterministic";
  }
  double closest = 1e9, wall = 1e9;
  for (size_t k = 0; k < walkers[0].track.size(); ++k)
    for (size_t i = 0; i < walkers.size(); ++i) {
      wall = std::min(wall, room_clearance(walkers[i].track[k].xy, 0, 0));
      for (size_t j = i + 1; j < walkers.size(); ++j)
        closest = std::min(closest, (walkers[i].track[k].xy - walkers[j].track[k].xy).norm());
    }
  EXPECT_GE(closest, kCrowdSpacing - 1e-6);
  EXPECT_GE(wall, kCrowdClearance - 1e-6);
  // Each goes most of the way along the corridor and back in 30 s.
  for (const ActorSpec& w : walkers) {
    double lo = 1e9, hi = -1e9;
    for (const TrackPoint& p : w.track) lo = std::min(lo, p.xy.x()), hi = std::max(hi, p.xy.x());
    EXPECT_GT(hi - lo, 4.0) << w.name;
    EXPECT_GT(w.track.back().walked, 10.0) << w.name;
  }
  // The pose between samples is interpolated, held outside the track.
  const TrackPoint mid = track_at(walkers[0].track, 0.5 * kCrowdStep);
  EXPECT_NEAR((mid.xy - 0.5 * (walkers[0].track[0].xy + walkers[0].track[1].xy)).norm(), 0, 1e-9);
  EXPECT_EQ(track_at(walkers[0].track, -1.0).xy, walkers[0].track.front().xy);
}

TEST(CrowdSimulation, AnAreaTooSmallIsOneErrorNamingTheCrowd) {
  EXPECT_THAT(error_of([] { simulate_crowds({corridor(20)}, 4.0, 5.0, 1, room_clearance); }),
              ::testing::StartsWith("test.yaml:3: crowd 'c': its area holds "));
}

}  // namespace
}  // namespace depot::sim
