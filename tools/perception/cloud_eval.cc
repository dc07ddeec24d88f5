#include "tools/perception/cloud_eval.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <vector>

#include <assimp/scene.h>
#include <assimp/Importer.hpp>
#include <opencv2/flann.hpp>

#include "common/error.h"
#include "common/percentile.h"
#include "common/progress.h"
#include "common/tum_io.h"
#include "dataset/dataset_info.h"
#include "dataset/objects.h"
#include "eval/alignment.h"
#include "eval/ate.h"
#include "eval/instance_classes.h"
#include "eval/matched_trajectories.h"
#include "eval/motion_truth.h"
#include "slam/camera/lens_distortion.h"
#include "slam/dense/dense_cloud.h"
#include "slam/io/ply_file.h"
#include "slam/io/settings.h"
#include "slam/io/tum_sequence.h"

namespace fs = std::filesystem;

namespace depot::perception {
namespace {

std::vector<Eigen::Vector3d> read_cloud(const std::string& path) {
  // assimp pads a cut file's missing rows with zeros: our own check of the
  // header against the body comes first.
  const slam::PlyCheck ply = slam::check_ply_file(path);
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, 0);
  if (!scene)
    fail(path, std::string("not a point cloud assimp reads (") + importer.GetErrorString() + ")");
  std::vector<Eigen::Vector3d> points;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
      const aiVector3D& v = mesh->mVertices[i];
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        fail(path, "point " + std::to_string(i) + " is not finite");
      points.emplace_back(v.x, v.y, v.z);
    }
  }
  if (points.empty()) fail(path, "has no points");
  if (ply.only_vertices && points.size() != ply.vertices)
    fail(path, "assimp read " + std::to_string(points.size()) +
                   " points where the header declares " + std::to_string(ply.vertices));
  return points;
}

// --static must name the same scenario and seed rendered with nothing living
// in it and exact depth (`sim render ... --load 0 --ideal`): anything else
// would score the cloud against a surface with people in it, or noise.
void check_static_render(const std::string& static_dataset, const std::string& dataset) {
  const std::string not_static = "is not a static render of " + dataset + ": ";
  const std::string how = " (render it with `depot sim render SCENARIO --load 0 --ideal`)";
  const std::optional<dataset::DatasetInfo> info = dataset::read_info(static_dataset);
  if (!info) fail(static_dataset, not_static + "it has no info.json (the simulator writes one)");
  if (!info->dynamic_load || *info->dynamic_load != 0.0) {
    const std::string load =
        info->dynamic_load ? fmt::format("{:g}", *info->dynamic_load) : "not stated";
    fail(static_dataset, not_static + "its dynamic_load is " + load + how);
  }
  if (info->sensor && *info->sensor != "ideal")
    fail(static_dataset,
         not_static + "its depth is the " + *info->sensor + " sensor model's, not exact" + how);
  const std::optional<dataset::DatasetInfo> of = dataset::read_info(dataset);
  auto named = [](const dataset::DatasetInfo& i) {
    return i.scenario + " seed " + (i.seed ? std::to_string(*i.seed) : "?");
  };
  if (of && (of->scenario != info->scenario || of->seed != info->seed))
    fail(static_dataset, not_static + "it renders " + named(*info) + ", the dataset " + named(*of));
}

// The true camera-to-world pose of each frame, by rgb timestamp (the
// simulator writes one ground-truth pose per frame).
class TruePoses {
 public:
  explicit TruePoses(const std::string& dataset) {
    const std::string path = (fs::path(dataset) / "groundtruth.txt").string();
    for (const StampedPose& p : read_tum_trajectory(path)) poses_[p.timestamp] = p.pose;
    if (poses_.empty()) fail(path, "has no poses");
  }
  const Pose* at(double t) const {
    auto after = poses_.lower_bound(t);
    const Pose* best = nullptr;
    double best_dt = 0.005;  // half a frame at 100 Hz
    if (after != poses_.end() && after->first - t < best_dt) {
      best = &after->second;
      best_dt = after->first - t;
    }
    if (after != poses_.begin() && t - std::prev(after)->first < best_dt)
      best = &std::prev(after)->second;
    return best;
  }

 private:
  std::map<double, Pose> poses_;
};

slam::PinholeCamera dataset_camera(const slam::TumSequence& sequence) {
  if (sequence.calibration_path().empty())
    fail(sequence.folder(), "has no calibration.yaml (not a simulated dataset)");
  return slam::load_settings(sequence.calibration_path(), slam::SlamSettings()).camera;
}

}  // namespace

