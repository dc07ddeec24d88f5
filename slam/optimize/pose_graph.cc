#include "slam/optimize/pose_graph.h"

#include <array>

#include <ceres/ceres.h>

namespace depot::slam {
namespace {

struct RelativePoseError {
  Eigen::Quaterniond q_ab;
  Eigen::Vector3d t_ab;

  template <typename T>
  bool operator()(const T* q_a_, const T* t_a_, const T* q_b_, const T* t_b_, T* r) const {
    Eigen::Map<const Eigen::Quaternion<T>> q_a(q_a_), q_b(q_b_);
    Eigen::Map<const Eigen::Matrix<T, 3, 1>> t_a(t_a_), t_b(t_b_);
    // Estimate of T_ab = T_aw * T_bw^-1.
    const Eigen::Quaternion<T> q_est = q_a * q_b.conjugate();
    const Eigen::Matrix<T, 3, 1> t_est = t_a - q_est * t_b;
    const Eigen::Quaternion<T> q_meas_inv = q_ab.conjugate().template cast<T>();
    const Eigen::Quaternion<T> dq = q_meas_inv * q_est;
    const Eigen::Matrix<T, 3, 1> dt = q_meas_inv * (t_est - t_ab.template cast<T>());
    r[0] = dt.x(), r[1] = dt.y(), r[2] = dt.z();
    r[3] = T(2) * dq.x(), r[4] = T(2) * dq.y(), r[5] = T(2) * dq.z();
    return true;
  }
};

}  // namespace

double optimize_pose_graph(std::vector<Pose>& T_cw, const std::vector<bool>& fixed,
                           const std::vector<PoseGraphEdge>& edges, int iterations) {
  if (edges.empty()) return 0;
  const size_t n = T_cw.size();
  std::vector<std::array<double, 4>> q(n);  // x, y, z, w (Eigen's order)
  std::vector<std::array<double, 3>> t(n);
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Quaterniond qi = Eigen::Quaterniond(T_cw[i].linear()).normalized();
    q[i] = {qi.x(), qi.y(), qi.z(), qi.w()};
    const Eigen::Vector3d ti = T_cw[i].translation();
    t[i] = {ti.x(), ti.y(), ti.z()};
  }
  ceres::Problem problem;
  std::vector<bool> used(n, false);
  for (const PoseGraphEdge& e : edges) {
    auto* cost =
        new ceres::AutoDiffCostFunction<RelativePoseError, 6, 4, 3, 4, 3>(new RelativePoseError{
            Eigen::Quaterniond(e.T_ab.linear()).normalized(), e.T_ab.translation()});
    problem.AddResidualBlock(cost, nullptr, q[e.a].data(), t[e.a].data(), q[e.b].data(),
                             t[e.b].data());
    used[e.a] = used[e.b] = true;
  }
  for (size_t i = 0; i < n; ++i) {
    if (!used[i]) continue;
    problem.SetManifold(q[i].data(), new ceres::EigenQuaternionManifold);
    if (fixed[i]) {
      problem.SetParameterBlockConstant(q[i].data());
      problem.SetParameterBlockConstant(t[i].data());
    }
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = iterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  for (size_t i = 0; i < n; ++i) {
    if (!used[i] || fixed[i]) continue;
    const Eigen::Quaterniond qi(q[i][3], q[i][0], q[i][1], q[i][2]);
    T_cw[i] = make_pose(qi.normalized(), Eigen::Vector3d(t[i][0], t[i][1], t[i][2]));
  }
  return summary.final_cost;
}

}  // namespace depot::slam
