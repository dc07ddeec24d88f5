#include "slam/reject/ego_motion_flow.h"

#include <algorithm>
#include <cmath>

#include <opencv2/calib3d.hpp>

#include "slam/camera/lens_distortion.h"

namespace depot::slam {

EgoMotionModel fit_ego_motion(const PinholeCamera& camera, const std::vector<cv::Point2f>& pixels,
                              const std::vector<float>& depth, const std::vector<cv::Point2f>& flow,
                              const std::vector<uint8_t>& ok, const EgoMotionParams& params) {
  EgoMotionModel model;
  std::vector<cv::Point3f> object;
  std::vector<cv::Point2f> image;
  for (size_t i = 0; i < pixels.size(); ++i) {
    if (!ok[i] || !(depth[i] > 0)) continue;
    const cv::Point2f ray = undistort_pixel(camera, pixels[i]);
    const Eigen::Vector3d p = camera.unproject(ray.x, ray.y, depth[i]);
    object.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                        static_cast<float>(p.z()));
    image.push_back(pixels[i] - flow[i]);
  }
  model.points = static_cast<int>(object.size());
  if (model.points < params.min_points) return model;
  const cv::Matx33d k = opencv_camera_matrix(camera);
  // The flow lives in the image, so the fit projects through the lens.
  const cv::Vec<double, 5> lens = opencv_distortion(camera);
  // Consecutive frames: start from "no motion" and refine.
  cv::Mat rvec = cv::Mat::zeros(3, 1, CV_64F), tvec = cv::Mat::zeros(3, 1, CV_64F);
  std::vector<int> inliers;
  const bool found = cv::solvePnPRansac(object, image, k, lens, rvec, tvec, true, 100,
                                        scaled_px(params.ransac_px, camera), 0.99, inliers,
                                        cv::SOLVEPNP_ITERATIVE);
  model.inliers = static_cast<int>(inliers.size());
  if (!found || model.inliers < params.min_inlier_share * model.points) return model;
  std::vector<cv::Point3f> in_object;
  std::vector<cv::Point2f> in_image;
  for (int i : inliers) {
    in_object.push_back(object[i]);
    in_image.push_back(image[i]);
  }
  cv::solvePnPRefineLM(in_object, in_image, k, lens, rvec, tvec);
  cv::Mat r;
  cv::Rodrigues(rvec, r);
  model.rotation = cv::Matx33d(r);
  model.translation = cv::Vec3d(tvec);
  model.valid = true;
  return model;
}

namespace {

// Where the camera motion puts a static point on `ray` (z = 1), `depth` m
// away (infinite depth: rotation only), in the image. False when behind
// the camera.
bool predict_previous(const EgoMotionModel& model, const PinholeCamera& camera,
                      const Eigen::Vector3d& ray, double depth, cv::Point2d* predicted) {
  const cv::Vec3d dir(ray.x(), ray.y(), ray.z());
  const cv::Vec3d q = std::isfinite(depth) ? model.rotation * (dir * depth) + model.translation
                                           : model.rotation * dir;
  if (q[2] <= 1e-9) return false;
  const cv::Point2f image =
      distort_pixel(camera, cv::Point2f(static_cast<float>(camera.fx * q[0] / q[2] + camera.cx),
                                        static_cast<float>(camera.fy * q[1] / q[2] + camera.cy)));
  *predicted = {image.x, image.y};
  return true;
}

double distance_to_segment(const cv::Point2d& p, const cv::Point2d& a, const cv::Point2d& b) {
  const cv::Point2d ab = b - a;
  const double len2 = ab.dot(ab);
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  const cv::Point2d d = p - (a + t * ab);
  return std::sqrt(d.dot(d));
}

}  // namespace

bool predict_static_previous(const EgoMotionModel& model, const PinholeCamera& camera,
                             const cv::Point2f& pixel, float depth, float no_depth_min,
                             cv::Point2f* near, cv::Point2f* far) {
  if (!model.valid) return false;
  const cv::Point2f undistorted = undistort_pixel(camera, pixel);
  const Eigen::Vector3d ray = camera.unproject(undistorted.x, undistorted.y, 1.0);
  cv::Point2d a, b;
  if (depth > 0) {
    if (!predict_previous(model, camera, ray, depth, &a)) return false;
    b = a;
  } else if (!predict_previous(model, camera, ray, no_depth_min, &a) ||
             !predict_previous(model, camera, ray, INFINITY, &b)) {
    return false;
  }
  *near = cv::Point2f(static_cast<float>(a.x), static_cast<float>(a.y));
  *far = cv::Point2f(static_cast<float>(b.x), static_cast<float>(b.y));
  return true;
}

float distance_to_prediction(const cv::Point2f& seen, const cv::Point2f& near,
                             const cv::Point2f& far) {
  return static_cast<float>(distance_to_segment(seen, near, far));
}

}  // namespace depot::slam
