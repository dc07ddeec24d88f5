#include "slam/match/orb_matcher.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <opencv2/features2d.hpp>

#include "slam/feature/descriptor_distance.h"

namespace depot::slam {
namespace {

constexpr int kHistogramLength = 30;

// Keeps only matches whose keypoint rotation change agrees with the three
// most common changes (ORB-SLAM2's orientation consistency check).
class RotationHistogram {
 public:
  void add(float angle_a, float angle_b, size_t index) {
    float rot = angle_a - angle_b;
    if (rot < 0) rot += 360.0f;
    int bin = static_cast<int>(std::round(rot * kHistogramLength / 360.0f)) % kHistogramLength;
    bins_[bin].push_back(index);
  }
  // Indices outside the three fullest bins.
  std::vector<size_t> rejected() const {
    std::array<size_t, 3> top{};
    std::array<int, 3> best = {-1, -1, -1};
    for (int i = 0; i < kHistogramLength; ++i) {
      size_t n = bins_[i].size();
      if (best[0] < 0 || n > bins_[best[0]].size()) {
        best = {i, best[0], best[1]};
      } else if (best[1] < 0 || n > bins_[best[1]].size()) {
        best = {best[0], i, best[1]};
      } else if (best[2] < 0 || n > bins_[best[2]].size()) {
        best[2] = i;
      }
    }
    for (int k = 0; k < 3; ++k) top[k] = best[k] < 0 ? 0 : bins_[best[k]].size();
    // Bins much smaller than the best do not count as consistent.
    std::vector<size_t> out;
    for (int i = 0; i < kHistogramLength; ++i) {
      bool keep = (i == best[0]) || (i == best[1] && top[1] >= 0.1 * top[0]) ||
                  (i == best[2] && top[2] >= 0.1 * top[0]);
      if (!keep) out.insert(out.end(), bins_[i].begin(), bins_[i].end());
    }
    return out;
  }

