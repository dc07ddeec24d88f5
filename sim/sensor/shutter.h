#pragma once
// Exposure and rolling shutter of the colour camera, integrated from
// sub-frame renders (the reference path: every effect of motion, the
// camera's and each actor's own, comes out of the renderer itself).
//
// Timing convention (written into calibration.yaml and info.json):
// - the frame's timestamp is the middle of the exposure of the middle row;
// - row y starts its exposure (y - (H - 1) / 2) / (H - 1) x readout after the
//   middle row, so the first and last rows are readout / 2 before and after;
// - each row integrates light for `exposure` seconds centred on its time;
// - depth, labels, boxes and ground truth belong to the timestamp (the
//   depth camera is treated as global shutter, instant).
// Plain functions of time offsets relative to the timestamp; no MuJoCo here
// (sim/world/simulated_sequence.cc renders the sub-frames).
#include <vector>

#include <opencv2/core.hpp>

#include "common/pose.h"

namespace depot::sim {

struct ShutterTiming {
  double exposure = 0.0;  // s, each row's integration time
  double readout = 0.0;   // s, from the first row's start to the last row's
  int max_subframes = 15;

  bool active() const { return exposure > 0.0 || readout > 0.0; }
  // Seconds from the first row's exposure start to the last row's end.
  double span() const { return exposure + readout; }
  // Offset of row `y`'s mid-exposure from the timestamp (rows 0..height-1).
  double row_offset(int y, int height) const;
};

// The sub-frame instants (offsets from the timestamp, ascending, an odd
// count with 0 in the middle) covering the span, spaced so that no point of
// the image moves more than about one pixel between two of them:
// `image_motion_px` is the largest displacement over the whole span. At
// least 3 when active, at most max_subframes (rounded down to odd).
std::vector<double> subframe_offsets(const ShutterTiming& timing, double image_motion_px);

// Largest image displacement (pixels) of a point `depth` metres in front of
// the camera between camera poses `a` and `b` (T_world_camera), over the
// image's corners, edge midpoints and centre: how far the camera's own
// motion smears a surface at that depth.
double camera_image_motion(const Pose& a, const Pose& b, double focal, double cx, double cy,
                           int width, int height, double depth);

// Integrates colour sub-frames (CV_8UC3, taken at `offsets`) into one image:
// each row is the time average, over its own exposure window, of the colour
// linearly interpolated between sub-frames (a zero exposure gives the
// colour at the row's instant). Rounded back to 8 bits.
cv::Mat integrate_shutter(const std::vector<cv::Mat>& subframes, const std::vector<double>& offsets,
                          const ShutterTiming& timing);

}  // namespace depot::sim
