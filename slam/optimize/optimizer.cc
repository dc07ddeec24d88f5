#include "slam/optimize/optimizer.h"

#include <array>
#include <cmath>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include <ceres/ceres.h>

#include "slam/data/map_point.h"

namespace depot::slam {
namespace {

// ---------------------------------------------------------------------------
// Pose parameter block: 7 doubles, a unit quaternion (x, y, z, w: Eigen's
// coefficient order) and a translation, for T_cw. Updates are left
// increments T <- [exp(omega) | dt] * T with a 6-vector (omega, dt), as in
// g2o's SE3Expmap. The cost functions return their Jacobians with respect to
// that increment directly (in the 6 columns matching the manifold's "lift"
// below, the w column zero), so PlusJacobian is a constant selection matrix.

constexpr int kPoseSize = 7;

using PoseParams = std::array<double, kPoseSize>;

PoseParams to_params(const Pose& T_cw) {
  PoseParams x;
  const Eigen::Quaterniond q = Eigen::Quaterniond(T_cw.linear()).normalized();
  Eigen::Map<Eigen::Quaterniond> q_out(x.data());
  Eigen::Map<Eigen::Vector3d> t_out(x.data() + 4);
  q_out = q;
  t_out = T_cw.translation();
  return x;
}

Pose to_pose(const double* x) {
  return make_pose(Eigen::Quaterniond(Eigen::Map<const Eigen::Quaterniond>(x)),
                   Eigen::Vector3d(Eigen::Map<const Eigen::Vector3d>(x + 4)));
}

Eigen::Quaterniond exp_so3(const Eigen::Vector3d& omega) {
  const double angle = omega.norm();
  if (angle < 1e-10)
    return Eigen::Quaterniond(1, 0.5 * omega.x(), 0.5 * omega.y(), 0.5 * omega.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, omega / angle));
}

class LeftSe3Manifold : public ceres::Manifold {
 public:
  int AmbientSize() const override { return kPoseSize; }
  int TangentSize() const override { return 6; }

  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    const Eigen::Quaterniond dq = exp_so3(Eigen::Vector3d(delta[0], delta[1], delta[2]));
    Eigen::Map<const Eigen::Quaterniond> q(x);
    Eigen::Map<const Eigen::Vector3d> t(x + 4);
    Eigen::Map<Eigen::Quaterniond> q_out(x_plus_delta);
    Eigen::Map<Eigen::Vector3d> t_out(x_plus_delta + 4);
    q_out = (dq * q).normalized();
    t_out = dq * t + Eigen::Vector3d(delta[3], delta[4], delta[5]);
    return true;
  }
  // Rows: q_x, q_y, q_z, q_w, t_x, t_y, t_z; columns: omega, dt.
  bool PlusJacobian(const double*, double* jacobian) const override {
    Eigen::Map<Eigen::Matrix<double, kPoseSize, 6, Eigen::RowMajor>> J(jacobian);
    J.setZero();
    J.block<3, 3>(0, 0).setIdentity();
    J.block<3, 3>(4, 3).setIdentity();
    return true;
  }
  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    Eigen::Map<const Eigen::Quaterniond> qy(y), qx(x);
    Eigen::Quaterniond dq = (qy * qx.conjugate()).normalized();
    if (dq.w() < 0) dq.coeffs() = -dq.coeffs();
    const Eigen::AngleAxisd aa(dq);
    const Eigen::Vector3d omega = aa.angle() * aa.axis();
    const Eigen::Vector3d dt =
        Eigen::Map<const Eigen::Vector3d>(y + 4) - dq * Eigen::Map<const Eigen::Vector3d>(x + 4);
    for (int i = 0; i < 3; ++i) y_minus_x[i] = omega[i], y_minus_x[3 + i] = dt[i];
    return true;
  }
  bool MinusJacobian(const double*, double* jacobian) const override {
    Eigen::Map<Eigen::Matrix<double, 6, kPoseSize, Eigen::RowMajor>> J(jacobian);
    J.setZero();
    J.block<3, 3>(0, 0).setIdentity();
    J.block<3, 3>(3, 4).setIdentity();
    return true;
  }
};

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// One keypoint measurement with everything needed to predict it.
struct Measurement {
  double fx, fy, cx, cy, bf;
  double u, v, u_right;  // u_right used by the stereo residual only
  double weight;         // sqrt(inv_sigma2[octave])

