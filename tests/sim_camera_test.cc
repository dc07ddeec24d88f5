// Exposure blur and rolling shutter against geometry: the camera turns about
// its own vertical axis at a known rate omega, so every point near the image
// centre moves sideways at omega x f pixels per second. An exposure t smears
// it over omega x t x f pixels; a readout time r shifts the last row
// omega x r x f pixels against the first. Both are measured on real renders
// of the depot (sub-frames integrated by sim/sensor/shutter.h) against the
// instant render of the same instant.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>
#include <sstream>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "common/pose.h"
#include "common/tum_io.h"
#include "common/yaml_overrides.h"
#include "sim/scenario/scenario_loader.h"
#include "sim/world/simulated_sequence.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace depot::test {
namespace {

namespace fs = std::filesystem;

constexpr double kStart = 1700000000.0;
constexpr int kWidth = 320;

// A scenario of the empty depot's stage whose camera turns about its own y
// axis (down in OpenCV axes) at `omega` rad/s, from a TUM file sampled at
// 1 kHz (its interpolation is then exact to well below a pixel).
std::string turning_scenario(double omega, const std::string& sensor, double start = kStart) {
  const std::string base = temp_path("shutter");
  fs::create_directories(base);
  const std::string trajectory = base + "/turn.txt";
  std::ofstream t(trajectory);
  t << std::fixed << std::setprecision(9);
  for (int i = -200; i <= 400; ++i) {
    const double time = kStart + i * 1e-3;
    const double angle = omega * i * 1e-3;
    // Rotation about y by `angle`: quaternion (0, sin(a/2), 0, cos(a/2)).
    t << time << " 0 0 0 0 " << std::sin(angle / 2) << " 0 " << std::cos(angle / 2) << "\n";
  }
  const std::string yaml = base + "/turn.yaml";
  std::ofstream(yaml) << "name: shutter_turn\n"
                      << "scene: " << DEPOT_SOURCE_DIR << "/scenes/depot.yaml\n"
                      << "classes: " << DEPOT_SOURCE_DIR << "/scenes/classes.yaml\n"
                      << "frames: 3\n"
                      << "timestamps: {rate: 30, start: " << std::setprecision(3) << std::fixed
                      << start << "}\n"
                      << "motion: {type: file, file: " << trajectory
                      << ", position: [0.0, 0.9, 1.35], look_at: [0.0, 4.5, 0.9]}\n"
                      << "sensor: " << sensor << "\n";
  return yaml;
}

// Frame 1, exact (no sensor noise: that is the dataset writer's).
sim::RenderedFrame middle_frame(const std::string& yaml) {
  sim::Scenario s = sim::load_scenario(yaml);
  sim::scale_camera(s.camera, kWidth);
  sim::SimulatedSequence sequence(s, sim::GlBackend::kOsMesa);
  sim::RenderedFrame frame;
  sim::FrameTruth truth;
  for (int i = 0; i < 2; ++i) EXPECT_TRUE(sequence.next(frame, truth));
  return frame;
}

// The colour image of frame 1 (grey, float) and the camera's focal length.
cv::Mat render_middle_frame(const std::string& yaml, double* focal = nullptr) {
  sim::Scenario s = sim::load_scenario(yaml);
  sim::scale_camera(s.camera, kWidth);
  if (focal) *focal = s.camera.f;
  sim::SimulatedSequence sequence(s, sim::GlBackend::kOsMesa);
  sim::RenderedFrame frame;
  sim::FrameTruth truth;
  for (int i = 0; i < 2; ++i) EXPECT_TRUE(sequence.next(frame, truth));
  cv::Mat grey, out;
  cv::cvtColor(frame.bgr, grey, cv::COLOR_BGR2GRAY);
  grey.convertTo(out, CV_32F);
  return out;
}

// Row `y` of `image` shifted right by `shift` pixels (linear interpolation).
float shifted(const cv::Mat& image, int y, double x) {
  const int x0 = static_cast<int>(std::floor(x));
  const double a = x - x0;
  const float* row = image.ptr<float>(y);
  return static_cast<float>((1 - a) * row[x0] + a * row[x0 + 1]);
}

// The box length (pixels) whose horizontal smear of `sharp` best matches
// `blurred` over the central window (where omega x f varies by < 3 %).
double fitted_blur_length(const cv::Mat& sharp, const cv::Mat& blurred) {
  const int cx = sharp.cols / 2, cy = sharp.rows / 2;
  double best_length = 0, best_error = 1e300;
  for (double length = 0.0; length <= 30.0; length += 0.1) {
    // The box sampled at 0.1 px steps: close enough to the exact kernel.
    const int taps = std::max(1, static_cast<int>(std::lround(length / 0.1)) + 1);
    double error = 0;
    for (int y = cy - 50; y <= cy + 50; y += 2) {
      for (int x = cx - 40; x <= cx + 40; ++x) {
        double sum = 0;
        for (int k = 0; k < taps; ++k) {
          const double dx = taps == 1 ? 0.0 : -0.5 * length + length * k / (taps - 1);
          sum += shifted(sharp, y, x + dx);
        }
        const double d = sum / taps - blurred.at<float>(y, x);
        error += d * d;
      }
    }
    if (error < best_error) best_error = error, best_length = length;
  }
  return best_length;
}

// Sideways shift (pixels) of each band of rows of `skewed` against `sharp`,
// against the band's middle row.
std::vector<std::pair<double, double>> band_shifts(const cv::Mat& sharp, const cv::Mat& skewed) {
  const int cx = sharp.cols / 2;
  std::vector<std::pair<double, double>> out;
  for (int top = 20; top + 12 <= sharp.rows - 20; top += 12) {
    double best_shift = 0, best_error = 1e300;
    for (double shift = -20.0; shift <= 20.0; shift += 0.05) {
      double error = 0;
      for (int y = top; y < top + 12; ++y)
        for (int x = cx - 60; x <= cx + 60; ++x) {
          const double d = shifted(sharp, y, x + shift) - skewed.at<float>(y, x);
          error += d * d;
        }
      if (error < best_error) best_error = error, best_shift = shift;
    }
    out.emplace_back(top + 5.5, best_shift);
  }
  return out;
}

// The sensor block of a turning scenario with `times` and `method`.
std::string shutter_sensor(const std::string& times, const std::string& method) {
  return "{model: kinect, " + times + ", motion_blur: " + method + "}";
}

void expect_smear_of_omega_exposure_focal(const std::string& method) {
  const double omega = 2.0, exposure = 0.02;
  double focal = 0;
  const cv::Mat sharp = render_middle_frame(turning_scenario(omega, "{model: kinect}"), &focal);
  const cv::Mat blurred = render_middle_frame(
      turning_scenario(omega, shutter_sensor("exposure: " + std::to_string(exposure), method)));
  const double expected = omega * exposure * focal;
  const double measured = fitted_blur_length(sharp, blurred);
  std::printf("%s: blur length %.2f px, omega x t x f = %.2f px\n", method.c_str(), measured,
              expected);
  EXPECT_NEAR(measured, expected, 0.1 * expected)
      << method << ": blur length " << measured << " px, omega x t x f = " << expected << " px";
  // Sanity of the measure itself: the instant render has no smear.
  EXPECT_LT(fitted_blur_length(sharp, sharp), 0.15);
}

void expect_skew_of_omega_readout_focal(const std::string& method) {
  const double omega = 2.0, readout = 0.03;
  double focal = 0;
  const cv::Mat sharp = render_middle_frame(turning_scenario(omega, "{model: kinect}"), &focal);
  const cv::Mat skewed = render_middle_frame(
      turning_scenario(omega, shutter_sensor("readout: " + std::to_string(readout), method)));
  const auto bands = band_shifts(sharp, skewed);
  ASSERT_GE(bands.size(), 10u);
  // Least-squares slope of shift against row.
  double sy = 0, ss = 0, syy = 0, sys = 0;
  for (const auto& [y, s] : bands) sy += y, ss += s, syy += y * y, sys += y * s;
  const double n = static_cast<double>(bands.size());
  const double slope = (n * sys - sy * ss) / (n * syy - sy * sy);
  // Signed: the camera turns right (its z axis toward +x about its y axis,
  // which points down), so later rows, lower in the image, see the scene
  // further left: the content of sharp column x + s at column x, s growing.
  const double measured = slope * (skewed.rows - 1);
  const double expected = omega * readout * focal;
  std::printf("%s: skew %+.2f px, omega x r x f = %.2f px\n", method.c_str(), measured, expected);
  EXPECT_NEAR(measured, expected, 0.1 * expected) << method << ": skew over the image " << measured
                                                  << " px, omega x r x f = " << expected << " px";
  // The middle row is the timestamp's: no shift there.
  double middle = 0;
  for (const auto& [y, s] : bands)
    if (std::abs(y - (skewed.rows - 1) / 2.0) < 7) middle = s;
  EXPECT_LT(std::abs(middle), 0.1 * expected);
}

TEST(SimShutter, ExposureSmearsByOmegaTimesExposureTimesFocal) {
  expect_smear_of_omega_exposure_focal("subframes");
}

TEST(SimShutter, ReadoutSkewsByOmegaTimesReadoutTimesFocal) {
  expect_skew_of_omega_readout_focal("subframes");
}

// The cheap path (sim/sensor/motion_field.h) against the same geometry.
TEST(SimShutter, MotionFieldSmearsByOmegaTimesExposureTimesFocal) {
  expect_smear_of_omega_exposure_focal("field");
}

TEST(SimShutter, MotionFieldSkewsByOmegaTimesReadoutTimesFocal) {
  expect_skew_of_omega_readout_focal("field");
}

// Colour frames `first`..`first + count - 1` of a shipped scenario at 320 px
// with the sensor keys `set` (no sensor noise: that is the writer's).
std::vector<cv::Mat> colour_frames(const std::string& scenario, int first, int count,
                                   const std::vector<YamlOverride>& set) {
  std::vector<YamlOverride> overrides = set;
  overrides.push_back({"frames", std::to_string(first + count)});
  sim::Scenario s = sim::load_scenario(scenario_path(scenario), overrides);
  sim::scale_camera(s.camera, kWidth);
  sim::SimulatedSequence sequence(s, sim::GlBackend::kOsMesa);
  std::vector<cv::Mat> out;
  sim::RenderedFrame frame;
  sim::FrameTruth truth;
  while (sequence.next(frame, truth))
    if (truth.index >= first) out.push_back(frame.bgr.clone());
  return out;
}

double mean_grey_difference(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat difference;
  cv::absdiff(a, b, difference);
  return cv::mean(difference.reshape(1))[0];
}

// The motion field against the sub-frame reference it stands in for, on a
// depot with walking people and a camera turning fast (walking_rpy) under a
// Kinect-like shutter (20 ms exposure, 28 ms readout): its images are far
// closer to the reference than the instant camera's are.
TEST(SimShutter, MotionFieldStaysCloseToTheSubFrameReference) {
  const std::vector<YamlOverride> times = {{"sensor.exposure", "0.02"},
                                           {"sensor.readout", "0.028"}};
  auto with = [&](const std::string& method) {
    auto set = times;
    set.push_back({"sensor.motion_blur", method});
    return set;
  };
  const int first = 40, count = 6;
  const auto instant = colour_frames("depot_walking_rpy", first, count, {});
  const auto reference = colour_frames("depot_walking_rpy", first, count, with("subframes"));
  const auto field = colour_frames("depot_walking_rpy", first, count, with("field"));
  ASSERT_EQ(reference.size(), static_cast<size_t>(count));
  double field_error = 0, instant_error = 0;
  for (int i = 0; i < count; ++i) {
    const double f = mean_grey_difference(field[i], reference[i]);
    const double n = mean_grey_difference(instant[i], reference[i]);
    std::printf("frame %d: field %.2f, instant %.2f grey levels from the reference\n", first + i, f,
                n);
    field_error += f / count;
    instant_error += n / count;
  }
  std::printf("mean: field %.2f, instant camera %.2f grey levels (ratio %.2f)\n", field_error,
              instant_error, field_error / instant_error);
  EXPECT_GT(instant_error, 2.0);  // the shutter matters on these frames
  EXPECT_LT(field_error, 0.6 * instant_error);
}

TEST(SimShutter, IdealSensorAndZeroTimesAreTheInstantCamera) {
  const cv::Mat instant = render_middle_frame(turning_scenario(2.0, "{model: kinect}"));
  const cv::Mat ideal =
      render_middle_frame(turning_scenario(2.0, "{model: ideal, exposure: 0.02, readout: 0.01}"));
  EXPECT_EQ(cv::norm(instant, ideal, cv::NORM_INF), 0.0);
}

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A shutter changes the colour images only: the truth is the timestamp's,
// byte for byte, and the same seed gives the same dataset.
TEST(SimShutter, TruthIsTheTimestampsAndDatasetsAreByteIdentical) {
  SmallRender plain("depot_walking_xyz", 6, 160, false, 5);
  SmallRender exposed = plain;
  exposed.set = {{"sensor.exposure", "0.02"}, {"sensor.readout", "0.01"}};
  const std::string a = render_small(plain);
  const std::string b = render_small(exposed);
  const std::string c = render_small(exposed);
  EXPECT_EQ(compare_trees(b, c), "");
  for (const char* name : {"groundtruth.txt", "object_poses.txt", "boxes.txt", "rgb.txt"})
    EXPECT_EQ(file_text(a + "/" + name), file_text(b + "/" + name)) << name;
  // Labels and depth are the timestamp's too; colour differs.
  const std::string stamp =
      "/labels/" + fs::directory_iterator(a + "/labels")->path().filename().string();
  EXPECT_EQ(file_text(a + stamp), file_text(b + stamp));
  const std::string depth = "/depth/" + fs::path(stamp).filename().string();
  EXPECT_EQ(file_text(a + depth), file_text(b + depth));
  EXPECT_NE(compare_trees(a + "/rgb", b + "/rgb"), "");
  EXPECT_NE(file_text(b + "/calibration.yaml").find("shutter:\n  exposure: 0.02"),
            std::string::npos);
  EXPECT_THAT(file_text(a + "/calibration.yaml"), ::testing::Not(::testing::HasSubstr("shutter:")));
}

// Under a rolling shutter, groundtruth_rows.txt gives the camera at sampled
// rows' instants: each row's time is the frame's plus its offset, and the
// camera turning at omega has turned omega x that offset from the frame's
// pose in groundtruth.txt.
TEST(SimShutter, RowPosesAreTheCameraAtEachRowsInstant) {
  const double omega = 2.0, readout = 0.03;
  SmallRender request(turning_scenario(omega, "{model: kinect, readout: 0.03}"), 3, 160, false);
  const std::string root = render_small(request);
  std::map<double, Pose> frames;
  for (const StampedPose& p : read_tum_trajectory(root + "/groundtruth.txt"))
    frames[p.timestamp] = p.pose;
  ASSERT_EQ(frames.size(), 3u);
  std::ifstream in(root + "/groundtruth_rows.txt");
  ASSERT_TRUE(in.good());
  std::string line;
  int samples = 0;
  double largest_turn = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    double stamp, time, tx, ty, tz, qx, qy, qz, qw;
    int row;
    ASSERT_TRUE(fields >> stamp >> row >> time >> tx >> ty >> tz >> qx >> qy >> qz >> qw) << line;
    ASSERT_EQ(frames.count(stamp), 1u) << line;
    const int height = 120;  // 160 px wide
    EXPECT_NEAR(time - stamp, (row / (height - 1.0) - 0.5) * readout, 2e-6) << line;
    const Pose camera = make_pose(Eigen::Quaterniond(qw, qx, qy, qz), Eigen::Vector3d(tx, ty, tz));
    const double turn = rotation_angle_between(camera, frames[stamp]);
    // Signed: about the camera's own y axis, later rows turned further.
    const Eigen::AngleAxisd relative(frames[stamp].linear().transpose() * camera.linear());
    EXPECT_NEAR(relative.angle() * relative.axis().y(), omega * (time - stamp), 1e-4) << line;
    largest_turn = std::max(largest_turn, turn);
    ++samples;
  }
  EXPECT_EQ(samples, 3 * (sim::kRowPoseIntervals + 1));
  EXPECT_NEAR(largest_turn, omega * readout / 2, 1e-4);  // first and last rows
  // A global shutter has no row poses.
  SmallRender global(turning_scenario(omega, "{model: kinect, exposure: 0.01}"), 3, 160, false);
  EXPECT_FALSE(fs::exists(render_small(global) + "/groundtruth_rows.txt"));
}

