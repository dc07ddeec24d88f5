#include "common/tum_io.h"

#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/testing/scratch_folder.h"

namespace depot {
namespace {

TEST(TumIo, TrajectoryRoundTripKeepsPoses) {
  const testkit::ScratchFolder scratch("tum_io");
  std::vector<StampedPose> poses;
  for (int i = 0; i < 5; ++i) {
    Eigen::Quaterniond q(Eigen::AngleAxisd(0.1 * i, Eigen::Vector3d(1, 2, 3).normalized()));
    poses.push_back({100.0 + i / 30.0, make_pose(q, Eigen::Vector3d(i, -i, 0.5 * i))});
  }
  auto path = scratch.write("roundtrip.txt", "");
  write_tum_trajectory(path, poses);
  auto back = read_tum_trajectory(path);
  ASSERT_EQ(back.size(), poses.size());
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(back[i].timestamp, poses[i].timestamp, 1e-6);
    EXPECT_LT(translation_between(back[i].pose, poses[i].pose), 1e-8);
    EXPECT_LT(rotation_angle_between(back[i].pose, poses[i].pose), 1e-8);
  }
}

TEST(TumIo, ErrorsNameFileAndLine) {
  const testkit::ScratchFolder scratch("tum_io");
  auto path = scratch.write("bad.txt", "# header\n1.0 0 0 0 0 0 0 1\n2.0 0 0 nan 0 0 0 1\n");
  try {
    read_tum_trajectory(path);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr(path + ":3")) << e.what();
  }
  EXPECT_THROW(read_tum_trajectory(scratch.write("short.txt", "1.0 0 0 0\n")), Error);
  EXPECT_THROW(read_tum_trajectory(scratch.write("empty.txt", "# nothing\n")), Error);
  EXPECT_THROW(read_tum_trajectory("/nonexistent/file.txt"), Error);
  EXPECT_THROW(
      read_tum_trajectory(scratch.write("order.txt", "2.0 0 0 0 0 0 0 1\n1.0 0 0 0 0 0 0 1\n")),
      Error);
}

