#include "dataset/object_poses.h"

#include <gtest/gtest.h>

#include "common/testing/error_of.h"
#include "dataset/test_folder.h"

namespace depot::dataset {
namespace {

TEST(ObjectPoses, RoundTripInFileOrder) {
  const std::string dir = testing::new_test_folder();
  std::vector<ObjectPoseRecord> want;
  for (int frame = 0; frame < 3; ++frame)
    for (int id : {3, 1}) {
      ObjectPoseRecord r;
      r.timestamp = 1.0 + frame / 30.0;
      r.id = id;
      r.pose = make_pose(
          Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * frame + id, Eigen::Vector3d::UnitZ())),
          Eigen::Vector3d(0.25 * frame, id, 0.5));
      r.moving = id == 3 && frame > 0;
      want.push_back(r);
    }
  write_object_poses(dir, "walk", want);
  const std::vector<ObjectPoseRecord> read = read_object_poses(dir);
  ASSERT_EQ(read.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_NEAR(read[i].timestamp, want[i].timestamp, 5e-7) << i;
    EXPECT_EQ(read[i].id, want[i].id) << i;
    EXPECT_EQ(read[i].moving, want[i].moving) << i;
    EXPECT_TRUE(read[i].pose.isApprox(want[i].pose, 1e-8)) << i;
  }
}

TEST(ObjectPoses, Text) {
  ObjectPoseRecord r;
  r.timestamp = 2.5;
  r.id = 12;
  r.pose = make_pose(Eigen::Quaterniond::Identity(), Eigen::Vector3d(1, 2, 3));
  r.moving = true;
  EXPECT_EQ(format_object_pose(r),
            "2.500000 12 1.000000000 2.000000000 3.000000000 0.000000000 0.000000000 0.000000000 "
            "1.000000000 1\n");
  EXPECT_EQ(object_poses_header("walk"),
            "# per-frame poses of pushables and actors (dataset frame); moving = moved >1 mm or "
            ">0.1 deg\n# file: 'walk' (depot-slam simulator)\n"
            "# timestamp id tx ty tz qx qy qz qw moving\n");
}

TEST(ObjectPoses, MalformedLinesNameTheFileAndLine) {
  const std::string dir = testing::new_test_folder();
  EXPECT_EQ(error_of([&] { read_object_poses(dir); }),
            dir +
                "/object_poses.txt: cannot open file (the objects' per-frame poses; not a "
                "simulated dataset?)");
  const struct {
    std::string line, problem;
  } cases[] = {
      {"1.0 2 0 0 0 0 0 0 1",
       "expected 10 fields (timestamp id tx ty tz qx qy qz qw moving), "
       "found 9"},
      {"x 2 0 0 0 0 0 0 1 0", "timestamp 'x' is not a number"},
      {"1.0 2.5 0 0 0 0 0 0 1 0", "id '2.5' is not an integer"},
      {"1.0 0 0 0 0 0 0 0 1 0", "id 0 is not an instance id (1..65535)"},
      {"1.0 2 0 nan 0 0 0 0 1 0", "ty 'nan' is not a number"},
      {"1.0 2 0 0 0 0 0 0 2 0", "quaternion norm 2.000000 is not 1"},
      {"1.0 2 0 0 0 0 0 0 1 yes", "moving 'yes' is not 0 or 1"},
  };
  for (const auto& c : cases) {
    testing::write_text(dir, "object_poses.txt", "# a\n1.0 1 0 0 0 0 0 0 1 0\n\n" + c.line + "\n");
    EXPECT_EQ(error_of([&] { read_object_poses(dir); }), dir + "/object_poses.txt:4: " + c.problem)
        << c.line;
  }
}

}  // namespace
}  // namespace depot::dataset
