#include "eval/alignment.h"

#include <Eigen/LU>
#include <Eigen/SVD>

#include "common/error.h"

namespace depot::eval {
namespace {

Eigen::Vector3d mean_of(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

}  // namespace

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

  const double n = static_cast<double>(source.size());
  const Eigen::Vector3d source_mean = mean_of(source);
  const Eigen::Vector3d target_mean = mean_of(target);

  // Cross-covariance (Umeyama eq. 38) and source variance (eq. 36).
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double source_variance = 0.0;
  for (size_t k = 0; k < source.size(); ++k) {
    const Eigen::Vector3d x = source[k] - source_mean;
    covariance += (target[k] - target_mean) * x.transpose();
    source_variance += x.squaredNorm();
  }
  covariance /= n;
  source_variance /= n;

  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  // Force a proper rotation (det +1) rather than a reflection (eq. 39-40).
  Eigen::Vector3d sign(1.0, 1.0, 1.0);
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) sign.z() = -1.0;
  out.rotation = svd.matrixU() * sign.asDiagonal() * svd.matrixV().transpose();

  if (kind == AlignmentKind::kSimilarity) {
    if (!(source_variance > 0.0)) {
      fail("alignment", "cannot estimate a scale: all estimated positions coincide");
    }
    out.scale = svd.singularValues().dot(sign) / source_variance;  // eq. 42
  }
  out.translation = target_mean - out.scale * (out.rotation * source_mean);  // eq. 41
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