// The motion field through a lens (sub-frames made on the canvas, then
// resampled like a render): datasets stay byte-identical for one seed, and
// depth and labels stay the timestamp's.
TEST(SimShutter, MotionFieldDatasetsAreByteIdenticalThroughALens) {
  SmallRender plain("depot_walking_xyz", 5, 160, false, 5);
  plain.set = {{"sensor.k1", "-0.2"}, {"sensor.k2", "0.05"}};
  SmallRender field = plain;
  field.set.push_back({"sensor.exposure", "0.02"});
  field.set.push_back({"sensor.readout", "0.028"});
  field.set.push_back({"sensor.motion_blur", "field"});
  const std::string a = render_small(plain);
  const std::string b = render_small(field);
  // Sub-frames are made in parallel: one thread gives the same bytes.
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  const std::string c = render_small(field);
  cv::setNumThreads(threads);
  EXPECT_EQ(compare_trees(b, c), "");
  EXPECT_EQ(compare_trees(a + "/labels", b + "/labels"), "");
  EXPECT_EQ(compare_trees(a + "/depth", b + "/depth"), "");
  EXPECT_NE(compare_trees(a + "/rgb", b + "/rgb"), "");
}

// Exposure + readout longer than a frame (20 + 20 ms at 30 Hz): the next
// frame's first rows expose before this frame's last row is read, so the
// world is stepped again from a saved state. Every frame must be exactly
// the frame the same camera takes when its neighbours are far apart (every
// other stamp only): the pushed chair (physics) is where it was then, not
// where the world had got to.
TEST(SimShutter, ASpanLongerThanAFrameGivesEachFrameAsIfAlone) {
  const std::string base = temp_path("overlap");
  fs::create_directories(base);
  // A chair pushed across the view at 0.8 m/s from about 0.6 s.
  const std::string yaml = base + "/push.yaml";
  std::ofstream(yaml) << "name: push_across\n"
                      << "scene: " << DEPOT_SOURCE_DIR << "/scenes/depot.yaml\n"
                      << "classes: " << DEPOT_SOURCE_DIR << "/scenes/classes.yaml\n"
                      << "frames: 40\n"
                      << "motion: {type: static, position: [0.0, 0.6, 1.35], look_at: [0.0, 4.5, "
                         "0.9]}\n"
                      << "sensor: {exposure: 0.02, readout: 0.02, max_subframes: 3}\n"
                      << "actors:\n"
                      << "  - {name: chair_pushed, type: chair, position: [-0.9, 2.35]}\n"
                      << "  - {name: pusher, type: human, speed: 0.8, pushes: chair_pushed, loop: "
                         "false, path: [[-2.0, 2.35], [1.2, 2.35]]}\n";
  const int count = 40;
  auto stamps = [&](int step) {
    const std::string path = base + "/stamps_" + std::to_string(step) + ".txt";
    std::ofstream out(path);
    out << std::fixed << std::setprecision(6);
    for (int i = 0; i < count; i += step) {
      const double t = kStart + i / 30.0;
      out << t << " rgb/" << t << ".png\n";
    }
    return path;
  };
  auto render = [&](const std::string& stamp_file) {
    sim::Scenario s = sim::load_scenario(yaml, {{"timestamps.file", stamp_file}});
    sim::scale_camera(s.camera, 160);
    sim::SimulatedSequence sequence(s, sim::GlBackend::kOsMesa);
    std::vector<cv::Mat> colour;
    sim::RenderedFrame frame;
    sim::FrameTruth truth;
    while (sequence.next(frame, truth)) colour.push_back(frame.bgr.clone());
    return colour;
  };
  const std::vector<cv::Mat> dense = render(stamps(1));
  const std::vector<cv::Mat> sparse = render(stamps(2));
  ASSERT_EQ(dense.size(), static_cast<size_t>(count));
  ASSERT_EQ(sparse.size(), static_cast<size_t>(count / 2));
  for (size_t j = 0; j < sparse.size(); ++j)
    EXPECT_EQ(cv::norm(dense[2 * j], sparse[j], cv::NORM_INF), 0.0) << "frame " << 2 * j;
}

