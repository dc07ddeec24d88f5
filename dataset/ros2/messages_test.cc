// ROS 2 messages in CDR: the byte layout of a known message (alignment, the
// encapsulation header, strings with their NUL), round trips, and damage.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/testing/error_of.h"
#include "dataset/ros2/cdr.h"
#include "dataset/ros2/messages.h"

namespace depot::ros2 {
namespace {

using ::testing::HasSubstr;

TEST(Cdr, APoseStampedHasTheLayoutRos2Writes) {
  PoseStamped p;
  p.header.stamp = {5, 7};
  p.header.frame_id = "ab";
  p.position = {1.0, 2.0, 3.0};
  const std::string b = encode(p);
  // 4 header, then sec 4 + nanosec 4 + length 4 + "ab\0" 3 = 15, padded to
  // 16 (doubles align to 8 from after the header), then 7 doubles.
  ASSERT_EQ(b.size(), 4u + 16u + 56u);
  EXPECT_EQ(b.substr(0, 4), std::string("\0\1\0\0", 4));
  EXPECT_EQ(static_cast<uint8_t>(b[4]), 5);
  EXPECT_EQ(static_cast<uint8_t>(b[12]), 3);  // string length counts the NUL
  EXPECT_EQ(b.substr(16, 3), std::string("ab\0", 3));
  double x;
  std::memcpy(&x, b.data() + 20, 8);
  EXPECT_EQ(x, 1.0);
  const PoseStamped back = decode_pose_stamped(b, "t");
  EXPECT_EQ(back.header.frame_id, "ab");
  EXPECT_EQ(back.header.stamp.nanosec, 7u);
  EXPECT_EQ(back.position, p.position);
  EXPECT_EQ(back.orientation.w(), 1.0);
}

TEST(Cdr, ImagesCameraInfoAndTfRoundTrip) {
  Image im;
  im.header = {{1, 2}, "cam"};
  im.height = 2;
  im.width = 3;
  im.encoding = "32FC1";
  im.step = 12;
  im.data = std::string(24, '\x7f');
  const Image im2 = decode_image(encode(im), "t");
  EXPECT_EQ(im2.data, im.data);
  EXPECT_EQ(im2.encoding, "32FC1");
  EXPECT_EQ(im2.step, 12u);

  CameraInfo ci;
  ci.width = 640;
  ci.height = 480;
  ci.d = {0.1, -0.2, 0.001, 0.002, 0.03};
  ci.k = {535.4, 0, 320.1, 0, 539.2, 247.6, 0, 0, 1};
  const CameraInfo ci2 = decode_camera_info(encode(ci), "t");
  EXPECT_EQ(ci2.d, ci.d);
  EXPECT_EQ(ci2.k, ci.k);
  EXPECT_EQ(ci2.distortion_model, "plumb_bob");

  TFMessage tf;
  tf.transforms.resize(2);
  tf.transforms[1].child_frame_id = "child";
  tf.transforms[1].translation = {0.5, -1, 2};
  tf.transforms[1].rotation = Eigen::Quaterniond(0, 1, 0, 0);
  const TFMessage tf2 = decode_tf_message(encode(tf), "t");
  ASSERT_EQ(tf2.transforms.size(), 2u);
  EXPECT_EQ(tf2.transforms[1].child_frame_id, "child");
  EXPECT_EQ(tf2.transforms[1].translation, tf.transforms[1].translation);
  EXPECT_EQ(tf2.transforms[1].rotation.x(), 1.0);
  EXPECT_EQ(header_stamp(encode(im), "t").nanosec, 2u);
}

TEST(Cdr, DamagedMessagesAreOneErrorNamingThem) {
  Image im;
  im.encoding = "rgb8";
  im.data = std::string(100, 'x');
  const std::string b = encode(im);
  EXPECT_THAT(error_of([&] { decode_image(b.substr(0, b.size() - 10), "bag.mcap (/c)"); }),
              HasSubstr("bag.mcap (/c): truncated CDR message"));
  std::string big_endian = b;
  big_endian[1] = 0;
  EXPECT_THAT(error_of([&] { decode_image(big_endian, "w"); }), HasSubstr("big-endian CDR"));
  EXPECT_THAT(error_of([&] { decode_image(std::string("\0\7\0\0", 4), "w"); }),
              HasSubstr("unknown encapsulation"));
}

TEST(MessageTypes, DefinitionsCarryEveryTypeTheyUse) {
  const std::string d = detection_array_type().definition;
  for (const char* t : {"MSG: vision_msgs/Detection2D", "MSG: vision_msgs/Point2D",
                        "MSG: geometry_msgs/PoseWithCovariance", "MSG: builtin_interfaces/Time"})
    EXPECT_THAT(d, HasSubstr(t));
  EXPECT_EQ(without_msg("sensor_msgs/msg/Image"), "sensor_msgs/Image");
}

}  // namespace
}  // namespace depot::ros2
