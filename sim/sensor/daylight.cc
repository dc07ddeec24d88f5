#include "sim/sensor/daylight.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/number_text.h"
#include "sim/sensor/light.h"

namespace depot::sim {

namespace {

constexpr double kOnWall = 0.05;  // m, how near a wall an opening's centre must lie
// A surface this far behind the wall's plane still lies on it (depth noise
// of the exact render is far smaller).
constexpr double kBehindWall = 0.05;
// The floor in front of an open door stays floor: the opening starts 1 cm up.
constexpr double kAboveFloor = 0.01;

}  // namespace

std::vector<WallOpening> place_openings(const std::vector<Scenario::Opening>& openings,
                                        double length, double width, double height) {
  const double hx = length / 2, hy = width / 2;
  struct Wall {
    const char* name;
    double distance;  // of the centre from the wall
    Eigen::Vector3d foot, along, inward;
    double half_length;
  };
  std::vector<WallOpening> placed;
  for (const Scenario::Opening& o : openings) {
    const double x = o.centre.x(), y = o.centre.y();
    const Wall walls[] = {{"north", std::abs(y - hy), {x, hy, 0}, {1, 0, 0}, {0, -1, 0}, hx},
                          {"south", std::abs(y + hy), {x, -hy, 0}, {1, 0, 0}, {0, 1, 0}, hx},
                          {"east", std::abs(x - hx), {hx, y, 0}, {0, 1, 0}, {-1, 0, 0}, hy},
                          {"west", std::abs(x + hx), {-hx, y, 0}, {0, 1, 0}, {1, 0, 0}, hy}};
    const Wall* wall = &walls[0];
    for (const Wall& w : walls)
      if (w.distance < wall->distance) wall = &w;
    if (wall->distance > kOnWall)
      fail(o.where, "opening centre (" + metres_text(x) + ", " + metres_text(y) + ") is " +
                        metres_text(wall->distance) + " from the nearest wall (" + wall->name +
                        "); an opening lies on a wall's foot");
    // It keeps kLeafDepth from the wall's ends: the wall round the corner
    // lies that near its plane and would show the outside too.
    const double along_centre = wall->along.dot(wall->foot);
    if (std::abs(along_centre) + o.width / 2 > wall->half_length - kLeafDepth + 1e-9)
      fail(o.where, "opening " + metres_text(o.width) + " wide at " + metres_text(along_centre) +
                        " comes within " + metres_text(kLeafDepth) + " of the end of the " +
                        wall->name + " wall (" + metres_text(2 * wall->half_length) + " long)");
    if (o.height > height + 1e-9)
      fail(o.where, "opening " + metres_text(o.height) + " high is taller than the hall (" +
                        metres_text(height) + ")");
    WallOpening w;
    w.foot = wall->foot;
    w.along = wall->along;
    w.inward = wall->inward;
    w.width = o.width;
    w.height = o.height;
    w.radiance = o.radiance;
    w.open = o.open;
    placed.push_back(w);
  }
  return placed;
}

cv::Mat pixel_rays(const CameraIntrinsics& camera, const LensMapping* lens) {
  cv::Mat rays(camera.height, camera.width, CV_32FC2);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      cv::Vec2f& r = rays.at<cv::Vec2f>(y, x);
      if (lens) {
        // The canvas pixel the lens took this pixel's depth from (nearest,
        // border replicated: sim/sensor/lens.cc), not the exact map: the
        // depth belongs to that pixel's ray.
        const CameraIntrinsics& c = lens->canvas;
        const int u = std::clamp(cvRound(lens->map_x.at<float>(y, x)), 0, c.width - 1);
        const int v = std::clamp(cvRound(lens->map_y.at<float>(y, x)), 0, c.height - 1);
        r[0] = static_cast<float>((u - c.cx) / c.f);
        r[1] = static_cast<float>((v - c.cy) / c.f);
      } else {
        r[0] = static_cast<float>((x - camera.cx) / camera.f);
        r[1] = static_cast<float>((y - camera.cy) / camera.focal_y());
      }
    }
  return rays;
}

cv::Mat daylight_radiance(const cv::Mat& depth, const cv::Mat& rays, const Pose& world_camera,
                          const std::vector<WallOpening>& openings, double t) {
  if (depth.type() != CV_32F || rays.type() != CV_32FC2 || depth.size() != rays.size())
    fail("daylight", "depth and pixel rays differ in size or type");
  // Each opening's open rectangle, in the camera's frame.
  struct Open {
    Eigen::Vector3d foot, along, inward;
    double half_width, top, radiance;
  };
  std::vector<Open> open;
  const Pose camera_from_world = world_camera.inverse();
  for (const WallOpening& o : openings) {
    const double share = light_level_at(o.open, t);
    if (share <= 0) continue;
    open.push_back({camera_from_world * o.foot, camera_from_world.linear() * o.along,
                    camera_from_world.linear() * o.inward, o.width / 2, share * o.height,
                    o.radiance});
  }
  if (open.empty()) return {};
  const Eigen::Vector3d up = camera_from_world.linear() * Eigen::Vector3d::UnitZ();
  cv::Mat radiance(depth.size(), CV_32F, cv::Scalar(0));
  bool any = false;
  for (int y = 0; y < depth.rows; ++y) {
    const float* d = depth.ptr<float>(y);
    const cv::Vec2f* r = rays.ptr<cv::Vec2f>(y);
    float* out = radiance.ptr<float>(y);
    for (int x = 0; x < depth.cols; ++x) {
      if (d[x] <= 0) continue;
      const Eigen::Vector3d p(r[x][0] * d[x], r[x][1] * d[x], d[x]);
      for (const Open& o : open) {
        const Eigen::Vector3d q = p - o.foot;
        const double in_front = q.dot(o.inward), side = q.dot(o.along), rise = q.dot(up);
        if (in_front < -kBehindWall || in_front > kLeafDepth || std::abs(side) > o.half_width ||
            rise < kAboveFloor || rise > o.top)
          continue;
        out[x] = static_cast<float>(o.radiance);
        any = true;
        break;
      }
    }
  }
  return any ? radiance : cv::Mat();
}

void show_daylight(const cv::Mat& radiance, cv::Mat& bgr, cv::Mat& depth, cv::Mat& instance) {
  if (radiance.empty()) return;
  const cv::Mat outside = radiance > 0;
  if (!bgr.empty()) bgr.setTo(cv::Scalar::all(255), outside);
  if (!depth.empty()) depth.setTo(0, outside);
  if (!instance.empty()) instance.setTo(0, outside);
}

}  // namespace depot::sim
