#pragma once
// A map's points as a coloured point cloud (`depot slam map export`): each
// good map point at its position, painted with the colour under its
// reference keyframe's keypoint, with the number of keyframes observing it.
// Rejected keypoints never become map points (they are removed before
// tracking), so nothing a mover carried is in it.
#include <vector>

#include "slam/data/map.h"
#include "slam/io/ply_file.h"

namespace depot::slam {

// The caller holds map.mutex().
std::vector<PlyPoint> map_point_cloud(const Map& map) DEPOT_REQUIRES(map.mutex());

}  // namespace depot::slam
