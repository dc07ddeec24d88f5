#include "sim/sensor/daylight.h"

#include <gtest/gtest.h>

#include "common/error.h"

namespace depot::sim {
namespace {

// A 160x120 camera at (-6, 0.8, 1.5) looking at the west wall (x = -10) of a
// 20 x 12 x 4.5 m hall: the wall 4 m ahead fills the view above the floor.
struct WallView {
  CameraIntrinsics camera;
  Pose world_camera = Pose::Identity();
  cv::Mat depth;

  WallView() {
    camera.width = 160;
    camera.height = 120;
    camera.f = 134.8;
    camera.cx = 79.5;
    camera.cy = 59.5;
    Eigen::Matrix3d axes;  // columns: the camera's x (right), y (down), z (ahead)
    axes.col(0) = Eigen::Vector3d(0, 1, 0);
    axes.col(1) = Eigen::Vector3d(0, 0, -1);
    axes.col(2) = Eigen::Vector3d(-1, 0, 0);
    world_camera.linear() = axes;
    world_camera.translation() = Eigen::Vector3d(-6, 0.8, 1.5);
    depth = cv::Mat(camera.height, camera.width, CV_32F);
    for (int v = 0; v < camera.height; ++v)
      for (int u = 0; u < camera.width; ++u) {
        const double down = (v - camera.cy) / camera.f;  // world z falls by `down` per metre ahead
        const double floor = down > 0 ? 1.5 / down : 1e9;
        depth.at<float>(v, u) = static_cast<float>(std::min(4.0, floor));
      }
  }
  // The pixel showing the wall point (y, z), on the wall 4 m ahead.
  cv::Point pixel(double y, double z) const {
    return {static_cast<int>(std::lround(camera.cx + camera.f * (y - 0.8) / 4.0)),
            static_cast<int>(std::lround(camera.cy + camera.f * (1.5 - z) / 4.0))};
  }
};

Scenario::Opening west_door(double open) {
  Scenario::Opening o;
  o.where = "test.yaml:3";
  o.centre = {-10.0, 0.8};
  o.width = 2.4;
  o.height = 3.0;
  o.radiance = 20.0;
  o.open.events = {{0.0, open}};
  return o;
}

TEST(Daylight, TheOpenPartOfTheDoorShowsTheOutsideAndNothingElseDoes) {
  WallView view;
  const auto openings = place_openings({west_door(0.5)}, 20, 12, 4.5);  // open to 1.5 m
  ASSERT_EQ(openings.size(), 1u);
  // A person 0.5 m in front of the wall, inside the doorway.
  const cv::Point person = view.pixel(0.3, 0.8);
  view.depth.at<float>(person) = 3.5f;
  const cv::Mat radiance = daylight_radiance(view.depth, pixel_rays(view.camera, nullptr),
                                             view.world_camera, openings, 1.0);
  ASSERT_FALSE(radiance.empty());
  auto at = [&](cv::Point p) { return radiance.at<float>(p); };
  EXPECT_EQ(at(view.pixel(0.8, 1.0)), 20.0f) << "in the open part";
  EXPECT_EQ(at(view.pixel(-0.3, 0.2)), 20.0f) << "near its bottom corner";
  EXPECT_EQ(at(view.pixel(0.8, 2.0)), 0.0f) << "the door still closed above 1.5 m";
  EXPECT_EQ(at(view.pixel(-0.7, 1.0)), 0.0f) << "the wall beside the door";
  EXPECT_EQ(at(person), 0.0f) << "someone standing in the doorway";
  const int floor_row = view.pixel(0.8, 0.0).y + 3;  // the floor 4 m ahead and nearer
  EXPECT_EQ(radiance.at<float>(floor_row, view.pixel(0.8, 0.0).x), 0.0f) << "the floor";
  // A door leaf 6 cm in front of the wall counts as the door; closed, none.
  view.depth.at<float>(view.pixel(0.8, 1.0)) = 3.94f;
  EXPECT_EQ(daylight_radiance(view.depth, pixel_rays(view.camera, nullptr), view.world_camera,
                              openings, 1.0)
                .at<float>(view.pixel(0.8, 1.0)),
            20.0f);
  EXPECT_TRUE(daylight_radiance(view.depth, pixel_rays(view.camera, nullptr), view.world_camera,
                                place_openings({west_door(0.0)}, 20, 12, 4.5), 1.0)
                  .empty());
}

TEST(Daylight, AnOpeningOffTheWallsOrLargerThanItsWallIsAnErrorNamingIt) {
  Scenario::Opening off = west_door(1.0);
  off.centre = {-9.0, 0.8};
  try {
    place_openings({off}, 20, 12, 4.5);
    FAIL() << "accepted an opening 1 m from the wall";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "test.yaml:3: opening centre (-9.00 m, 0.80 m) is 1.00 m from the nearest wall "
                 "(west); an opening lies on a wall's foot");
  }
  Scenario::Opening wide = west_door(1.0);
  wide.width = 10.4;  // centred 0.8 m off the middle of a 12 m wall: 5 cm from its end
  EXPECT_THROW(place_openings({wide}, 20, 12, 4.5), Error);
  wide.width = 10.2;  // 15 cm
  EXPECT_NO_THROW(place_openings({wide}, 20, 12, 4.5));
  Scenario::Opening tall = west_door(1.0);
  tall.height = 4.6;
  EXPECT_THROW(place_openings({tall}, 20, 12, 4.5), Error);
  // On each wall, the outside lies through it.
  for (const Eigen::Vector2d& c : {Eigen::Vector2d(0, 6), Eigen::Vector2d(0, -6),
                                   Eigen::Vector2d(10, 0), Eigen::Vector2d(-10, 0)}) {
    Scenario::Opening o = west_door(1.0);
    o.centre = c;
    const WallOpening w = place_openings({o}, 20, 12, 4.5).front();
    EXPECT_NEAR(w.inward.head<2>().dot(c), -c.norm(), 1e-12) << c.transpose();
  }
}

}  // namespace
}  // namespace depot::sim