 private:
  std::array<std::vector<size_t>, kHistogramLength> bins_;
};

double radius_by_viewing_cos(double view_cos) {
  return view_cos > 0.998 ? 2.5 : 4.0;
}

}  // namespace

bool project_into(const MapPoint& mp, const Pose& T_cw, const Features& f, ProjectedPoint& out) {
  const Eigen::Vector3d pc = T_cw * mp.position;
  if (pc.z() <= 0) return false;
  const Eigen::Vector2d uv = f.camera.project(pc);
  if (!f.camera.in_image(uv.x(), uv.y())) return false;
  const Eigen::Vector3d center = T_cw.inverse().translation();
  const Eigen::Vector3d po = mp.position - center;
  const double dist = po.norm();
  if (dist < 0.8 * mp.min_distance || dist > 1.2 * mp.max_distance) return false;
  const double view_cos = po.dot(mp.normal) / dist;
  if (view_cos < 0.5) return false;
  out.point = const_cast<MapPoint*>(&mp);
  out.u = uv.x();
  out.v = uv.y();
  out.u_right = uv.x() - f.camera.bf / pc.z();
  out.level = mp.predict_level(static_cast<float>(dist), *f.levels);
  out.view_cos = view_cos;
  return true;
}

int match_by_projection(Frame& current, const Frame& last, float th) {
  const Features& f = current.features;
  const ScaleLevels& lv = *f.levels;
  const Pose T_lc = last.T_cw * current.T_cw.inverse();
  const double baseline = f.camera.bf / f.camera.fx;
  const bool forward = T_lc.translation().z() > baseline;    // current is ahead of last
  const bool backward = -T_lc.translation().z() > baseline;  // current is behind last
  RotationHistogram hist;
  int matches = 0;
  for (size_t i = 0; i < last.size(); ++i) {
    MapPoint* mp = last.map_points[i];
    if (!mp || mp->bad || last.outlier[i]) continue;
    const Eigen::Vector3d pc = current.T_cw * mp->position;
    if (pc.z() <= 0) continue;
    const Eigen::Vector2d uv = f.camera.project(pc);
    if (!f.camera.in_image(uv.x(), uv.y())) continue;
    const int last_level = last.features.keypoints[i].octave;
    const double radius = th * lv.scale[last_level];
    std::vector<size_t> candidates;
    if (forward) {
      candidates = f.in_area(uv.x(), uv.y(), radius, last_level, -1);
    } else if (backward) {
      candidates = f.in_area(uv.x(), uv.y(), radius, 0, last_level);
    } else {
      candidates = f.in_area(uv.x(), uv.y(), radius, std::max(0, last_level - 1), last_level + 1);
    }
    const double u_right = uv.x() - f.camera.bf / pc.z();
    int best = 256;
    size_t best_idx = 0;
    for (size_t j : candidates) {
      MapPoint* existing = current.map_points[j];
      if (existing && existing->n_observations() > 0) continue;
      if (f.u_right[j] > 0 && std::abs(u_right - f.u_right[j]) > radius) continue;
      const int d = descriptor_distance(mp->descriptor, f.descriptors.row(static_cast<int>(j)));
      if (d < best) best = d, best_idx = j;
    }
    if (best <= kMatchThHigh) {
      current.map_points[best_idx] = mp;
      ++matches;
      hist.add(last.features.keypoints[i].angle, f.keypoints[best_idx].angle, best_idx);
    }
  }
  for (size_t j : hist.rejected()) {
    if (current.map_points[j]) {
      current.map_points[j] = nullptr;
      --matches;
    }
  }
  return matches;
}

int match_local_points(Frame& frame, const std::vector<ProjectedPoint>& points, float th) {
  const Features& f = frame.features;
  int matches = 0;
  for (const ProjectedPoint& p : points) {
    MapPoint* mp = p.point;
    if (mp->bad) continue;
    const double radius = radius_by_viewing_cos(p.view_cos) * th * f.levels->scale[p.level];
    std::vector<size_t> candidates = f.in_area(p.u, p.v, radius, p.level - 1, p.level);
    int best = 256, second = 256, best_level = -1, second_level = -1;
    size_t best_idx = 0;
    for (size_t j : candidates) {
      MapPoint* existing = frame.map_points[j];
      if (existing && existing->n_observations() > 0) continue;
      if (f.u_right[j] > 0 && std::abs(p.u_right - f.u_right[j]) > radius) continue;
      const int d = descriptor_distance(mp->descriptor, f.descriptors.row(static_cast<int>(j)));
      if (d < best) {
        second = best, second_level = best_level;
        best = d, best_level = f.keypoints[j].octave, best_idx = j;
      } else if (d < second) {
        second = d, second_level = f.keypoints[j].octave;
      }
    }
    if (best > kMatchThHigh) continue;
    if (best_level == second_level && best > 0.8 * second) continue;
    frame.map_points[best_idx] = mp;
    ++matches;
  }
  return matches;
}

int match_by_descriptor(const KeyFrame& kf, const Frame& frame, std::vector<MapPoint*>& matches,
                        float ratio) {
  matches.assign(frame.size(), nullptr);
  std::vector<size_t> kf_index;
  cv::Mat kf_desc;
  for (size_t i = 0; i < kf.map_points.size(); ++i) {
    MapPoint* mp = kf.map_points[i];
    if (!mp || mp->bad) continue;
    kf_index.push_back(i);
    kf_desc.push_back(kf.features.descriptors.row(static_cast<int>(i)));
  }
  if (kf_index.empty() || frame.features.descriptors.empty()) return 0;
  std::vector<std::vector<cv::DMatch>> knn;
  cv::BFMatcher matcher(cv::NORM_HAMMING);
  matcher.knnMatch(kf_desc, frame.features.descriptors, knn, 2);
  RotationHistogram hist;
  std::vector<int> best_dist(frame.size(), 256);
  int n = 0;
  for (const auto& m : knn) {
    if (m.empty() || m[0].distance > kMatchThLow) continue;
    if (m.size() > 1 && m[0].distance >= ratio * m[1].distance) continue;
    const size_t ki = kf_index[m[0].queryIdx];
    const size_t fi = static_cast<size_t>(m[0].trainIdx);
    if (m[0].distance >= best_dist[fi]) continue;  // keep the better of two claims
    if (!matches[fi]) ++n;
    matches[fi] = kf.map_points[ki];
    best_dist[fi] = static_cast<int>(m[0].distance);
    hist.add(kf.features.keypoints[ki].angle, frame.features.keypoints[fi].angle, fi);
  }
  for (size_t fi : hist.rejected()) {
    if (matches[fi]) {
      matches[fi] = nullptr;
      --n;
    }
  }
  return n;
}

int match_by_bow(const KeyFrame& kf, const Frame& frame, std::vector<MapPoint*>& matches,
                 float ratio) {
  matches.assign(frame.size(), nullptr);
  RotationHistogram hist;
  int n = 0;
  auto ik = kf.bow_features.begin();
  auto iff = frame.bow_features.begin();
  while (ik != kf.bow_features.end() && iff != frame.bow_features.end()) {
    if (ik->first < iff->first) {
      ik = kf.bow_features.lower_bound(iff->first);
      continue;
    }
    if (iff->first < ik->first) {
      iff = frame.bow_features.lower_bound(ik->first);
      continue;
    }
    for (size_t ki : ik->second) {
      MapPoint* mp = kf.map_points[ki];
      if (!mp || mp->bad) continue;
      const uint8_t* d_kf = kf.features.descriptors.ptr<uint8_t>(static_cast<int>(ki));
      int best = 256, second = 256;
      size_t best_fi = 0;
      for (size_t fi : iff->second) {
        if (matches[fi]) continue;
        const int d = descriptor_distance(
            d_kf, frame.features.descriptors.ptr<uint8_t>(static_cast<int>(fi)));
        if (d < best) {
          second = best;
          best = d, best_fi = fi;
        } else if (d < second) {
          second = d;
        }
      }
      if (best > kMatchThLow || best >= ratio * second) continue;
      matches[best_fi] = mp;
      ++n;
      hist.add(kf.features.keypoints[ki].angle, frame.features.keypoints[best_fi].angle, best_fi);
    }
    ++ik, ++iff;
  }
  for (size_t fi : hist.rejected()) {
    if (matches[fi]) {
      matches[fi] = nullptr;
      --n;
    }
  }
  return n;
}

int match_for_triangulation(const KeyFrame& kf1, const KeyFrame& kf2,
                            std::vector<std::pair<size_t, size_t>>& pairs) {
  pairs.clear();
  const Features& f1 = kf1.features;
  const Features& f2 = kf2.features;
  // Fundamental matrix F12 with x1^T F12 x2 = 0.
  const Pose T12 = kf1.T_cw * kf2.T_cw.inverse();
  const Eigen::Matrix3d R12 = T12.linear();
  const Eigen::Vector3d t12 = T12.translation();
  Eigen::Matrix3d tx;
  tx << 0, -t12.z(), t12.y(), t12.z(), 0, -t12.x(), -t12.y(), t12.x(), 0;
  Eigen::Matrix3d K;
  K << f1.camera.fx, 0, f1.camera.cx, 0, f1.camera.fy, f1.camera.cy, 0, 0, 1;
  const Eigen::Matrix3d Kinv = K.inverse();
  const Eigen::Matrix3d F12 = Kinv.transpose() * tx * R12 * Kinv;
  // Epipole of camera 1 in image 2: keypoints near it give unstable points.
  const Eigen::Vector3d c1_in_2 = kf2.T_cw * kf1.camera_center();
  const Eigen::Vector2d epipole = f2.camera.project(c1_in_2);
  const bool epipole_valid = c1_in_2.z() > 0;

  std::vector<int> claimed(f2.size(), -1);
  std::vector<int> claimed_dist(f2.size(), 256);
  RotationHistogram hist;
  // The best epipolar match in image 2 for keypoint i of image 1 among
  // `candidates`; a keypoint of image 2 keeps the closest claim.
  auto match_one = [&](size_t i, const std::vector<size_t>& candidates) {
    if (kf1.map_points[i]) return;
    const cv::KeyPoint& k1 = f1.keypoints[i];
    const Eigen::Vector3d line =
        F12.transpose() * Eigen::Vector3d(k1.pt.x, k1.pt.y, 1.0);  // in image 2
    const double norm = line.head<2>().squaredNorm();
    if (norm < 1e-12) return;
    const uint8_t* d1 = f1.descriptors.ptr<uint8_t>(static_cast<int>(i));
    int best = kMatchThLow + 1;
    size_t best_j = 0;
    for (size_t j : candidates) {
      if (kf2.map_points[j]) continue;
      const int d = descriptor_distance(d1, f2.descriptors.ptr<uint8_t>(static_cast<int>(j)));
      if (d >= best) continue;
      const cv::KeyPoint& k2 = f2.keypoints[j];
      if (epipole_valid) {
        const double ex = epipole.x() - k2.pt.x, ey = epipole.y() - k2.pt.y;
        if (ex * ex + ey * ey < 100.0 * f2.levels->scale[k2.octave]) continue;
      }
      const double num = line.x() * k2.pt.x + line.y() * k2.pt.y + line.z();
      if (num * num / norm >= 3.84 * f2.levels->sigma2[k2.octave]) continue;
      best = d, best_j = j;
    }
    if (best > kMatchThLow) return;
    if (claimed[best_j] >= 0 && best >= claimed_dist[best_j]) return;
    claimed[best_j] = static_cast<int>(i);
    claimed_dist[best_j] = best;
  };
  if (!kf1.bow_features.empty() && !kf2.bow_features.empty()) {
    // Only keypoints under the same vocabulary node are compared
    // (ORB-SLAM2's SearchForTriangulation): a tenth of the pairs or fewer.
    auto a = kf1.bow_features.begin();
    auto b = kf2.bow_features.begin();
    while (a != kf1.bow_features.end() && b != kf2.bow_features.end()) {
      if (a->first < b->first) {
        a = kf1.bow_features.lower_bound(b->first);
      } else if (b->first < a->first) {
        b = kf2.bow_features.lower_bound(a->first);
      } else {
        for (size_t i : a->second) match_one(i, b->second);
        ++a, ++b;
      }
    }
  } else {
    std::vector<size_t> all2(f2.size());
    for (size_t j = 0; j < f2.size(); ++j) all2[j] = j;
    for (size_t i = 0; i < f1.size(); ++i) match_one(i, all2);
  }
  for (size_t j = 0; j < f2.size(); ++j) {
    if (claimed[j] < 0) continue;
    hist.add(f1.keypoints[claimed[j]].angle, f2.keypoints[j].angle, j);
  }
  std::vector<size_t> rejected = hist.rejected();
  for (size_t j : rejected) claimed[j] = -1;
  for (size_t j = 0; j < f2.size(); ++j)
    if (claimed[j] >= 0) pairs.emplace_back(static_cast<size_t>(claimed[j]), j);
  return static_cast<int>(pairs.size());
}

int fuse(KeyFrame* kf, const std::vector<MapPoint*>& points, float th) {
  const Features& f = kf->features;
  int fused = 0;
  for (MapPoint* mp : points) {
    if (!mp || mp->bad || mp->observations.count(kf)) continue;
    ProjectedPoint p;
    if (!project_into(*mp, kf->T_cw, f, p)) continue;
    const double radius = th * f.levels->scale[p.level];
    int best = 256;
    size_t best_idx = 0;
    for (size_t j : f.in_area(p.u, p.v, radius)) {
      const cv::KeyPoint& kp = f.keypoints[j];
      if (kp.octave < p.level - 1 || kp.octave > p.level) continue;
      const double ex = p.u - kp.pt.x, ey = p.v - kp.pt.y;
      double e2 = ex * ex + ey * ey;
      const double inv_sigma2 = f.levels->inv_sigma2[kp.octave];
      if (f.u_right[j] >= 0) {
        const double er = p.u_right - f.u_right[j];
        if ((e2 + er * er) * inv_sigma2 > 7.8) continue;
      } else if (e2 * inv_sigma2 > 5.99) {
        continue;
      }
      const int d = descriptor_distance(mp->descriptor, f.descriptors.row(static_cast<int>(j)));
      if (d < best) best = d, best_idx = j;
    }
    if (best > kMatchThLow) continue;
    MapPoint* existing = kf->map_points[best_idx];
    if (existing && !existing->bad) {
      if (existing->n_observations() > mp->n_observations()) {
        mp->replace(existing);
      } else {
        existing->replace(mp);
      }
    } else {
      mp->add_observation(kf, best_idx);
      kf->add_map_point(mp, best_idx);
    }
    ++fused;
  }
  return fused;
}

}  // namespace depot::slam
