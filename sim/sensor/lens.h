#pragma once
// Lens distortion and non-square pixels of the colour camera, made by
// resampling a wider square-pixel pinhole render (MuJoCo 2.2 renders only
// those). The model is OpenCV's radial-tangential one (common/lens_model.h)
// on normalised coordinates, then u = fx xd + cx, v = fy yd + cy.
// Output pixel (u, v) shows the canvas at the ray (x, y, 1) whose distorted
// image it is. Colour is sampled bilinearly; depth and instance labels
// nearest, at one and the same canvas pixel, so labels, boxes (made from the
// labels) and depth agree exactly with each other and lie within half a
// canvas pixel of the output pixel's own ray.
#include <string>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "sim/render/rendered_frame.h"
#include "sim/scenario/scenario.h"

namespace depot::sim {

// det(d distorted / d xy) at xy: <= 0 where the mapping folds.
double distortion_jacobian_det(const LensDistortion& lens, const Eigen::Vector2d& xy);
// The ray whose distorted image is `distorted` (Newton's method from the
// distorted point); false when it does not converge.
bool undistort_normalised(const LensDistortion& lens, const Eigen::Vector2d& distorted,
                          Eigen::Vector2d& xy);

// Whether images of `camera` with `lens` need the resampling: a distortion
// or fx != fy.
bool lens_resamples(const CameraIntrinsics& camera, const LensDistortion& lens);

struct LensMapping {
  CameraIntrinsics canvas;  // the square-pixel render covering every output ray
  cv::Mat map_x, map_y;     // CV_32F, output pixel -> canvas pixel
};

// The canvas and the per-pixel mapping of `camera` with `lens`. Throws
// depot::Error naming `where` when the lens folds the image (two rays on one
// pixel: the mapping turns back inside the frame) or needs a canvas larger
// than kMaxImageSide.
LensMapping make_lens_mapping(const CameraIntrinsics& camera, const LensDistortion& lens,
                              const std::string& where);

// The output images from a canvas render (any of its images may be empty).
void apply_lens(const LensMapping& mapping, const RenderedFrame& canvas, RenderedFrame& out);
void apply_lens_colour(const LensMapping& mapping, const cv::Mat& canvas_bgr, cv::Mat& out);

}  // namespace depot::sim
