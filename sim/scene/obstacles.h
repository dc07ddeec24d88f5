#pragma once
// The depot's static geometry as a distance function, for clearance checks of
// camera paths and actor lanes: every geom of the scene objects (racks and
// their goods, crates, sacks, desks, monitors, barrels, posters, doors...)
// built exactly as the renderer builds them for a world seed, plus the hall's
// walls and ceiling. The floor is not an obstacle (cameras may ride low),
// nor are actors and pushables (they move).
//
// Boxes, spheres and upright cylinders are exact; ellipsoids (sacks) and
// capsules count as their bounding boxes, so a distance is never larger than
// the real one.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "common/pose.h"
#include "sim/actors/actor.h"
#include "sim/actors/actor_variation.h"
#include "sim/scenario/scene_layout.h"

namespace depot::sim {

struct Nearest {
  double distance = std::numeric_limits<double>::infinity();  // m; negative inside
  std::string object;  // e.g. "'crates_e' (crate)" or "the east wall"
};

class StaticObstacles {
 public:
  StaticObstacles(const SceneLayout& layout, uint64_t world_seed);

  // The nearest static surface to a point.
  Nearest nearest(const Eigen::Vector3d& p) const;
  // The nearest static surface to a vertical segment at `xy` from height
  // z_lo to z_hi (an actor's body): horizontal distance where heights
  // overlap (exact for upright boxes and cylinders).
  Nearest nearest_column(const Eigen::Vector2d& xy, double z_lo, double z_hi) const;
  // nearest_column's distance, as the actors' lane variation asks for it
  // (valid while this object lives).
  ColumnClearance column_clearance() const {
    return [this](const Eigen::Vector2d& xy, double z_lo, double z_hi) {
      return nearest_column(xy, z_lo, z_hi).distance;
    };
  }

  size_t size() const { return solids_.size(); }

 private:
  struct Solid {
    Shape shape = Shape::kBox;      // kBox, kSphere or kCylinder (others become boxes)
    Pose pose = Pose::Identity();   // world from geom
    Eigen::Vector3d half{0, 0, 0};  // box: half extents; sphere: r; cylinder: r, r, half height
    double z_lo = 0, z_hi = 0;      // world height range
    bool upright = true;            // geom z axis is world z
    size_t label = 0;               // index into labels_
  };
  double solid_distance(const Solid& s, const Eigen::Vector3d& p) const;
  double solid_column_distance(const Solid& s, const Eigen::Vector2d& xy, double z_lo,
                               double z_hi) const;

  std::vector<Solid> solids_;
  std::vector<std::string> labels_;
  double half_length_ = 10, half_width_ = 6, height_ = 4.5;
};

}  // namespace depot::sim
