#pragma once
// A point cloud of the static world (`depot slam run --dense-map`, `depot
// slam map export`, or any system's PLY) scored against a simulated
// dataset's truth (`depot eval cloud`):
//  - on moving objects: a point lies on a mover's true surface when, in
//    some frame of the dataset, it projects onto a pixel labelled as an
//    object moving in that frame whose depth agrees with the point's
//    (within depth_tolerance_m + depth_tolerance_per_m * depth), and (with a
//    static render) it is not within static_tolerance_m of the true static
//    surface: a table's edge a person brushes past is the table's;
//  - accuracy: the distance of each point to the nearest point of the true
//    static surface, which is the static render's depth (the same scenario and
//    seed rendered with `--load 0 --ideal`: no living actors, exact depth)
//    lifted with the true camera poses.
// The cloud is in the SLAM run's world; the run's trajectory aligned to the
// dataset's ground truth pose by pose (eval::align_poses: orientations and
// positions) brings it into the truth's.
#include <map>
#include <string>

#include "eval/statistics.h"

namespace depot::perception {

struct CloudScoreOptions {
  std::string cloud;           // PLY (or any point format assimp reads)
  std::string dataset;         // simulated dataset the cloud was made from
  std::string trajectory;      // the run's TUM trajectory (the cloud's world)
  std::string static_dataset;  // the static render ("" = no accuracy)
  size_t every = 1;            // check every n-th frame of the dataset for movers
  size_t static_every = 5;     // lift every n-th frame of the static render
  double depth_tolerance_m = 0.04;
  double depth_tolerance_per_m = 0.01;
  double static_tolerance_m = 0.03;
  double near_m = 0.05;  // accuracy: the share of points closer than this
  bool quiet = false;
};

struct CloudScore {
  size_t points = 0;
  size_t on_moving = 0;
  size_t frames_checked = 0;
  std::map<std::string, size_t> on_moving_by_class;  // objects.json class of the mover
  double alignment_rmse = 0;  // ATE of the trajectory that aligned the cloud (m)
  bool has_accuracy = false;
  eval::ErrorStatistics distance;  // to the true static surface (m)
  double p90_m = 0;
  double near_share = 0;  // points within near_m of it
  size_t surface_points = 0;
  double on_moving_share() const { return points ? static_cast<double>(on_moving) / points : 0; }
};

// Throws depot::Error naming the file for an unreadable cloud, a dataset
// without labels, a trajectory that does not match the dataset, or a static
// render whose camera path is not the dataset's.
CloudScore score_static_cloud(const CloudScoreOptions& options);

}  // namespace depot::perception