  Measurement(const Features& f, size_t i) {
    const PinholeCamera& c = f.camera;
    fx = c.fx, fy = c.fy, cx = c.cx, cy = c.cy, bf = c.bf;
    const cv::KeyPoint& kp = f.keypoints[i];
    u = kp.pt.x;
    v = kp.pt.y;
    u_right = f.u_right[i];
    weight = 1.0;
    if (f.levels && kp.octave >= 0 && kp.octave < static_cast<int>(f.levels->inv_sigma2.size()))
      weight = std::sqrt(static_cast<double>(f.levels->inv_sigma2[kp.octave]));
  }

  // Weighted residual (predicted - observed) of the camera-frame point p and,
  // when J is given, its derivative with respect to p.
  template <int kDim>
  void residual(const Eigen::Vector3d& p, double* r, Eigen::Matrix<double, kDim, 3>* J) const {
    const double inv_z = 1.0 / p.z();
    const double u_hat = fx * p.x() * inv_z + cx;
    r[0] = (u_hat - u) * weight;
    r[1] = (fy * p.y() * inv_z + cy - v) * weight;
    if constexpr (kDim == 3) r[2] = (u_hat - bf * inv_z - u_right) * weight;
    if (!J) return;
    const double w_iz = weight * inv_z;
    (*J)(0, 0) = fx * w_iz;
    (*J)(0, 1) = 0;
    (*J)(0, 2) = -fx * p.x() * inv_z * w_iz;
    (*J)(1, 0) = 0;
    (*J)(1, 1) = fy * w_iz;
    (*J)(1, 2) = -fy * p.y() * inv_z * w_iz;
    if constexpr (kDim == 3) {
      (*J)(2, 0) = (*J)(0, 0);
      (*J)(2, 1) = 0;
      (*J)(2, 2) = (*J)(0, 2) + bf * inv_z * w_iz;
    }
  }
};

// Jacobian block of a residual with respect to the pose increment, given
// d r / d p_c at p_c, written into the 7 ambient columns (w column zero).
template <int kDim>
void write_pose_jacobian(const Eigen::Matrix<double, kDim, 3>& J_p, const Eigen::Vector3d& p_c,
                         double* out) {
  Eigen::Map<Eigen::Matrix<double, kDim, kPoseSize, Eigen::RowMajor>> J(out);
  J.template block<kDim, 3>(0, 0) = -J_p * skew(p_c);  // d(exp(w) p)/dw = -[p]x
  J.col(3).setZero();
  J.template block<kDim, 3>(0, 4) = J_p;
}

// Pose-only residual: the world point is a constant.
template <int kDim>
class PoseOnlyCost : public ceres::SizedCostFunction<kDim, kPoseSize> {
 public:
  PoseOnlyCost(const Measurement& m, const Eigen::Vector3d& x_w) : m_(m), x_w_(x_w) {}
  bool Evaluate(double const* const* params, double* residuals, double** jacobians) const override {
    const Eigen::Map<const Eigen::Quaterniond> q(params[0]);
    const Eigen::Map<const Eigen::Vector3d> t(params[0] + 4);
    const Eigen::Vector3d p = q * x_w_ + t;
    Eigen::Matrix<double, kDim, 3> J_p;
    const bool jac = jacobians && jacobians[0];
    m_.residual<kDim>(p, residuals, jac ? &J_p : nullptr);
    if (jac) write_pose_jacobian<kDim>(J_p, p, jacobians[0]);
    return true;
  }

 private:
  Measurement m_;
  Eigen::Vector3d x_w_;
};