// The depth camera's own clock: its image is the one an instant camera takes
// at the depth stamp (the camera turns, so any other instant differs), and
// depth.txt says so.
TEST(SimCameraTiming, DepthOffsetRendersDepthAtItsOwnStamp) {
  const double offset = 0.008;
  const sim::RenderedFrame shifted = middle_frame(
      turning_scenario(2.0, "{model: kinect, depth_offset: " + std::to_string(offset) + "}"));
  const sim::RenderedFrame at_depth_stamp =
      middle_frame(turning_scenario(2.0, "{model: kinect}", kStart + offset));
  const sim::RenderedFrame at_colour_stamp = middle_frame(turning_scenario(2.0, "{model: kinect}"));
  EXPECT_EQ(cv::norm(shifted.depth, at_depth_stamp.depth, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(shifted.depth, at_colour_stamp.depth, cv::NORM_INF), 0.1);
  // Colour and labels stay the colour stamp's.
  EXPECT_EQ(cv::norm(shifted.bgr, at_colour_stamp.bgr, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(shifted.instance, at_colour_stamp.instance, cv::NORM_INF), 0.0);
}

// The depth camera's own instant comes after the motion field's render at
// the timestamp and reuses the renderer's canvas (a lens): the colour must
// still be made from the timestamp's render, as without a depth offset.
TEST(SimCameraTiming, DepthOffsetLeavesTheMotionFieldsColourAlone) {
  const std::string sensor = "{model: kinect, exposure: 0.02, motion_blur: field, k1: -0.2";
  const sim::RenderedFrame own_depth =
      middle_frame(turning_scenario(2.0, sensor + ", depth_offset: 0.008}"));
  const sim::RenderedFrame same_depth = middle_frame(turning_scenario(2.0, sensor + "}"));
  EXPECT_EQ(cv::norm(own_depth.bgr, same_depth.bgr, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(own_depth.depth, same_depth.depth, cv::NORM_INF), 0.1);
}

TEST(SimCameraTiming, JitterAndDropsAreADriversAndTheTruthFollows) {
  SmallRender r("depot_static", 40, 64, false, 9);
  r.set = {{"timestamps.jitter", "0.003"},
           {"timestamps.drop_rate", "0.2"},
           {"sensor.depth_offset", "-0.004"}};
  const std::string root = render_small(r);
  const auto rgb = read_file_list(root + "/rgb.txt");
  const auto depth = read_file_list(root + "/depth.txt");
  const auto truth = read_tum_trajectory(root + "/groundtruth.txt");
  ASSERT_EQ(rgb.size(), depth.size());
  ASSERT_EQ(rgb.size(), truth.size());
  EXPECT_LT(rgb.size(), 40u);  // dropped frames are missing
  EXPECT_GT(rgb.size(), 20u);
  const double period = 1.0 / 30.0;
  double sum_sq = 0;
  long last_index = -1;
  for (size_t i = 0; i < rgb.size(); ++i) {
    EXPECT_NEAR(depth[i].timestamp - rgb[i].timestamp, -0.004, 2e-6);
    EXPECT_NEAR(truth[i].timestamp, rgb[i].timestamp, 1e-6);  // truth at the capture
    const double since = rgb[i].timestamp - 1700000000.0;
    const long index = std::lround(since / period);
    const double late = since - index * period;
    EXPECT_LE(std::abs(late), 0.25 * period + 1e-6);
    EXPECT_GT(index, last_index);
    last_index = index;
    sum_sq += late * late;
  }
  const double sigma = std::sqrt(sum_sq / rgb.size());
  EXPECT_GT(sigma, 0.0015);
  EXPECT_LT(sigma, 0.0045);
  // The same scenario and seed: the same frames, byte for byte.
  EXPECT_EQ(compare_trees(root, render_small(r)), "");
}

// Lens distortion and non-square pixels (sim/sensor/lens.h) against an
// independent inversion: each pixel of the distorted image, undistorted by
// OpenCV, must show what the pinhole render of the same instant shows along
// that ray (same instance, same depth), and the boxes made from the labels
// follow.
struct LensAgreement {
  double labels = 0;       // share of compared pixels with the same instance
  double depth_error = 0;  // median |z - z_ref| / z_ref where labels agree
  int compared = 0;
};

sim::RenderedFrame frame_of(const sim::Scenario& s, int index) {
  sim::SimulatedSequence sequence(s, sim::GlBackend::kOsMesa);
  sim::RenderedFrame frame;
  sim::FrameTruth truth;
  for (int i = 0; i <= index; ++i) EXPECT_TRUE(sequence.next(frame, truth));
  return frame;
}

// `lensed` seen through `camera` + `lens` (or, with `undistort` false, as
// if it were a pinhole) against the pinhole render `plain` of focal f,
// whose pixels are looked up `shift` pixels off.
LensAgreement compare_through_lens(const sim::RenderedFrame& lensed,
                                   const sim::CameraIntrinsics& camera,
                                   const sim::LensDistortion& lens, const sim::RenderedFrame& plain,
                                   bool undistort, cv::Point2d shift = {0, 0}) {
  std::vector<cv::Point2f> pixels, rays;
  for (int v = 0; v < lensed.depth.rows; v += 2)
    for (int u = 0; u < lensed.depth.cols; u += 2) pixels.emplace_back(u, v);
  const cv::Matx33d k(camera.f, 0, camera.cx, 0, camera.focal_y(), camera.cy, 0, 0, 1);
  const std::vector<double> dist{lens.k1, lens.k2, lens.p1, lens.p2, lens.k3};
  if (undistort)
    cv::undistortPoints(
        pixels, rays, k, dist, cv::noArray(), cv::noArray(),
        cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-12));
  LensAgreement a;
  int same = 0;
  std::vector<double> errors;
  for (size_t i = 0; i < pixels.size(); ++i) {
    const cv::Point2f& p = pixels[i];
    const double x = undistort ? rays[i].x : (p.x - camera.cx) / camera.f;
    const double y = undistort ? rays[i].y : (p.y - camera.cy) / camera.f;
    const int u = cvRound(camera.f * x + camera.cx + shift.x),
              v = cvRound(camera.f * y + camera.cy + shift.y);
    if (u < 0 || v < 0 || u >= plain.depth.cols || v >= plain.depth.rows) continue;
    ++a.compared;
    const uint16_t id = lensed.instance.at<uint16_t>(cvRound(p.y), cvRound(p.x));
    if (id != plain.instance.at<uint16_t>(v, u)) continue;
    ++same;
    const float z = lensed.depth.at<float>(cvRound(p.y), cvRound(p.x));
    const float z_ref = plain.depth.at<float>(v, u);
    if (z_ref > 0) errors.push_back(std::abs(z - z_ref) / z_ref);
  }
  a.labels = a.compared ? static_cast<double>(same) / a.compared : 0.0;
  if (!errors.empty()) {
    std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
    a.depth_error = errors[errors.size() / 2];
  }
  return a;
}

TEST(SimLens, EachPixelShowsWhatItsUndistortedRaySees) {
  sim::Scenario plain = sim::load_scenario(scenario_path("depot_walking_xyz"));
  sim::scale_camera(plain.camera, kWidth);
  sim::Scenario lensed = plain;
  lensed.sensor.lens = {-0.25, 0.08, 0.0015, -0.001, 0.0};
  lensed.camera.fy = plain.camera.f * 1.02;
  const sim::RenderedFrame a = frame_of(lensed, 5);
  const sim::RenderedFrame b = frame_of(plain, 5);
  ASSERT_EQ(a.bgr.size(), b.bgr.size());
  const LensAgreement through = compare_through_lens(a, lensed.camera, lensed.sensor.lens, b, true);
  const LensAgreement ignored =
      compare_through_lens(a, lensed.camera, lensed.sensor.lens, b, false);
  std::printf(
      "lens: labels agree on %.2f %% of %d pixels (median depth error %.3f %%); "
      "read as a pinhole %.2f %%\n",
      100 * through.labels, through.compared, 100 * through.depth_error, 100 * ignored.labels);
  // Barrel: the corners' rays lie outside the pinhole render.
  EXPECT_GT(through.compared, 0.8 * (a.bgr.total() / 4));
  // What disagrees lies on edges, where two grids round to different
  // sides: no half-pixel shift of the lookup agrees better.
  EXPECT_GT(through.labels, 0.96);
  for (const cv::Point2d shift :
       {cv::Point2d(0.5, 0), cv::Point2d(-0.5, 0), cv::Point2d(0, 0.5), cv::Point2d(0, -0.5)}) {
    const LensAgreement off =
        compare_through_lens(a, lensed.camera, lensed.sensor.lens, b, true, shift);
    EXPECT_LT(off.labels, through.labels) << shift;
  }
  EXPECT_LT(through.depth_error, 0.002);
  EXPECT_LT(ignored.labels, through.labels - 0.05);
  // --ideal keeps the camera's pixels and drops the lens.
  sim::Scenario ideal = lensed;
  ideal.sensor.ideal = true;
  ideal.camera.fy = 0;
  const sim::RenderedFrame c = frame_of(ideal, 5);
  EXPECT_EQ(cv::norm(c.depth, b.depth, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(c.instance, b.instance, cv::NORM_INF), 0.0);
}

TEST(SimLens, CalibrationStatesTheLensAndDatasetsAreByteIdentical) {
  SmallRender plain("depot_walking_xyz", 4, 160, false, 5);
  SmallRender lensed = plain;
  lensed.set = {
      {"sensor.k1", "-0.2"}, {"sensor.k2", "0.05"}, {"sensor.p2", "0.002"}, {"camera.fy", "545"}};
  const std::string a = render_small(lensed);
  const std::string b = render_small(lensed);
  EXPECT_EQ(compare_trees(a, b), "");
  const std::string calibration = file_text(a + "/calibration.yaml");
  for (const char* line :
       {"  k1: -0.2\n", "  k2: 0.05\n", "  p1: 0\n", "  p2: 0.002\n", "  fy: 136.250000\n"})
    EXPECT_THAT(calibration, ::testing::HasSubstr(line)) << line << " in " << calibration;
  // Ground truth does not depend on the lens; the images do.
  const std::string c = render_small(plain);
  EXPECT_EQ(file_text(a + "/groundtruth.txt"), file_text(c + "/groundtruth.txt"));
  EXPECT_NE(compare_trees(a + "/labels", c + "/labels"), "");
  // A lens that folds the image is refused before anything is written.
  SmallRender folding = plain;
  folding.set = {{"sensor.k1", "-1"}};
  try {
    render_small(folding);
    FAIL() << "a folding lens rendered";
  } catch (const Error& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("folds the image")) << e.what();
  }
}

}  // namespace
}  // namespace depot::test
