#pragma once
// Descriptor matching between frames, keyframes and map points, the ways
// ORB-SLAM2 does: by projection with a search radius, by descriptor with a
// ratio test, along epipolar lines for triangulation, and fusing duplicates.
// All callers hold the map mutex.
#include <utility>
#include <vector>

#include "slam/data/frame.h"
#include "slam/data/keyframe.h"
#include "slam/data/map_point.h"

namespace depot::slam {

constexpr int kMatchThHigh = 100;  // Hamming distance accepted by projection
constexpr int kMatchThLow = 50;    // stricter: by descriptor, triangulation, fusion

// Where a map point is predicted to appear in a frame (local-map search).
struct ProjectedPoint {
  MapPoint* point = nullptr;
  double u = 0, v = 0, u_right = -1;
  int level = 0;
  double view_cos = 1;
};

// Predicts a point's image position, level and viewing angle in a frame with
// pose T_cw; false when behind, outside the image, out of its distance range
// or seen at more than 60 deg from its mean viewing direction.
bool project_into(const MapPoint& mp, const Pose& T_cw, const Features& f, ProjectedPoint& out);

// Motion-model tracking: points of the last frame projected into the current
// one (its T_cw predicted). Returns matches set in current.map_points.
int match_by_projection(Frame& current, const Frame& last, float radius_factor);

// Local-map tracking: candidates near each projection, best within TH_HIGH
// and a ratio to the second best at the same level.
int match_local_points(Frame& frame, const std::vector<ProjectedPoint>& points,
                       float radius_factor);

// A keyframe's map points against all keypoints of a frame by descriptor
// (ratio test and orientation consistency); `matches` is per frame keypoint.
int match_by_descriptor(const KeyFrame& kf, const Frame& frame, std::vector<MapPoint*>& matches,
                        float ratio);

// As match_by_descriptor, but a keyframe keypoint is compared only with
// the frame's keypoints under the same vocabulary node (the direct indices
// kf.bow_features and frame.bow_features, which must be set): ORB-SLAM2's
// SearchByBoW, for relocalisation and loop closing.
int match_by_bow(const KeyFrame& kf, const Frame& frame, std::vector<MapPoint*>& matches,
                 float ratio);

// Unmatched keypoint pairs of two keyframes that agree with the epipolar
// geometry of their poses. With both direct indices set (bow_features),
// only keypoints under the same vocabulary node are compared, as ORB-SLAM2
// does; otherwise every pair.
int match_for_triangulation(const KeyFrame& kf1, const KeyFrame& kf2,
                            std::vector<std::pair<size_t, size_t>>& pairs);

// Projects points into kf and merges each with the map point already at the
// matching keypoint (keeping the better observed one) or adds the
// observation. Returns the number fused or added.
int fuse(KeyFrame* kf, const std::vector<MapPoint*>& points, float radius_factor);

}  // namespace depot::slam