// Bundle-adjustment residual: pose and world point are variables.
template <int kDim>
class BaCost : public ceres::SizedCostFunction<kDim, kPoseSize, 3> {
 public:
  explicit BaCost(const Measurement& m) : m_(m) {}
  bool Evaluate(double const* const* params, double* residuals, double** jacobians) const override {
    const Eigen::Map<const Eigen::Quaterniond> q(params[0]);
    const Eigen::Map<const Eigen::Vector3d> t(params[0] + 4);
    const Eigen::Map<const Eigen::Vector3d> x_w(params[1]);
    const Eigen::Vector3d p = q * x_w + t;
    Eigen::Matrix<double, kDim, 3> J_p;
    const bool jac = jacobians && (jacobians[0] || jacobians[1]);
    m_.residual<kDim>(p, residuals, jac ? &J_p : nullptr);
    if (!jac) return true;
    if (jacobians[0]) write_pose_jacobian<kDim>(J_p, p, jacobians[0]);
    if (jacobians[1]) {
      Eigen::Map<Eigen::Matrix<double, kDim, 3, Eigen::RowMajor>> J_x(jacobians[1]);
      J_x = J_p * q.toRotationMatrix();
    }
    return true;
  }

 private:
  Measurement m_;
};

// chi2 (squared weighted error) and camera-frame depth at the given pose / point.
template <int kDim>
double chi2_of(const Measurement& m, const double* pose, const double* x_w, double* depth) {
  const Eigen::Map<const Eigen::Quaterniond> q(pose);
  const Eigen::Map<const Eigen::Vector3d> t(pose + 4);
  const Eigen::Vector3d p = q * Eigen::Map<const Eigen::Vector3d>(x_w) + t;
  double r[3] = {0, 0, 0};
  m.residual<kDim>(p, r, nullptr);
  if (depth) *depth = p.z();
  return r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
}

ceres::Problem::Options problem_options() {
  ceres::Problem::Options o;
  o.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  o.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  o.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  return o;
}

ceres::Solver::Options solver_options(int iterations, ceres::LinearSolverType solver) {
  ceres::Solver::Options o;
  o.linear_solver_type = solver;
  o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  o.max_num_iterations = iterations;
  o.num_threads = 1;
  o.logging_type = ceres::SILENT;
  o.minimizer_progress_to_stdout = false;
  return o;
}

class AbortCallback : public ceres::IterationCallback {
 public:
  explicit AbortCallback(const std::atomic<bool>* abort) : abort_(abort) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    return aborted(abort_) ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }
  static bool aborted(const std::atomic<bool>* a) {
    return a && a->load(std::memory_order_relaxed);
  }

 private:
  const std::atomic<bool>* abort_;
};

// ---------------------------------------------------------------------------
// Pose-only optimisation.

struct PoseEdge {
  size_t index;  // keypoint index in the frame
  bool stereo;
  Measurement m;
  Eigen::Vector3d x_w;
  std::unique_ptr<ceres::CostFunction> cost;
};

}  // namespace

