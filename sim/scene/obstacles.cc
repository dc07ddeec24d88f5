#include "sim/scene/obstacles.h"

#include <algorithm>
#include <cmath>

#include "sim/scene/depot_objects.h"

namespace depot::sim {
namespace {

// Signed distance to an axis-aligned box centred at the origin.
double box_distance(const Eigen::Vector3d& q, const Eigen::Vector3d& half) {
  const Eigen::Vector3d d = q.cwiseAbs() - half;
  return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
}

double rect_distance(const Eigen::Vector2d& q, const Eigen::Vector2d& half) {
  const Eigen::Vector2d d = q.cwiseAbs() - half;
  return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
}

void keep_nearer(Nearest& best, double d, const std::string& object) {
  if (d < best.distance) {
    best.distance = d;
    best.object = object;
  }
}

}  // namespace

StaticObstacles::StaticObstacles(const SceneLayout& layout, uint64_t world_seed)
    : half_length_(layout.length / 2), half_width_(layout.width / 2), height_(layout.height) {
  for (const SceneObject& object : layout.objects) {
    for (const InstanceGeometry& g : build_scene_object(object, world_seed)) {
      labels_.push_back("'" + g.name + "' (" + g.class_name + ")");
      for (const GeomDesc& geom : g.geoms) {
        if (!geom.visible) continue;
        Solid s;
        s.label = labels_.size() - 1;
        s.pose = g.pose * geom.local;
        switch (geom.shape) {
          case Shape::kBox:
          case Shape::kEllipsoid:
            s.shape = Shape::kBox;
            s.half = geom.size;
            break;
          case Shape::kSphere:
            s.shape = Shape::kSphere;
            s.half = Eigen::Vector3d::Constant(geom.size.x());
            break;
          case Shape::kCylinder:
            s.shape = Shape::kCylinder;
            s.half = Eigen::Vector3d(geom.size.x(), geom.size.x(), geom.size.y());
            break;
          case Shape::kCapsule:
            s.shape = Shape::kBox;
            s.half = Eigen::Vector3d(geom.size.x(), geom.size.x(), geom.size.x() + geom.size.y());
            break;
        }
        const Eigen::Matrix3d& r = s.pose.linear();
        s.upright = s.shape == Shape::kSphere || std::abs(r(2, 2)) > 1.0 - 1e-9;
        const double reach_z = (r.cwiseAbs() * s.half).z();
        s.z_lo = s.pose.translation().z() - reach_z;
        s.z_hi = s.pose.translation().z() + reach_z;
        solids_.push_back(s);
      }
    }
  }
}

double StaticObstacles::solid_distance(const Solid& s, const Eigen::Vector3d& p) const {
  const Eigen::Vector3d q = s.pose.linear().transpose() * (p - s.pose.translation());
  switch (s.shape) {
    case Shape::kSphere:
      return q.norm() - s.half.x();
    case Shape::kCylinder: {
      const double dr = std::hypot(q.x(), q.y()) - s.half.x();
      const double dz = std::abs(q.z()) - s.half.z();
      return std::hypot(std::max(dr, 0.0), std::max(dz, 0.0)) + std::min(std::max(dr, dz), 0.0);
    }
    default:
      return box_distance(q, s.half);
  }
}

double StaticObstacles::solid_column_distance(const Solid& s, const Eigen::Vector2d& xy,
                                              double z_lo, double z_hi) const {
  // Horizontal distance to the solid's footprint.
  double horizontal;
  const Eigen::Vector2d c = s.pose.translation().head<2>();
  if (!s.upright) {
    // Tilted geoms (none in the shipped scene): the world bounding box.
    const Eigen::Vector2d reach = (s.pose.linear().cwiseAbs() * s.half).head<2>();
    horizontal = rect_distance(xy - c, reach);
  } else if (s.shape == Shape::kBox) {
    const Eigen::Matrix2d r = s.pose.linear().topLeftCorner<2, 2>();
    horizontal = rect_distance(r.transpose() * (xy - c), s.half.head<2>());
  } else {
    horizontal = (xy - c).norm() - s.half.x();
  }
  const double gap = std::max({0.0, s.z_lo - z_hi, z_lo - s.z_hi});
  if (gap <= 0.0) return horizontal;
  return std::hypot(std::max(horizontal, 0.0), gap);
}

Nearest StaticObstacles::nearest(const Eigen::Vector3d& p) const {
  Nearest best;
  keep_nearer(best, half_length_ - p.x(), "the east wall");
  keep_nearer(best, half_length_ + p.x(), "the west wall");
  keep_nearer(best, half_width_ - p.y(), "the north wall");
  keep_nearer(best, half_width_ + p.y(), "the south wall");
  keep_nearer(best, height_ - p.z(), "the ceiling");
  double d = best.distance;
  size_t label = labels_.size();
  for (const Solid& s : solids_) {
    const double ds = solid_distance(s, p);
    if (ds < d) {
      d = ds;
      label = s.label;
    }
  }
  if (label < labels_.size()) keep_nearer(best, d, labels_[label]);
  return best;
}

Nearest StaticObstacles::nearest_column(const Eigen::Vector2d& xy, double z_lo, double z_hi) const {
  Nearest best;
  keep_nearer(best, half_length_ - xy.x(), "the east wall");
  keep_nearer(best, half_length_ + xy.x(), "the west wall");
  keep_nearer(best, half_width_ - xy.y(), "the north wall");
  keep_nearer(best, half_width_ + xy.y(), "the south wall");
  keep_nearer(best, height_ - z_hi, "the ceiling");
  double d = best.distance;
  size_t label = labels_.size();
  for (const Solid& s : solids_) {
    const double ds = solid_column_distance(s, xy, z_lo, z_hi);
    if (ds < d) {
      d = ds;
      label = s.label;
    }
  }
  if (label < labels_.size()) keep_nearer(best, d, labels_[label]);
  return best;
}

}  // namespace depot::sim
