#include "sim/scene/geometry.h"

#include "sim/actors/limb.h"

namespace depot::sim {

GeomDesc box(const Eigen::Vector3d& half, const Eigen::Vector3d& at, const std::string& material,
             double yaw) {
  GeomDesc g;
  g.shape = Shape::kBox;
  g.size = half;
  g.local = make_pose(rot_z(yaw), at);
  g.material = material;
  return g;
}

GeomDesc cylinder(double radius, double half_height, const Eigen::Vector3d& at,
                  const std::string& material) {
  GeomDesc g;
  g.shape = Shape::kCylinder;
  g.size = {radius, half_height, 0};
  g.local = make_pose(Eigen::Matrix3d::Identity(), at);
  g.material = material;
  return g;
}

Eigen::AlignedBox3d local_bounds(const std::vector<GeomDesc>& geoms) {
  Eigen::AlignedBox3d out;
  for (const auto& g : geoms) {
    if (!g.visible) continue;
    Eigen::Vector3d half = g.size;
    switch (g.shape) {
      case Shape::kBox:
        half = g.size;
        break;
      case Shape::kSphere:
        half = Eigen::Vector3d::Constant(g.size.x());
        break;
      case Shape::kEllipsoid:
        half = g.size;
        break;
      case Shape::kCapsule:
        half = Eigen::Vector3d(g.size.x(), g.size.x(), g.size.x() + g.size.y());
        break;
      case Shape::kCylinder:
        half = Eigen::Vector3d(g.size.x(), g.size.x(), g.size.y());
        break;
    }
    // Bounds of the rotated box: |R| * half.
    Eigen::Vector3d ext = g.local.linear().cwiseAbs() * half;
    out.extend(g.local.translation() - ext);
    out.extend(g.local.translation() + ext);
  }
  return out;
}

}  // namespace depot::sim