int optimize_pose(Frame& frame) {
  if (frame.outlier.size() < frame.map_points.size())
    frame.outlier.resize(frame.map_points.size(), false);
  std::vector<PoseEdge> edges;
  edges.reserve(frame.map_points.size());
  const Features& f = frame.features;
  for (size_t i = 0; i < frame.map_points.size() && i < f.size(); ++i) {
    const MapPoint* mp = frame.map_points[i];
    if (!mp || mp->bad) continue;
    frame.outlier[i] = false;
    PoseEdge e{i, f.u_right[i] >= 0, Measurement(f, i), mp->position, nullptr};
    if (e.stereo)
      e.cost = std::make_unique<PoseOnlyCost<3>>(e.m, e.x_w);
    else
      e.cost = std::make_unique<PoseOnlyCost<2>>(e.m, e.x_w);
    edges.push_back(std::move(e));
  }
  if (edges.size() < 3) return 0;

  PoseParams pose = to_params(frame.T_cw);
  LeftSe3Manifold manifold;
  ceres::HuberLoss huber_mono(std::sqrt(kChi2Mono));
  ceres::HuberLoss huber_stereo(std::sqrt(kChi2Stereo));
  const ceres::Solver::Options options = solver_options(10, ceres::DENSE_QR);
  constexpr int kRounds = 4;
  int n_bad = 0;
  for (int round = 0; round < kRounds; ++round) {
    const bool robust = round < kRounds - 1;  // the last round has no robust loss
    ceres::Problem problem(problem_options());
    problem.AddParameterBlock(pose.data(), kPoseSize, &manifold);
    int n_active = 0;
    for (const PoseEdge& e : edges) {
      if (frame.outlier[e.index]) continue;
      ceres::LossFunction* loss = robust ? (e.stereo ? &huber_stereo : &huber_mono) : nullptr;
      problem.AddResidualBlock(e.cost.get(), loss, pose.data());
      ++n_active;
    }
    if (n_active < 3) break;  // too few to constrain the pose: keep the last estimate
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);

    // Classify every correspondence, the excluded ones included.
    n_bad = 0;
    for (const PoseEdge& e : edges) {
      const double chi2 = e.stereo ? chi2_of<3>(e.m, pose.data(), e.x_w.data(), nullptr)
                                   : chi2_of<2>(e.m, pose.data(), e.x_w.data(), nullptr);
      const bool bad = chi2 > (e.stereo ? kChi2Stereo : kChi2Mono);
      frame.outlier[e.index] = bad;
      n_bad += bad;
    }
  }
  frame.T_cw = to_pose(pose.data());
  return static_cast<int>(edges.size()) - n_bad;
}

// ---------------------------------------------------------------------------
// Local bundle adjustment.

namespace {

struct BaKeyFrame {
  KeyFrame* kf;
  bool fixed;
  PoseParams pose;
};

struct BaPoint {
  MapPoint* mp;
  std::array<double, 3> x;
};

struct BaEdge {
  int kf;        // index into the keyframe blocks
  int pt;        // index into the point blocks
  size_t index;  // keypoint index in the keyframe
  bool stereo;
  bool active;
  Measurement m;
  std::unique_ptr<ceres::CostFunction> cost;
};

struct BaProblem {
  std::vector<BaKeyFrame> kfs;
  std::vector<BaPoint> pts;
  std::vector<BaEdge> edges;
};

// chi2 > threshold or behind the camera.
bool edge_is_bad(const BaProblem& ba, const BaEdge& e) {
  double depth = 0;
  const double* pose = ba.kfs[e.kf].pose.data();
  const double* x = ba.pts[e.pt].x.data();
  const double chi2 =
      e.stereo ? chi2_of<3>(e.m, pose, x, &depth) : chi2_of<2>(e.m, pose, x, &depth);
  return chi2 > (e.stereo ? kChi2Stereo : kChi2Mono) || depth <= 0;
}

// One pass over the active edges. Returns false when aborted or failed, in
// which case Ceres leaves the parameter blocks untouched.
bool solve_ba(BaProblem& ba, int iterations, const std::atomic<bool>* abort,
              ceres::LinearSolverType solver = ceres::DENSE_SCHUR) {
  LeftSe3Manifold manifold;
  ceres::HuberLoss huber_mono(std::sqrt(kChi2Mono));
  ceres::HuberLoss huber_stereo(std::sqrt(kChi2Stereo));
  ceres::Problem problem(problem_options());
  std::vector<char> kf_used(ba.kfs.size(), 0), pt_used(ba.pts.size(), 0);
  for (BaEdge& e : ba.edges) {
    if (!e.active) continue;
    double* pose = ba.kfs[e.kf].pose.data();
    if (!kf_used[e.kf]) {
      problem.AddParameterBlock(pose, kPoseSize, &manifold);
      if (ba.kfs[e.kf].fixed) problem.SetParameterBlockConstant(pose);
      kf_used[e.kf] = 1;
    }
    pt_used[e.pt] = 1;
    problem.AddResidualBlock(e.cost.get(), e.stereo ? &huber_stereo : &huber_mono, pose,
                             ba.pts[e.pt].x.data());
  }
  if (problem.NumResidualBlocks() == 0) return true;

  // Schur complement: eliminate the points first.
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (size_t i = 0; i < ba.pts.size(); ++i)
    if (pt_used[i]) ordering->AddElementToGroup(ba.pts[i].x.data(), 0);
  for (size_t i = 0; i < ba.kfs.size(); ++i)
    if (kf_used[i]) ordering->AddElementToGroup(ba.kfs[i].pose.data(), 1);

  ceres::Solver::Options options = solver_options(iterations, solver);
  options.linear_solver_ordering = ordering;
  AbortCallback callback(abort);
  options.callbacks.push_back(&callback);
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return summary.IsSolutionUsable();
}

// Fills a BaProblem: keyframes (optimised or fixed), points, and one edge
// per observation. The caller holds the map lock.
class BaBuilder {
 public:
  explicit BaBuilder(BaProblem& ba) : ba_(ba) {}

