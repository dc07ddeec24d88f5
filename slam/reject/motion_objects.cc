#include "slam/reject/motion_objects.h"

#include <algorithm>
#include <numeric>

namespace depot::slam {
namespace {

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

float depth_tolerance(float depth, const MotionObjectParams& params) {
  return params.link_depth_m + params.link_depth_per_m * depth;
}

}  // namespace

std::vector<MotionObject> find_motion_objects(const std::vector<TestedKeypoint>& tested,
                                              cv::Size image, const MotionObjectParams& params) {
  std::vector<int> seeds;
  for (size_t i = 0; i < tested.size(); ++i)
    if (tested[i].moving) seeds.push_back(static_cast<int>(i));
  if (static_cast<float>(seeds.size()) > params.max_frame_moving_share * tested.size()) return {};
  const float link_px = params.link_px * static_cast<float>(image.width) / 640.0f;

  // Single linkage over the failing keypoints.
  std::vector<int> parent(seeds.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (size_t a = 0; a < seeds.size(); ++a) {
    const TestedKeypoint& p = tested[seeds[a]];
    for (size_t b = a + 1; b < seeds.size(); ++b) {
      const TestedKeypoint& q = tested[seeds[b]];
      const cv::Point2f d = p.pixel - q.pixel;
      if (d.dot(d) > link_px * link_px) continue;
      if (std::abs(p.depth - q.depth) > depth_tolerance(std::min(p.depth, q.depth), params))
        continue;
      parent[find_root(parent, static_cast<int>(a))] = find_root(parent, static_cast<int>(b));
    }
  }
  std::vector<std::vector<int>> groups(seeds.size());
  for (size_t a = 0; a < seeds.size(); ++a)
    groups[find_root(parent, static_cast<int>(a))].push_back(seeds[a]);

  const cv::Rect2f frame(0, 0, static_cast<float>(image.width), static_cast<float>(image.height));
  std::vector<MotionObject> objects;
  for (const std::vector<int>& group : groups) {
    if (static_cast<int>(group.size()) < params.min_seeds) continue;
    float x0 = 1e9f, y0 = 1e9f, x1 = -1e9f, y1 = -1e9f, z0 = 1e9f, z1 = 0;
    std::vector<float> depths;
    for (int i : group) {
      const TestedKeypoint& k = tested[i];
      x0 = std::min(x0, k.pixel.x), x1 = std::max(x1, k.pixel.x);
      y0 = std::min(y0, k.pixel.y), y1 = std::max(y1, k.pixel.y);
      z0 = std::min(z0, k.depth), z1 = std::max(z1, k.depth);
      depths.push_back(k.depth);
    }
    // The evidence: every tested keypoint among the group's, at its depth.
    const float z_lo = z0 - depth_tolerance(z0, params), z_hi = z1 + depth_tolerance(z1, params);
    int inside = 0, moving = 0;
    for (const TestedKeypoint& k : tested) {
      if (k.depth < z_lo || k.depth > z_hi) continue;
      if (k.pixel.x < x0 || k.pixel.x > x1 || k.pixel.y < y0 || k.pixel.y > y1) continue;
      inside++;
      moving += k.moving;
    }
    if (moving < params.min_moving_share * static_cast<float>(inside)) continue;
    const float gx = std::max(params.grow * (x1 - x0), link_px);
    const float gy = std::max(params.grow * (y1 - y0), link_px);
    MotionObject object;
    object.box = cv::Rect2f(x0 - gx, y0 - gy, x1 - x0 + 2 * gx, y1 - y0 + 2 * gy) & frame;
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
    object.depth = depths[depths.size() / 2];
    object.seeds = static_cast<int>(group.size());
    object.tested = inside;
    objects.push_back(object);
  }
  std::sort(objects.begin(), objects.end(),
            [](const MotionObject& a, const MotionObject& b) { return a.seeds > b.seeds; });
  return objects;
}

}  // namespace depot::slam
