#pragma once
// calibration.yaml: the camera of a dataset's images (pinhole with OpenCV's
// radial-tangential lens, common/lens_model.h) and how its depth PNGs encode
// metres. Its `camera:` and `depth:` sections are also those of SLAM settings
// files (slam/io/settings.h), which is why a dataset's calibration serves as
// its settings; this file owns both sections. The simulator appends blocks
// of its own truth after them (shutter, depth artefacts, colour formation:
// sim/dataset/dataset_writer.cc), which readers here skip.
//
//   camera: {model: pinhole, width, height, fx, fy, cx, cy, k1, k2, p1, p2, k3,
//            baseline (m, ORB-SLAM2's Camera.bf / fx; read, not written)}
//   depth:  {factor (PNG value per metre), min, max (m, what the sensor
//            returns), model (kinect or ideal), baseline (m, the simulated
//            projector's; written for people, not read: the SLAM's virtual
//            baseline is camera.baseline), close_baselines (read: ORB-SLAM2's
//            ThDepth, in baselines)}
#include <string>

#include <yaml-cpp/yaml.h>

#include "common/lens_model.h"

namespace depot::dataset {

struct CameraCalibration {
  int width = 640, height = 480;
  double fx = 535.4, fy = 539.2, cx = 320.1, cy = 247.6;
  LensCoefficients lens;
  // ORB-SLAM2's virtual stereo: bf = baseline (m) x fx. As read, both (an
  // absent baseline keeps the defaults' bf: baseline = bf / fx).
  double bf = 40.0;
  double baseline = 40.0 / 535.4;
  double depth_factor = 5000.0;
  double close_baselines = 40.0;
  // Written by the simulator for people; not read.
  double depth_min = 0.0, depth_max = 0.0;
  std::string depth_model = "kinect";
  double depth_baseline = 0.075;
};

// The `camera:` and `depth:` sections of `root` (the file at `path`); keys
// that are absent keep `defaults` (a baseline absent keeps its bf). Ranges
// checked; each problem one error "<path>:<line>: <what>".
CameraCalibration read_camera_sections(const YAML::Node& root, const std::string& path,
                                       const CameraCalibration& defaults = {});

// A camera stated by its intrinsics alone (a ROS CameraInfo): everything
// else as in `defaults`, the baseline kept as read_camera_sections keeps an
// absent one. Checks the ranges calibration.yaml has; errors name `where`.
CameraCalibration calibration_of_intrinsics(const CameraCalibration& defaults, int width,
                                            int height, double fx, double fy, double cx, double cy,
                                            const LensCoefficients& lens, const std::string& where);

// A dataset's calibration.yaml, which must state the image size.
CameraCalibration read_calibration(const std::string& path);

// The two sections as calibration.yaml starts, with the comments that say
// what they mean.
std::string calibration_text(const CameraCalibration& c);

}  // namespace depot::dataset
