#pragma once
// The cheap path of exposure blur and rolling shutter (`sensor: {motion_blur:
// field}`): instead of rendering the world at every sub-frame instant (the
// reference, sim/sensor/shutter.h), the one render at the timestamp is moved
// to each instant along the exact motion of what each pixel shows. Its 3D
// point (from the render's exact depth) is carried by the camera's own motion
// and, on a pushable or an actor, by the body it lies on: the body of its
// instance whose origin is nearest at the timestamp (a skinned limb moves
// with its nearest bone). Each moved point lands on its nearest pixel, as
// the renderer rasterises, through a z-buffer: nearer surfaces cover farther
// ones; a pixel no point
// reaches (background an actor uncovers, content entering at the border)
// takes the colour of the farthest of the nearest reached pixels left, right,
// above and below it, looking up to 96 px each way (farther: black; the
// image motion the sub-frames are spaced for is far smaller). The sub-frames then go
// through integrate_shutter like rendered ones, so the rows' timing is one
// code. What one render cannot know is the error against the reference:
// surfaces hidden at the timestamp, and skins blending several bones.
// Plain functions of images and poses; no MuJoCo here.
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "common/pose.h"
#include "sim/scenario/scenario.h"

namespace depot::sim {

// How points move from the timestamp to one sub-frame instant: each pose maps
// points of the timestamp's camera frame into the instant's camera frame.
struct InstantMotion {
  Pose scene = Pose::Identity();  // the static scene (the camera's own motion)
  std::vector<Pose> bodies;       // per moving body, as indexed by the body map
};

// The motion of the static scene and of each body between the timestamp
// (`camera_at_stamp`, `bodies_at_stamp`) and an instant (`camera`, `bodies`);
// all T_world_x, bodies in one order.
InstantMotion instant_motion(const Pose& camera_at_stamp, const std::vector<Pose>& bodies_at_stamp,
                             const Pose& camera, const std::vector<Pose>& bodies);

// Per pixel (CV_16S), the index of the body whose motion it follows, -1 for
// the static scene: among the bodies of the instance the pixel shows
// (`body_instance[b]`), the one whose origin (`body_origin[b]`, in the
// timestamp's camera frame) is nearest its point. Pixels of instances with
// no body, or without depth, are static.
cv::Mat assign_bodies(const cv::Mat& depth, const cv::Mat& instance, const CameraIntrinsics& camera,
                      const std::vector<uint16_t>& body_instance,
                      const std::vector<Eigen::Vector3d>& body_origin);

// What the field moves, made once a frame from the timestamp's `bgr`
// (CV_8UC3), exact `depth` (CV_32F, metres, 0 = no surface: a point at
// infinity, moved by the camera's rotation only) and `body` map, for a
// square-pixel camera (the render). Points are stored by coordinate (one
// array each) so the static scene's motion, most of every image, runs as
// one vectorised loop; the pixels on bodies are listed apart.
struct FieldSource {
  cv::Mat bgr;
  // Per pixel, its point in homogeneous coordinates: w = 1 for a surface,
  // w = 0 for a ray at infinity (only the rotation moves it).
  std::vector<float> x, y, z, w;
  std::vector<int> on_body;      // pixels that follow a body, ascending
  std::vector<int16_t> body_of;  // their body, as indexed by the body map
  int bodies = 0;                // bodies the pixels follow (largest index + 1)
  float f = 0, cx = 0, cy = 0;
};
FieldSource make_field_source(const cv::Mat& bgr, const cv::Mat& depth, const cv::Mat& body,
                              const CameraIntrinsics& camera);

// The colour image (CV_8UC3, into `out`, reusing its buffer) at an instant:
// each point lands on the pixel nearest it, the nearest point on a pixel
// wins. Thread-safe (scratch is per thread).
void synthesise_subframe(const FieldSource& source, const InstantMotion& motion, cv::Mat& out);

}  // namespace depot::sim
