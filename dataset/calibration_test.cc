#include "dataset/calibration.h"

#include <gtest/gtest.h>

#include "common/testing/error_of.h"
#include "dataset/test_folder.h"

namespace depot::dataset {
namespace {

CameraCalibration distorted_camera() {
  CameraCalibration c;
  c.width = 320;
  c.height = 240;
  c.fx = 269.6;
  c.fy = 270.25;
  c.cx = 159.8;
  c.cy = 123.55;
  c.lens = {-0.25, 0.08, 0.001, -0.0005, 0.0123456789};
  c.depth_factor = 5000;
  c.depth_min = 0.4;
  c.depth_max = 4.5;
  c.depth_baseline = 0.075;
  return c;
}

TEST(Calibration, WrittenTextReadsBackAsTheSameCamera) {
  const std::string dir = testing::new_test_folder();
  const CameraCalibration want = distorted_camera();
  testing::write_text(dir, "calibration.yaml", calibration_text(want));
  const CameraCalibration got = read_calibration(dir + "/calibration.yaml");
  EXPECT_EQ(got.width, 320);
  EXPECT_EQ(got.height, 240);
  EXPECT_DOUBLE_EQ(got.fx, 269.6);
  EXPECT_DOUBLE_EQ(got.fy, 270.25);
  EXPECT_DOUBLE_EQ(got.cx, 159.8);
  EXPECT_DOUBLE_EQ(got.cy, 123.55);
  EXPECT_DOUBLE_EQ(got.lens.k1, -0.25);
  EXPECT_DOUBLE_EQ(got.lens.k3, 0.0123456789);
  EXPECT_DOUBLE_EQ(got.lens.p2, -0.0005);
  EXPECT_DOUBLE_EQ(got.depth_factor, 5000);
  // The SLAM's virtual baseline is not the file's depth.baseline: absent
  // camera.baseline keeps the default bf under the file's fx.
  EXPECT_DOUBLE_EQ(got.bf, CameraCalibration{}.bf);
  EXPECT_DOUBLE_EQ(got.baseline, CameraCalibration{}.bf / 269.6);
}

TEST(Calibration, TextIsTheFormatDatasetsHave) {
  // Byte for byte as datasets were written before this file owned it.
  const std::string text = calibration_text(distorted_camera());
  EXPECT_NE(text.find("camera:\n  model: pinhole\n  width: 320\n  height: 240\n  fx: 269.600000\n"
                      "  fy: 270.250000\n  cx: 159.800000\n  cy: 123.550000\n  k1: -0.25\n"
                      "  k2: 0.08\n  p1: 0.001\n  p2: -0.0005\n  k3: 0.0123456789\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("depth:\n  factor: 5000.0  # PNG value per metre\n  min: 0.400\n"
                      "  max: 4.500\n  model: kinect\n  baseline: 0.0750\n"),
            std::string::npos)
      << text;
}

TEST(Calibration, BadCalibrationsAreOneErrorNamingFileAndLine) {
  const std::string dir = testing::new_test_folder();
  const std::string path = dir + "/calibration.yaml";
  EXPECT_EQ(error_of([&] { read_calibration(path); }),
            path + ": cannot open file (the dataset's camera calibration)");
  testing::write_text(dir, "calibration.yaml", "depth: {factor: 5000}\n");
  EXPECT_EQ(error_of([&] { read_calibration(path); }), path + ": no camera: width/height");
  testing::write_text(dir, "calibration.yaml", "camera:\n  width: 640\n  height: 480\n  fx: -1\n");
  EXPECT_EQ(error_of([&] { read_calibration(path); }),
            path + ":4: 'fx' = -1 is out of range [1, 100000]");
  testing::write_text(dir, "calibration.yaml", "camera: {width: 640, height: 480}\ndepth: 5000\n");
  EXPECT_EQ(error_of([&] { read_calibration(path); }), path + ":2: depth must be a map");
  testing::write_text(dir, "calibration.yaml", "camera: {width: wide, height: 480}\n");
  EXPECT_EQ(error_of([&] { read_calibration(path); }), path + ":1: bad value for 'width'");
}

}  // namespace
}  // namespace depot::dataset