  // Index of k's block, added when new; `fixed` counts only when added.
  int add_keyframe(KeyFrame* k, bool fixed) {
    const auto [it, added] = kf_index_.emplace(k, static_cast<int>(ba_.kfs.size()));
    if (added) ba_.kfs.push_back({k, fixed, to_params(k->T_cw)});
    return it->second;
  }
  bool has_keyframe(const KeyFrame* k) const { return kf_index_.count(k) > 0; }

  // False when mp was added before.
  bool add_point(MapPoint* mp) {
    if (!pt_index_.emplace(mp, static_cast<int>(ba_.pts.size())).second) return false;
    ba_.pts.push_back({mp, {mp->position.x(), mp->position.y(), mp->position.z()}});
    return true;
  }

  // One edge per observation of every point; observers not added yet are
  // added by `observer` (which returns their block, or -1 to skip them).
  template <class Observer>
  void add_edges(Observer observer) {
    for (size_t p = 0; p < ba_.pts.size(); ++p)
      for (const auto& [k, idx] : ba_.pts[p].mp->observations) {
        if (k->bad || idx >= k->features.size()) continue;
        const int ki = observer(k);
        if (ki < 0) continue;
        const bool stereo = k->features.u_right[idx] >= 0;
        BaEdge e{ki,   static_cast<int>(p),           idx,    stereo,
                 true, Measurement(k->features, idx), nullptr};
        if (stereo)
          e.cost = std::make_unique<BaCost<3>>(e.m);
        else
          e.cost = std::make_unique<BaCost<2>>(e.m);
        ba_.edges.push_back(std::move(e));
      }
  }

 private:
  BaProblem& ba_;
  std::unordered_map<const KeyFrame*, int> kf_index_;
  std::unordered_map<const MapPoint*, int> pt_index_;
};

}  // namespace

void local_bundle_adjustment(KeyFrame* kf, Map& map, const std::atomic<bool>* abort,
                             const LocalBaOptions& options) {
  if (AbortCallback::aborted(abort)) return;

  BaProblem ba;
  {
    MutexLock lock(map.mutex());
    if (!kf || kf->bad) return;
    BaBuilder builder(ba);
    auto add_kf = [&](KeyFrame* k, bool fixed) {
      const bool added = !builder.has_keyframe(k);
      const int index = builder.add_keyframe(k, fixed || k->map_origin);
      if (added) (fixed ? k->fixed_ba_for : k->local_ba_for) = kf->id;
      return index;
    };

    // Local keyframes: kf and its covisibles.
    add_kf(kf, false);
    for (KeyFrame* k : kf->covisibles(options.max_local_keyframes))
      if (!k->bad) add_kf(k, false);
    const size_t n_local = ba.kfs.size();

    // Local map points: everything the local keyframes see.
    for (size_t i = 0; i < n_local; ++i)
      for (MapPoint* mp : ba.kfs[i].kf->map_points)
        if (mp && !mp->bad && builder.add_point(mp)) mp->local_ba_for = kf->id;

    // One residual per observation; observers outside the local set are fixed.
    builder.add_edges([&](KeyFrame* k) { return add_kf(k, true); });
  }
  if (ba.edges.empty()) return;

  // First pass with everything (robust loss); nothing changes if it is aborted.
  if (!solve_ba(ba, options.iterations_first, abort)) return;
  if (!AbortCallback::aborted(abort)) {
    // Second pass without the first pass's outliers. If it is aborted the
    // parameters keep the first pass's result, which is applied below.
    for (BaEdge& e : ba.edges) e.active = !edge_is_bad(ba, e);
    solve_ba(ba, options.iterations_second, abort);
  }

  std::vector<const BaEdge*> to_erase;
  for (const BaEdge& e : ba.edges)
    if (edge_is_bad(ba, e)) to_erase.push_back(&e);

  MutexLock lock(map.mutex());
  for (const BaEdge* e : to_erase) {
    KeyFrame* k = ba.kfs[e->kf].kf;
    MapPoint* mp = ba.pts[e->pt].mp;
    if (k->bad || mp->bad) continue;
    const auto it = mp->observations.find(k);
    if (it == mp->observations.end() || it->second != e->index) continue;  // changed meanwhile
    if (e->index < k->map_points.size() && k->map_points[e->index] == mp)
      k->erase_map_point(e->index);
    mp->erase_observation(k);
  }
  for (const BaKeyFrame& b : ba.kfs)
    if (!b.fixed && !b.kf->bad) b.kf->T_cw = to_pose(b.pose.data());
  for (const BaPoint& p : ba.pts) {
    if (p.mp->bad) continue;
    p.mp->position = Eigen::Vector3d(p.x[0], p.x[1], p.x[2]);
    p.mp->update_normal_and_depth();
  }
}

