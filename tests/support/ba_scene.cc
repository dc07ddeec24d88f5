#include "tests/support/ba_scene.h"

#include "slam/data/map_point.h"

namespace depot::slam::test {

const ScaleLevels& levels() {
  static const ScaleLevels lv = ScaleLevels::make(8, 1.2f);
  return lv;
}

Eigen::Matrix3d random_rotation(Rng& rng, double angle) {
  Eigen::Vector3d axis(rng.normal(), rng.normal(), rng.normal());
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

Eigen::Vector3d random_direction(Rng& rng) {
  return Eigen::Vector3d(rng.normal(), rng.normal(), rng.normal()).normalized();
}

Pose perturb(const Pose& T_cw, Rng& rng, double trans, double angle) {
  const Pose T_wc = T_cw.inverse();
  Pose out = make_pose(Eigen::Matrix3d(random_rotation(rng, angle) * T_wc.linear()),
                       Eigen::Vector3d(T_wc.translation() + trans * random_direction(rng)));
  return out.inverse();
}

Pose camera_pose(const Eigen::Vector3d& center, double yaw) {
  const Eigen::Matrix3d R_wc = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return make_pose(R_wc, center).inverse();
}

Features make_features(const std::vector<Keypoint>& kps, const PinholeCamera& cam) {
  Features f;
  f.camera = cam;
  f.levels = &levels();
  f.descriptors = cv::Mat::zeros(static_cast<int>(kps.size()), 32, CV_8U);
  for (const Keypoint& k : kps) {
    f.keypoints.emplace_back(static_cast<float>(k.u), static_cast<float>(k.v), 31.0f, -1.0f, 0.0f,
                             k.octave);
    f.depth.push_back(k.z > 0 ? static_cast<float>(k.z) : -1.0f);
    f.u_right.push_back(k.z > 0 ? static_cast<float>(cam.right_u(k.u, k.z)) : -1.0f);
  }
  return f;
}

void build_ba_scene(BaScene& s, uint64_t seed, int n_gross_per_kf) {
  MutexLock lock(s.map.mutex());  // the map is built as any writer builds it
  Rng rng(seed);
  const PinholeCamera cam;
  constexpr int kKeyframes = 5, kPoints = 400;
  for (int k = 0; k < kKeyframes; ++k)
    s.truth.push_back(camera_pose(Eigen::Vector3d(0.15 * k, 0.02 * k, 0.05 * k), -0.03 * k));
  // Points in front of the middle camera, spread in depth.
  const Pose mid_wc = s.truth[kKeyframes / 2].inverse();
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < kPoints; ++i)
    points.push_back(mid_wc * cam.unproject(rng.uniform(60, cam.width - 60),
                                            rng.uniform(50, cam.height - 50),
                                            rng.uniform(1.5, 5.0)));

  std::vector<std::vector<int>> point_of(kKeyframes);  // per keyframe: point of each keypoint
  for (int k = 0; k < kKeyframes; ++k) {
    std::vector<Keypoint> kps;
    for (int i = 0; i < kPoints; ++i) {
      const Eigen::Vector3d pc = s.truth[k] * points[i];
      if (pc.z() <= 0.1) continue;
      const Eigen::Vector2d uv = cam.project(pc);
      if (!cam.in_image(uv.x(), uv.y())) continue;
      kps.push_back({uv.x() + rng.normal(0, 0.5), uv.y() + rng.normal(0, 0.5),
                     pc.z() * (1.0 + rng.normal(0, 0.002)), static_cast<int>(rng.below(3))});
      point_of[k].push_back(i);
    }
    s.gross.emplace_back();
    for (int g = 0; g < n_gross_per_kf; ++g) {
      const size_t idx = rng.below(kps.size());
      kps[idx].u += 40 * (rng.uniform() < 0.5 ? -1 : 1);
      kps[idx].v += 30;
      s.gross.back().push_back(idx);
    }
    Frame f(k, 0.1 * k, make_features(kps, cam));
    f.T_cw = k == 0 ? s.truth[0] : perturb(s.truth[k], rng, 0.02, 1 * kDeg);
    f.has_pose = true;
    s.kfs.push_back(s.map.create_keyframe(f));
  }
  std::vector<MapPoint*> mps;
  for (int i = 0; i < kPoints; ++i)
    mps.push_back(s.map.create_map_point(points[i] + 0.03 * random_direction(rng), s.kfs[0]));
  for (int k = 0; k < kKeyframes; ++k)
    for (size_t idx = 0; idx < point_of[k].size(); ++idx) {
      MapPoint* mp = mps[point_of[k][idx]];
      mp->add_observation(s.kfs[k], idx);
      s.kfs[k]->add_map_point(mp, idx);
    }
  for (MapPoint* mp : mps) {
    if (!mp->observations.count(mp->reference)) mp->reference = mp->observations.begin()->first;
    mp->update_normal_and_depth();
  }
  for (KeyFrame* kf : s.kfs) kf->update_connections();
}

}  // namespace depot::slam::test
