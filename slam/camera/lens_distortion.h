#pragma once
// Between the images' pixels and the undistorted pinhole of PinholeCamera
// (OpenCV's radial-tangential model, which ORB-SLAM2 and TUM calibrations
// use). Without a distortion every function is the identity.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/camera/pinhole_camera.h"

namespace depot::slam {

// The camera in OpenCV's terms (calib3d's K and distortion coefficients).
cv::Matx33d opencv_camera_matrix(const PinholeCamera& camera);
cv::Vec<double, 5> opencv_distortion(const PinholeCamera& camera);

// Undistorted positions of image pixels.
std::vector<cv::Point2f> undistort_pixels(const PinholeCamera& camera,
                                          const std::vector<cv::Point2f>& pixels);
cv::Point2f undistort_pixel(const PinholeCamera& camera, const cv::Point2f& pixel);
// The image pixel an undistorted position comes from.
cv::Point2f distort_pixel(const PinholeCamera& camera, const cv::Point2f& undistorted);

// Sets min_u..max_v to the box around the image's undistorted border (as
// ORB-SLAM2's ComputeImageBounds). Throws depot::Error naming `where` when
// the distortion does not invert over the image (it folds the image).
void set_undistorted_bounds(PinholeCamera& camera, const std::string& where);

}  // namespace depot::slam
