#include "eval/alignment.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "common/error.h"

namespace depot::eval {

std::string to_string(AlignmentKind kind) {
  switch (kind) {
    case AlignmentKind::kNone:
      return "none";
    case AlignmentKind::kRigid:
      return "SE(3)";
    case AlignmentKind::kSimilarity:
      return "Sim(3)";
  }
  return "unknown";
}

SimilarityTransform align_points(const std::vector<Eigen::Vector3d>& source,
                                 const std::vector<Eigen::Vector3d>& target, AlignmentKind kind) {
  if (source.size() != target.size()) {
    fail("alignment", "point lists differ in length (" + std::to_string(source.size()) + " vs " +
                          std::to_string(target.size()) + ")");
  }
  if (source.empty()) fail("alignment", "no points to align");
  SimilarityTransform out;
  if (kind == AlignmentKind::kNone) return out;

  // Umeyama's method (eq. 34-42, a proper rotation even where a reflection
  // fits better), as Eigen implements it.
  Eigen::Matrix3Xd from(3, source.size()), to(3, target.size());
  for (size_t k = 0; k < source.size(); ++k) {
    from.col(static_cast<Eigen::Index>(k)) = source[k];
    to.col(static_cast<Eigen::Index>(k)) = target[k];
  }
  const bool scaled = kind == AlignmentKind::kSimilarity;
  if (scaled && !((from.colwise() - from.rowwise().mean()).squaredNorm() > 0.0))
    fail("alignment", "cannot estimate a scale: all estimated positions coincide");
  const Eigen::Matrix4d transform = Eigen::umeyama(from, to, scaled);
  const Eigen::Matrix3d scaled_rotation = transform.topLeftCorner<3, 3>();
  if (scaled) out.scale = scaled_rotation.col(0).norm();
  out.rotation = scaled_rotation / out.scale;
  out.translation = transform.topRightCorner<3, 1>();
  return out;
}

SimilarityTransform align_poses(const std::vector<Pose>& source, const std::vector<Pose>& target) {
  if (source.size() != target.size())
    fail("alignment", "pose lists differ in length (" + std::to_string(source.size()) + " vs " +
                          std::to_string(target.size()) + ")");
  if (source.empty()) fail("alignment", "no poses to align");
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (size_t k = 0; k < source.size(); ++k)
    sum += target[k].linear() * source[k].linear().transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d sign(1.0, 1.0, 1.0);
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) sign.z() = -1.0;
  SimilarityTransform out;
  out.rotation = svd.matrixU() * sign.asDiagonal() * svd.matrixV().transpose();
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < source.size(); ++k)
    offset += target[k].translation() - out.rotation * source[k].translation();
  out.translation = offset / static_cast<double>(source.size());
  return out;
}

}  // namespace depot::eval