CloudScore score_static_cloud(const CloudScoreOptions& o) {
  if (o.every < 1 || o.static_every < 1) fail("eval cloud", "frame steps must be at least 1");
  CloudScore score;
  const std::vector<Eigen::Vector3d> cloud = read_cloud(o.cloud);
  score.points = cloud.size();
  const eval::MotionTruth truth(o.dataset);
  slam::TumSequence sequence(o.dataset);
  const slam::PinholeCamera camera = dataset_camera(sequence);
  sequence.set_depth_factor(camera.depth_factor);
  const TruePoses true_poses(o.dataset);

  // The cloud in the truth's world: the run's poses aligned to the truth's
  // (eval::align_poses; positions alone leave a small trajectory's world
  // turned by a few tenths of a degree, centimetres at a map's far wall).
  const eval::MatchedTrajectories matched = eval::load_matched_trajectories(
      (fs::path(o.dataset) / "groundtruth.txt").string(), o.trajectory);
  score.alignment_rmse = eval::compute_ate(matched).statistics.rmse;
  const eval::SimilarityTransform alignment =
      eval::align_poses(matched.estimate, matched.reference);
  std::vector<Eigen::Vector3d> world(cloud.size());
  for (size_t i = 0; i < cloud.size(); ++i) world[i] = alignment.apply(cloud[i]);

  // Accuracy first: a point on the true static surface is the static
  // world's, whatever moved past it.
  cv::Mat bgr, depth;
  std::vector<double> distances;
  if (!o.static_dataset.empty()) {
    check_static_render(o.static_dataset, o.dataset);
    // The true static surface: the static render's exact depth at its true
    // poses, 5 mm voxels (finer than any map's).
    slam::TumSequence scene(o.static_dataset);
    const slam::PinholeCamera scene_camera = dataset_camera(scene);
    scene.set_depth_factor(scene_camera.depth_factor);
    const TruePoses scene_poses(o.static_dataset);
    slam::DenseCloudParams fine;
    fine.voxel_m = 0.005f;
    fine.max_depth_m = 20.0f;
    fine.stride = 1;
    fine.mask_margin_px = 0;
    fine.min_views = 1;
    fine.free_space = false;  // nothing moves in the static render
    slam::DenseCloud surface(scene_camera, fine);
    Progress surface_progress("eval cloud: static surface", scene.size(), !o.quiet);
    for (size_t f = 0; f < scene.size(); f += o.static_every) {
      surface_progress.update(f);
      const double t = scene.entry(f).rgb_timestamp;
      const Pose* T_wc = scene_poses.at(t);
      if (!T_wc) continue;
      const Pose* same = true_poses.at(t);
      if (!same || (same->translation() - T_wc->translation()).norm() > 1e-4)
        fail(o.static_dataset,
             "is not a static render of " + o.dataset + ": " +
                 (same ? "their camera paths differ" : "the dataset has no frame") +
                 " at t = " + std::to_string(t));
      scene.load(f, bgr, depth);
      surface.add_view(*T_wc, depth, bgr);
    }
    surface_progress.update(scene.size());
    surface_progress.finish();
    const std::vector<slam::PlyPoint> reference = surface.points();
    if (reference.empty()) fail(o.static_dataset, "has no depth to make a surface of");
    score.surface_points = reference.size();
    cv::Mat reference_mat(static_cast<int>(reference.size()), 3, CV_32F);
    for (size_t i = 0; i < reference.size(); ++i)
      for (int k = 0; k < 3; ++k)
        reference_mat.at<float>(static_cast<int>(i), k) = reference[i].position[k];
    cv::Mat query(static_cast<int>(world.size()), 3, CV_32F);
    for (size_t i = 0; i < world.size(); ++i)
      for (int k = 0; k < 3; ++k)
        query.at<float>(static_cast<int>(i), k) = static_cast<float>(world[i][k]);
    // One tree searched without a limit on checks: exact nearest neighbours.
    cv::flann::Index index(reference_mat, cv::flann::KDTreeIndexParams(1));
    cv::Mat indices, squared;
    index.knnSearch(query, indices, squared, 1, cv::flann::SearchParams(-1));
    distances.resize(world.size());
    size_t near = 0;
    for (size_t i = 0; i < world.size(); ++i) {
      distances[i] = std::sqrt(static_cast<double>(squared.at<float>(static_cast<int>(i), 0)));
      near += distances[i] <= o.near_m;
    }
    score.has_accuracy = true;
    score.distance = eval::compute_statistics(distances);
    score.p90_m = percentile(distances, 0.9);
    score.near_share = static_cast<double>(near) / world.size();
  }

  // On moving objects: frames where something moves, the point on its pixel
  // and at its depth.
  std::vector<uint8_t> on_moving(world.size(), 0);
  const std::map<int, std::string> classes =
      eval::instance_classes(dataset::read_objects(o.dataset));
  Progress progress("eval cloud: movers", sequence.size(), !o.quiet);
  for (size_t f = 0; f < sequence.size(); f += o.every) {
    progress.update(f + 1, "");
    const double t = sequence.entry(f).rgb_timestamp;
    const Pose* T_wc = true_poses.at(t);
    if (!T_wc) continue;
    cv::Mat labels;
    const cv::Mat moving = truth.moving_mask(t, &labels);
    ++score.frames_checked;
    if (cv::countNonZero(moving) == 0) continue;
    sequence.load(f, bgr, depth);
    const Pose T_cw = T_wc->inverse();
    for (size_t i = 0; i < world.size(); ++i) {
      if (on_moving[i]) continue;
      if (!distances.empty() && distances[i] <= o.static_tolerance_m) continue;
      const Eigen::Vector3d p = T_cw * world[i];
      if (p.z() <= 0.05) continue;
      const Eigen::Vector2d uv = camera.project(p);
      const cv::Point2f pixel = slam::distort_pixel(
          camera, cv::Point2f(static_cast<float>(uv.x()), static_cast<float>(uv.y())));
      const int u = static_cast<int>(std::lround(pixel.x)),
                v = static_cast<int>(std::lround(pixel.y));
      if (u < 0 || v < 0 || u >= moving.cols || v >= moving.rows || !moving.at<uint8_t>(v, u))
        continue;
      const float z = depth.at<float>(v, u);
      if (z > 0 && std::abs(z - p.z()) <= o.depth_tolerance_m + o.depth_tolerance_per_m * p.z()) {
        on_moving[i] = 1;
        const auto c = classes.find(labels.at<uint16_t>(v, u));
        ++score.on_moving_by_class[c == classes.end() ? "unknown" : c->second];
      }
    }
  }
  progress.finish();
  score.on_moving = static_cast<size_t>(std::count(on_moving.begin(), on_moving.end(), 1));

  return score;
}

}  // namespace depot::perception