// ---------------------------------------------------------------------------
// Global bundle adjustment.

GlobalBaResult global_bundle_adjustment(Map& map, const std::atomic<bool>* abort, int iterations) {
  GlobalBaResult result;
  BaProblem ba;
  {
    MutexLock lock(map.mutex());
    if (!map.first_keyframe()) return result;
    BaBuilder builder(ba);
    // Every map of the atlas, each held by its origin (they share nothing).
    for (KeyFrame* k : map.keyframes())
      if (!k->bad) builder.add_keyframe(k, k->map_origin);
    for (MapPoint* mp : map.map_points())
      if (!mp->bad) builder.add_point(mp);
    // Keyframes are all in; an observer missing from them is bad or gone.
    builder.add_edges(
        [&](KeyFrame* k) { return builder.has_keyframe(k) ? builder.add_keyframe(k, false) : -1; });
  }
  if (ba.edges.empty() || AbortCallback::aborted(abort)) return result;
  // The whole map: a sparse Schur complement (the reduced camera system of
  // a long run is large and sparse).
  const ceres::LinearSolverType solver =
      ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE) ? ceres::SPARSE_SCHUR
                                                                            : ceres::DENSE_SCHUR;
  if (!solve_ba(ba, iterations, abort, solver) || AbortCallback::aborted(abort)) return result;
  result.completed = true;
  for (const BaKeyFrame& b : ba.kfs) result.keyframes.push_back({b.kf, to_pose(b.pose.data())});
  for (const BaPoint& p : ba.pts)
    result.points.push_back({p.mp, Eigen::Vector3d(p.x[0], p.x[1], p.x[2])});
  return result;
}

// ---------------------------------------------------------------------------

double reprojection_rmse(const KeyFrame* kf, size_t* n_used) {
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < kf->map_points.size() && i < kf->features.size(); ++i) {
    const MapPoint* mp = kf->map_points[i];
    if (!mp || mp->bad) continue;
    const Eigen::Vector2d uv = kf->features.camera.project(kf->T_cw * mp->position);
    const cv::Point2f& pt = kf->features.keypoints[i].pt;
    sum += (uv - Eigen::Vector2d(pt.x, pt.y)).squaredNorm();
    ++n;
  }
  if (n_used) *n_used = n;
  return n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

double reprojection_rmse(const Map& map) {
  double sum = 0;
  size_t total = 0;
  for (const KeyFrame* kf : map.keyframes()) {
    size_t n = 0;
    const double rmse = reprojection_rmse(kf, &n);
    sum += rmse * rmse * static_cast<double>(n);
    total += n;
  }
  return total ? std::sqrt(sum / static_cast<double>(total)) : 0.0;
}

}  // namespace depot::slam
