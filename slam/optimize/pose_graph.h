#pragma once
// Pose-graph optimisation (ORB-SLAM2's essential graph after a loop, with
// scale fixed as RGB-D allows): keyframe poses T_cw linked by measured
// relative poses, solved with Ceres. Each edge (a, b) measures
// T_ab = T_aw * T_bw^-1; its residual is the translation error and twice the
// vector part of the rotation error quaternion of T_ab^-1 * (estimate),
// weighted equally (as ORB-SLAM2's identity information).
#include <vector>

#include "common/pose.h"

namespace depot::slam {

struct PoseGraphEdge {
  size_t a = 0, b = 0;
  Pose T_ab = Pose::Identity();
};

// Optimises `T_cw` in place; poses with fixed[i] stay. Returns the final cost
// (0 without edges). No locking: plain data in, plain data out.
double optimize_pose_graph(std::vector<Pose>& T_cw, const std::vector<bool>& fixed,
                           const std::vector<PoseGraphEdge>& edges, int iterations = 20);

}  // namespace depot::slam
