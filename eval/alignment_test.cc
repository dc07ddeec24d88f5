#include "eval/alignment.h"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "common/error.h"
#include "common/rng.h"
#include "eval/test_trajectories.h"

namespace depot::eval {
namespace {

std::vector<Eigen::Vector3d> random_points(size_t n, uint64_t seed) {
  Rng rng(seed);
  std::vector<Eigen::Vector3d> out;
  for (size_t k = 0; k < n; ++k) {
    out.emplace_back(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-1, 1));
  }
  return out;
}

std::vector<Eigen::Vector3d> transformed(const std::vector<Eigen::Vector3d>& points, double s,
                                         const Eigen::Matrix3d& r, const Eigen::Vector3d& t) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : points) out.push_back(s * r * p + t);
  return out;
}

const Eigen::Matrix3d kRotation =
    Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
const Eigen::Vector3d kTranslation(0.7, -1.9, 2.4);

TEST(Alignment, RecoversAKnownRigidTransform) {
  const auto source = random_points(40, 1);
  const auto target = transformed(source, 1.0, kRotation, kTranslation);
  const SimilarityTransform a = align_points(source, target, AlignmentKind::kRigid);
  EXPECT_TRUE(a.rotation.isApprox(kRotation, 1e-12));
  EXPECT_TRUE(a.translation.isApprox(kTranslation, 1e-12));
  EXPECT_DOUBLE_EQ(a.scale, 1.0);
  EXPECT_NEAR(a.rotation.determinant(), 1.0, 1e-12);
}

TEST(Alignment, Sim3RecoversAKnownScale) {
  const auto source = random_points(40, 2);
  const auto target = transformed(source, 2.5, kRotation, kTranslation);
  const SimilarityTransform a = align_points(source, target, AlignmentKind::kSimilarity);
  EXPECT_NEAR(a.scale, 2.5, 1e-12);
  EXPECT_TRUE(a.rotation.isApprox(kRotation, 1e-12));
  EXPECT_TRUE(a.translation.isApprox(kTranslation, 1e-12));
}

TEST(Alignment, MatchesEigenUmeyamaOnNoisyPoints) {
  const auto source = random_points(60, 3);
  auto target = transformed(source, 0.8, kRotation, kTranslation);
  Rng rng(4);
  for (auto& p : target) p += Eigen::Vector3d(rng.normal(), rng.normal(), rng.normal()) * 0.05;

  Eigen::Matrix3Xd src(3, source.size()), dst(3, target.size());
  for (size_t k = 0; k < source.size(); ++k) {
    src.col(static_cast<Eigen::Index>(k)) = source[k];
    dst.col(static_cast<Eigen::Index>(k)) = target[k];
  }
  for (bool with_scale : {false, true}) {
    const Eigen::Matrix4d expected = Eigen::umeyama(src, dst, with_scale);
    const SimilarityTransform a = align_points(
        source, target, with_scale ? AlignmentKind::kSimilarity : AlignmentKind::kRigid);
    EXPECT_TRUE((a.scale * a.rotation).isApprox(expected.topLeftCorner<3, 3>(), 1e-12));
    EXPECT_TRUE(a.translation.isApprox(expected.topRightCorner<3, 1>(), 1e-12));
  }
}

TEST(Alignment, NeverReturnsAReflection) {
  // A mirrored copy is best fitted by a reflection; the rotation must stay
  // proper (det +1), as in Umeyama's and Horn's methods.
  const auto source = random_points(30, 5);
  std::vector<Eigen::Vector3d> mirrored = source;
  for (auto& p : mirrored) p.x() = -p.x();
  const SimilarityTransform a = align_points(source, mirrored, AlignmentKind::kRigid);
  EXPECT_NEAR(a.rotation.determinant(), 1.0, 1e-12);
  EXPECT_TRUE((a.rotation.transpose() * a.rotation).isIdentity(1e-12));
}

TEST(Alignment, NoneIsIdentity) {
  const auto source = random_points(5, 6);
  const auto target = transformed(source, 1.0, kRotation, kTranslation);
  const SimilarityTransform a = align_points(source, target, AlignmentKind::kNone);
  EXPECT_TRUE(a.rotation.isIdentity());
  EXPECT_TRUE(a.translation.isZero());
  EXPECT_EQ(a.scale, 1.0);
}

TEST(Alignment, RejectsBadInput) {
  const auto points = random_points(5, 7);
  EXPECT_THROW(align_points(points, random_points(4, 8), AlignmentKind::kRigid), Error);
  EXPECT_THROW(align_points({}, {}, AlignmentKind::kRigid), Error);
  const std::vector<Eigen::Vector3d> same(5, Eigen::Vector3d(1, 2, 3));
  EXPECT_THROW(align_points(same, points, AlignmentKind::kSimilarity), Error);
  EXPECT_NO_THROW(align_points(same, points, AlignmentKind::kRigid));
}

}  // namespace
}  // namespace depot::eval

namespace depot::eval {
namespace {

// Poses of a camera that barely moves (a few cm), seen in a world turned by
// kRotation: positions alone cannot pin the turn; orientations can.
TEST(Alignment, PosesRecoverTheTurnOfAWorldFromATrajectoryThatBarelyMoves) {
  Rng rng(7);
  std::vector<Pose> source, target;
  Pose world = Pose::Identity();
  world.linear() = kRotation;
  world.translation() = kTranslation;
  for (int k = 0; k < 30; ++k) {
    Pose p = Pose::Identity();
    p.linear() =
        Eigen::AngleAxisd(rng.uniform(-0.2, 0.2), Eigen::Vector3d::UnitY()).toRotationMatrix();
    p.translation() = Eigen::Vector3d(rng.uniform(-0.02, 0.02), 0, rng.uniform(-0.02, 0.02));
    source.push_back(p);
    Pose noisy = world * p;
    noisy.translation() += Eigen::Vector3d(rng.uniform(-0.005, 0.005), 0, 0);
    target.push_back(noisy);
  }
  const SimilarityTransform a = align_poses(source, target);
  EXPECT_LT(Eigen::AngleAxisd(a.rotation * kRotation.transpose()).angle(), 1e-9);
  EXPECT_LT((a.translation - kTranslation).norm(), 0.003);
  EXPECT_THROW(align_poses(source, {}), Error);
}

}  // namespace
}  // namespace depot::eval
