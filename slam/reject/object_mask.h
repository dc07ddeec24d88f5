#pragma once
// An object's pixels inside its detection box, segmented from depth. The
// object's depth is the nearest strong peak of the box's depth histogram (a
// detected object stands in front of what else its box holds); the box's
// pixels at that depth seed a region grown over neighbouring pixels whose
// depth changes smoothly (a depth edge stops it) and stays within the
// object's depth extent. The floor an object stands on meets it without a
// depth edge, so with the camera's intrinsics the dominant plane of the
// search region's bottom third (RANSAC on its 3D points) is taken out first
// when it is a support surface: large, receding in depth, and reaching the
// region's bottom edge (a plane at one depth may be the object itself, e.g.
// a torso). A nearest object that does not reach the box's top is taken for
// an occluder standing before the object (a desk and a monitor before a
// seated person) when the object at the depth of the box's top is one the
// box holds: its region spills little past the box (a wall or shelf seen
// above a misplaced box fills the search region around it), and it stands
// at most a metre behind the occluder (what lies further back is what the
// box shows above a walking person). Pixels of the
// box at other depths are the background
// seen around the object; pixels without depth are on no object. Boxes from
// a detector are jittered and scaled, so the search region is the box grown
// on each side.
#include <vector>

#include <opencv2/core.hpp>

#include "slam/camera/pinhole_camera.h"

namespace depot::slam {

struct ObjectMaskParams {
  float grow = 0.15f;         // the search region: the box grown by this share of its size per side
  float bin_m = 0.05f;        // depth histogram bin for the object's depth
  float seed_band_m = 0.25f;  // half an object's thickness: peak window, and seeds' distance to it
  float peak_share = 0.5f;    // the nearest peak holding this share of the strongest one
  // Occluders: when the nearest object's region covers less than
  // top_min_share of the box's top (top_rows of its rows, top_columns of its
  // middle columns), the object is the one at the depth of the box's top,
  // if that one's region covers at most max_spill of the search region
  // outside the box and it stands at most max_occluder_gap_m behind the
  // occluder (a seated person sits just behind the desk; the wall behind a
  // walking person is metres away).
  float top_rows = 0.25f;
  float top_columns = 0.6f;
  float top_min_share = 0.1f;  // 0 = no occluder test
  float max_spill = 0.3f;
  float max_occluder_gap_m = 1.0f;
  float extent_m = 0.6f;          // the object reaches this far in depth from its mode
  float edge_step_m = 0.04f;      // a depth edge: neighbours further apart than
  float edge_step_per_m = 0.03f;  //   edge_step_m + edge_step_per_m * depth (m)
  int stride = 1;                 // segment on every stride-th pixel (then upsampled)
  int min_seed_pixels = 12;       // fewer seeds at the mode: no mask (object without depth)
  // Support-plane removal (needs the camera):
  bool remove_plane = true;
  float plane_tolerance_m = 0.02f;      // a pixel on the plane: this close, plus
  float plane_tolerance_per_m = 0.01f;  //   this much per metre of depth
  float plane_min_share = 0.3f;  // the plane holds at least this share of the region's bottom third
  float plane_min_depth_range = 0.3f;  // and its pixels span this much depth (10-90 %)
  int plane_iterations = 50;
};

struct ObjectMask {
  cv::Rect region;  // the image pixels `mask` covers (the grown box, clipped)
  cv::Mat mask;     // CV_8U of region.size(), 255 = on the object
  float depth = 0;  // the object's depth mode (m); 0 = none found
  bool valid() const { return !mask.empty(); }
  // The image pixel lies on the object.
  bool on_object(int x, int y) const;
  // A pixel of the object lies on the keypoint's centre or on its FAST
  // circle (radius 3 px at its pyramid level: 3 * scale_factor^octave),
  // the circle's radius scaled by `reach` (0 = the centre pixel only).
  bool touches(const cv::KeyPoint& keypoint, float scale_factor, float reach = 1.0f) const;
  // The bounding box of the object's pixels (empty when none).
  cv::Rect2f bounds() const;
};

// depth: CV_32F metres, 0 = none. `camera` (optional): the depth image's
// intrinsics, for support-plane removal.
// `known_depth` (m, 0 = find it): the object's depth when it is known, e.g.
// from the previous frame for a box carried over a missed detection.
ObjectMask segment_object(const cv::Mat& depth, const cv::Rect2f& box,
                          const ObjectMaskParams& params = {},
                          const PinholeCamera* camera = nullptr, float known_depth = 0);

// A box's search region: grown by `grow` of its size per side, clipped to
// the image.
cv::Rect search_region(const cv::Rect2f& box, cv::Size image, float grow);

// A person's mask from a segmenter's (CV_8U, image-sized, non-zero =
// person) inside the box's search region: the segmenter's pixels alone, or
// (union = true) those and the depth mask's together.
ObjectMask with_segmentation(const ObjectMask& from_depth, const cv::Mat& segmentation,
                             const cv::Rect2f& box, const ObjectMaskParams& params, bool union_);

}  // namespace depot::slam
