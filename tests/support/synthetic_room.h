#pragma once
// A synthetic RGB-D scene for the SLAM core's unit tests, so they need no
// outside data: the inside of a box-shaped room with a few boxes standing
// in it, whose faces carry a seeded texture at two scales (brick-like rows of grey
// panels with random offsets, some holding finer blocks: corners at several
// pyramid levels, flat areas between them, no period), rendered exactly by
// ray casting from any pose. Colour is 2x2 supersampled; depth is the true
// z of each pixel centre's ray. Poses are exact, translation gives true
// parallax and every pixel has depth: tracking, mapping and the system can
// be tested against known truth.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "common/pose.h"
#include "slam/camera/pinhole_camera.h"
#include "tests/support/real_frame.h"

namespace depot::test {

// An axis-aligned box standing in the room (a crate, a pillar).
struct RoomBox {
  Eigen::Vector3d centre, half_size;  // m
};

struct SyntheticRoom {
  Eigen::Vector3d half_size{2.4, 1.3, 2.2};  // m, about the world origin (its centre); y is down
  // Boxes at 0.8-1.6 m from the centre: depth that varies across the view,
  // so a turn is not confused with a sideways step.
  std::vector<RoomBox> boxes = {{{-0.7, 0.6, 1.1}, {0.25, 0.7, 0.25}},
                                {{0.8, 1.0, 1.4}, {0.35, 0.3, 0.3}},
                                {{0.25, -0.2, 0.9}, {0.15, 0.15, 0.15}},
                                {{-1.3, 0.9, -0.3}, {0.3, 0.4, 0.3}},
                                {{1.2, 0.8, -0.9}, {0.3, 0.5, 0.3}}};
  uint64_t seed = 1;  // the texture
};

// The view of `room` from a camera at T_cw (world to camera; the camera
// must be inside the room), CV_8UC3 colour and CV_32F depth in metres.
RealFrame render_room(const SyntheticRoom& room, const slam::PinholeCamera& camera,
                      const Pose& T_cw);

// The default room seen from its centre along +z with the default
// (TUM fr3) camera: the tests' stand-in for one real frame.
RealFrame room_frame();

// The default room from its centre turned by R_wc = `rotation` (its T_cw
// is turned_pose(rotation)): as turned_view of room_frame(), but rendered,
// so exact and without the border a resampled turn leaves empty.
RealFrame room_view(const Eigen::Matrix3d& rotation);

}  // namespace depot::test