// Found by fuzzing (tests/fuzz/fuzz_tum_trajectory): a line of whitespace
// other than spaces and tabs read a first field that was not there.
TEST(TumIo, LinesOfOnlyWhitespaceAreBlank) {
  const testkit::ScratchFolder scratch("tum_io");
  const std::string path = scratch.write("whitespace.txt", "# t\n1.0 a\n\v\n \f\r\n2.0 b\n");
  EXPECT_EQ(read_timestamps(path), (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(read_file_list(path).size(), 2u);
  EXPECT_EQ(detect_tum_file_kind(scratch.write("whitespace_first.txt", "\v\n1.0 a\n")),
            TumFileKind::kFileList);
}

TEST(TumIo, ReadsKittiPosesAndEurocCsv) {
  const testkit::ScratchFolder scratch("tum_io");
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()));
  const Eigen::Matrix3d r = q.toRotationMatrix();
  const std::string line = fmt::format(
      "{:.12f} {:.12f} {:.12f} 1.5 {:.12f} {:.12f} {:.12f} -2 {:.12f} {:.12f} {:.12f} 0.25\n",
      r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2));
  const auto kitti = read_kitti_poses(scratch.write("kitti.txt", std::string(line) + line));
  ASSERT_EQ(kitti.size(), 2u);
  EXPECT_LT(rotation_angle_between(kitti[1], make_pose(q, {1.5, -2, 0.25})), 1e-9);
  EXPECT_LT(translation_between(kitti[1], make_pose(q, {1.5, -2, 0.25})), 1e-12);
  const auto euroc = read_euroc_trajectory(scratch.write(
      "euroc.csv",
      "#timestamp [ns], p_x [m], p_y [m], p_z [m], q_w [], q_x [], q_y [], q_z []\n"
      "1403636579758555392,1,2,3,1,0,0,0\n1403636579763555584,1,2,3.5,0,1,0,0,9,9\n"));
  ASSERT_EQ(euroc.size(), 2u);
  EXPECT_NEAR(euroc[1].timestamp, 1403636579.763555584, 1e-6);
  EXPECT_NEAR(euroc[1].pose.translation().z(), 3.5, 1e-12);
  EXPECT_NEAR(euroc[1].pose.linear()(1, 1), -1.0, 1e-12);  // 180 deg about x
  // Not a rotation, a NaN, a short line, unsorted times: the file and line.
  auto error = [](auto read, const std::string& path) -> std::string {
    try {
      read(path);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  const std::string shear = scratch.write("shear.txt", "1 0.5 0 0 0 1 0 0 0 0 1 0\n");
  EXPECT_NE(error(read_kitti_poses, shear).find(shear + ":1: the 3x3 part is not a rotation"),
            std::string::npos);
  const std::string nan = scratch.write("nan.txt", "1 0 0 0 0 1 0 nan 0 0 1 0\n");
  EXPECT_THAT(error(read_kitti_poses, nan), ::testing::HasSubstr(nan + ":1"));
  const std::string unsorted =
      scratch.write("unsorted.csv", "2000,0,0,0,1,0,0,0\n1000,0,0,0,1,0,0,0\n");
  EXPECT_NE(error(read_euroc_trajectory, unsorted).find(unsorted + ":2: timestamps must increase"),
            std::string::npos);
  EXPECT_THROW(read_euroc_trajectory(scratch.write("short.csv", "1000,0,0,0\n")), Error);
}

std::string trajectory_error(const testkit::ScratchFolder& scratch, const std::string& name,
                             const std::string& text) {
  try {
    read_tum_trajectory(scratch.write(name, text));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(TumIo, QuaternionsMustBeUnitWithinTheStatedTolerance) {
  const testkit::ScratchFolder scratch("tum_io");
  // Four decimals (as TUM's own files) pass; 1.05 does not.
  EXPECT_EQ(trajectory_error(scratch, "q4.txt", "1.0 0 0 0 0.6124 0.3536 0.3536 0.6124\n"), "");
  const std::string e = trajectory_error(scratch, "q105.txt", "1.0 0 0 0 0 0 0 1.05\n");
  EXPECT_NE(e.find("q105.txt:1: quaternion is not unit length (norm 1.05"), std::string::npos) << e;
  EXPECT_NE(trajectory_error(scratch, "q1002.txt", "1.0 0 0 0 0 0 0 1.002\n"), "");
}

TEST(TumIo, ExtraColumnsAreRefused) {
  const testkit::ScratchFolder scratch("tum_io");
  const std::string e = trajectory_error(scratch, "nine.txt", "# c\n1.0 0 0 0 0 0 0 1 7\n");
  EXPECT_THAT(e, ::testing::HasSubstr("nine.txt:2: expected 8 fields")) << e;
  EXPECT_THAT(e, ::testing::HasSubstr("found 9")) << e;
}

TEST(TumIo, AFolderIsNotATextFile) {
  const testkit::ScratchFolder scratch("tum_io");
  const auto folder = scratch.path() / "folder";
  std::filesystem::create_directories(folder);
  EXPECT_NE(trajectory_error(scratch, "unused.txt", "").size(), 0u);
  try {
    read_tum_trajectory(folder.string());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("is a folder")) << e.what();
  }
}

TEST(TumIo, DetectsFileKinds) {
  const testkit::ScratchFolder scratch("tum_io");
  EXPECT_EQ(detect_tum_file_kind(scratch.write("k1.txt", "1.0 0 0 0 0 0 0 1\n")),
            TumFileKind::kTrajectory);
  EXPECT_EQ(detect_tum_file_kind(scratch.write("k2.txt", "1.0 rgb/1.png\n")),
            TumFileKind::kFileList);
  EXPECT_EQ(detect_tum_file_kind(scratch.write("k3.txt", "1.0 rgb/1.png 1.01 depth/1.png\n")),
            TumFileKind::kAssociation);
}

TEST(TumIo, ReadsRealTumTimestampFiles) {
  const std::string root = DEPOT_SHARED_DATA;
  const std::string assoc = root + "/tum/fr3_associations/fr3_walking_xyz.txt";
  if (!std::filesystem::exists(assoc)) GTEST_SKIP() << "shared data missing: " << assoc;
  auto pairs = read_associations(assoc);
  EXPECT_EQ(pairs.size(), 827u);
  auto gt = read_tum_trajectory(root + "/tum/fr1_xyz_trajectory/groundtruth.txt");
  EXPECT_EQ(gt.size(), 3000u);
}

}  // namespace
}  // namespace depot
