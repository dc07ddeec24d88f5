#pragma once
// Doorways to daylight (the scenario's `openings`): a depot's roller door
// rising from the floor shows the outside, far brighter than anything the
// hall's lamps light. No geometry is added: the opening is a rectangle on
// a wall, and a pixel shows the outside where its exact depth puts its
// surface on that wall (or within kLeafDepth in front of it: the door leaf,
// a poster, which roll up with the door) inside the open part. There
//  - the colour is the outside's radiance, `radiance` times the render's
//    white under light 1, not scaled by the hall's light or its flicker
//    (ColourCapture::daylight; the colour pipeline saturates it and the
//    auto-exposure meters it);
//  - the depth is 0 (no return: the outside lies beyond the sensor's range
//    and sunlight drowns an infrared pattern);
//  - the labels show no instance, as for any pixel without a surface.
// Whatever stands in front of the opening (a person, a rack) hides it.
// Which pixels are open is decided from a depth image at its own instant:
// the colour image and labels from the render at the frame's timestamp
// (under a rolling shutter every row alike), a depth camera with its own
// clock from its own image. Plain functions of images and poses; no MuJoCo
// here.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "common/pose.h"
#include "sim/scenario/scenario.h"
#include "sim/sensor/lens.h"

namespace depot::sim {

// How far in front of the wall a surface inside the opening still counts
// as the door (its leaf, a poster on it): 10 cm.
constexpr double kLeafDepth = 0.10;

// An opening placed on its wall (hall coordinates, z up).
struct WallOpening {
  Eigen::Vector3d foot{0, 0, 0};    // the centre of its bottom edge, on the wall
  Eigen::Vector3d along{1, 0, 0};   // unit, along the wall
  Eigen::Vector3d inward{0, 1, 0};  // unit, the wall's normal into the hall
  double width = 0.0, height = 0.0;
  double radiance = 1.0;
  LightSpec open;  // share open over time (light_level_at)
};

// The scenario's openings on the walls of a hall `length` x `width` x
// `height` m centred on the origin. Throws depot::Error naming the opening's
// entry when its centre is more than 5 cm from every wall, or it reaches past
// the wall's ends or above the ceiling.
std::vector<WallOpening> place_openings(const std::vector<Scenario::Opening>& openings,
                                        double length, double width, double height);

// Per pixel (CV_32F), the outside's radiance where the frame shows it
// through an opening at `t` (s since the first frame), 0 elsewhere; empty
// when no pixel does. `rays` (CV_32FC2) holds each pixel's ray in the
// camera's normalised coordinates (x/z, y/z), `depth` (CV_32F, m along the
// optical axis, 0 = none) the frame's exact depth, `world_camera`
// T_world_camera (x right, y down, z forward).
cv::Mat daylight_radiance(const cv::Mat& depth, const cv::Mat& rays, const Pose& world_camera,
                          const std::vector<WallOpening>& openings, double t);

// The normalised rays (CV_32FC2) of the output pixels: through `lens` (each
// pixel's canvas pixel, sim/sensor/lens.h) when there is one, else of the
// pinhole `camera`.
cv::Mat pixel_rays(const CameraIntrinsics& camera, const LensMapping* lens);

// Shows the outside where `radiance` > 0: white colour (what the exact camera
// makes of it), no depth, no instance. Any of the images may be empty.
void show_daylight(const cv::Mat& radiance, cv::Mat& bgr, cv::Mat& depth, cv::Mat& instance);

}  // namespace depot::sim
