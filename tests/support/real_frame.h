#pragma once
// The real TUM fr3 frame in ${DEPOT_SHARED_DATA}/tum/fr3_walking_xyz_frame
// and exact views of it from the same camera turned about its optical
// centre. A pure rotation has no parallax and no disocclusion, so the turned
// view of colour and depth is exact (up to resampling; what the turn brings
// into view is black with no depth), and its pose is known: unit tests of
// tracking get real texture and real depth with ground truth.
#include <string>

#include <opencv2/core.hpp>

#include "common/pose.h"
#include "slam/camera/pinhole_camera.h"

namespace depot::test {

struct RealFrame {
  cv::Mat bgr;    // CV_8UC3
  cv::Mat depth;  // CV_32F metres, 0 = none
};

// The folder of the frame; tests skip when it is missing.
std::string real_frame_folder();
// Loads it (the TUM depth PNG scaled by 1/5000); throws depot::Error when missing.
RealFrame load_real_frame();

// The rotation of a camera turned by yaw (about its y axis, positive turns
// right) and then pitch (about its x axis), in degrees.
Eigen::Matrix3d turn(double yaw_deg, double pitch_deg = 0.0);

// The view of `frame` (taken at T_cw = identity with `camera`) from the same
// centre turned by R_wc = `rotation`: its T_cw is turned_pose(rotation).
RealFrame turned_view(const RealFrame& frame, const slam::PinholeCamera& camera,
                      const Eigen::Matrix3d& rotation);
Pose turned_pose(const Eigen::Matrix3d& rotation);

// Angle (degrees) of the rotation between two poses' orientations.
double rotation_error_deg(const Pose& a, const Pose& b);

}  // namespace depot::test
