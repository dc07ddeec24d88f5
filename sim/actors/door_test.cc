// A door's leaf over time: shut, swinging, open, by its events or by its
// seeded timeline.
#include "sim/actors/door.h"

#include <gtest/gtest.h>

namespace depot::sim {
namespace {

DoorSpec door() {
  DoorSpec d;
  d.name = "d";
  d.hinge = {2.0, -5.97};
  d.width = 1.0;
  d.height = 2.0;
  d.swing_deg = 90;
  return d;
}

TEST(Door, TheLeafSwingsAboutItsHingeAsItsEventsSay) {
  DoorSpec spec = door();
  spec.events = {{1.0, 0.0}, {2.0, 1.0}};
  const DoorActor d(spec, 1);
  EXPECT_EQ(d.class_name(), "door");
  EXPECT_DOUBLE_EQ(d.share_open(0.5), 0.0);
  EXPECT_DOUBLE_EQ(d.share_open(1.5), 0.5);
  EXPECT_DOUBLE_EQ(d.share_open(3.0), 1.0);
  std::vector<Pose> parts;
  d.pose_parts(0.0, parts);  // shut: the leaf along +x from the hinge
  EXPECT_TRUE(parts[0].translation().isApprox(Eigen::Vector3d(2.5, -5.97, 1.0)));
  d.pose_parts(3.0, parts);  // open: turned 90 degrees, along +y
  EXPECT_TRUE(parts[0].translation().isApprox(Eigen::Vector3d(2.0, -5.47, 1.0)));
  // The hinge stays where it is.
  EXPECT_TRUE(d.root_pose(1.7).translation().isApprox(Eigen::Vector3d(2.0, -5.97, 0.0)));
}

TEST(Door, ASeededDoorOpensAndShutsOnItsOwnTimeline) {
  DoorSpec spec = door();
  spec.shut = {3.0, 6.0};
  spec.open = {2.0, 4.0};
  const DoorActor a(spec, 7), b(spec, 7), c(spec, 8);
  double first_open = -1, differs = 0;
  for (double t = 0; t < 60; t += 0.05) {
    EXPECT_EQ(a.share_open(t), b.share_open(t)) << "not deterministic at " << t;
    differs += a.share_open(t) != c.share_open(t);
    if (first_open < 0 && a.share_open(t) > 0) first_open = t;
  }
  EXPECT_GT(differs, 0) << "another seed must time it differently";
  EXPECT_GE(first_open, 3.0);
  EXPECT_LE(first_open, 6.05);
  // Shut or open except while swinging: at most kDoorSwing s between.
  int swinging = 0, samples = 0;
  for (double t = 0; t < 60; t += 0.05, ++samples) {
    const double s = a.share_open(t);
    swinging += s > 0 && s < 1;
  }
  EXPECT_GT(swinging, 0);
  EXPECT_LT(swinging, samples / 3);
}

}  // namespace
}  // namespace depot::sim
