// Light and exposure on real renders: when the depot's light drops to a
// quarter, the first frames after it are dark (the camera was exposed for
// the old light), then auto-exposure brings the image back to its
// brightness with its time constant, exposure first and gain once the
// exposure is at its longest; exposures.txt states what it chose. The
// colour pipeline's stages all on still give byte-identical datasets. The
// actors cast shadows where `shadows` is on; a lamp switched off darkens
// what it lit.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "dataset/exposures.h"
#include "sim/scenario/scenario_loader.h"
#include "sim/sensor/auto_exposure.h"
#include "sim/world/simulated_sequence.h"
#include "tests/support/cli_checks.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace depot::test {
namespace {

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

double mean_grey(const Dataset& d, size_t frame) {
  cv::Mat grey;
  cv::cvtColor(d.rgb(frame), grey, cv::COLOR_BGR2GRAY);
  return cv::mean(grey)[0];
}

TEST(SimLight, AutoExposureRecoversFromALightDropWithItsLag) {
  const int drop_frame = 15;  // the light falls to a quarter at 0.5 s
  const double tau = 0.15;
  SmallRender r("depot_static", 45, 96, false, 3);
  r.set = {{"sensor.light_events", "[[0.49, 1], [0.49, 0.25]]"},
           {"sensor.auto_exposure", "true"},
           {"sensor.exposure", "0.008"},
           {"sensor.max_exposure", "0.02"},
           {"sensor.ae_time_constant", std::to_string(tau)},
           {"sensor.rgb_noise", "0"}};
  const std::string root = render_small(r);
  const Dataset d = read_dataset(root);
  const auto exposures = dataset::read_exposures(root);
  ASSERT_EQ(exposures.size(), 45u);
  ASSERT_EQ(d.frames.size(), 45u);
  auto total = [&](size_t i) { return exposures[i].exposure * exposures[i].gain; };
  for (size_t i = 0; i < exposures.size(); ++i) {
    EXPECT_NEAR(exposures[i].timestamp, d.frames[i].rgb_timestamp, 1e-6);
    EXPECT_DOUBLE_EQ(exposures[i].light, static_cast<int>(i) < drop_frame ? 1.0 : 0.25) << i;
    if (exposures[i].gain > 1.0) {
      EXPECT_NEAR(exposures[i].exposure, 0.02, 1e-9) << i;
    }
  }
  // The loop had settled before the drop; the frame after it is exposed
  // for the old light and comes out dark.
  const double before = total(drop_frame - 1);
  EXPECT_NEAR(total(drop_frame - 2) / before, 1.0, 0.02);
  EXPECT_NEAR(total(drop_frame) / before, 1.0, 0.01);
  // On target (0.45 of full scale) before; the camera meters every fourth
  // pixel of every fourth row, the test every pixel: 2 % of full scale.
  const double target = 0.45 * 255, metering = 5.0;
  const double bright = mean_grey(d, drop_frame - 1);
  EXPECT_NEAR(bright, target, metering);
  EXPECT_LT(mean_grey(d, drop_frame), 0.75 * bright);
  // One time constant later, 1 - 1/e of the way in exposure x gain (log),
  // and four later back on target, at 4x the exposure x gain.
  const int lag = static_cast<int>(std::lround(tau * 30));
  const double reached = std::log(total(drop_frame + lag) / before) / std::log(4.0);
  EXPECT_NEAR(reached, 1.0 - std::exp(-1.0), 0.12);
  EXPECT_NEAR(total(44) / before, 4.0, 0.25);
  EXPECT_GT(exposures[44].gain, 1.0);
  EXPECT_NEAR(mean_grey(d, 44), target, metering);
  const std::string calibration = file_text(root + "/calibration.yaml");
  EXPECT_THAT(calibration, ::testing::HasSubstr("  auto_exposure: true\n")) << calibration;
}

// Shadows (`shadows: true`): MuJoCo's shadow maps for the depot's lights, so
// the moving actors (and pushed chairs) darken what they stand over. The
// same frame is rendered with and without its actors: with shadows off, the
// static pixels neither render covers are the same (lighting has no
// occlusion); with shadows on, the actors' shadows darken some of them, and
// no pixel gets lighter than it is without the actors.
TEST(SimLight, ShadowsOfTheActorsDarkenWhatTheyStandOver) {
  const int frames = 12;
  auto render = [&](bool shadows, bool actors) {
    SmallRender r("depot_walking_xyz", frames, 160, true, 1);
    r.set = {{"shadows", shadows ? "true" : "false"}};
    if (!actors) r.set.emplace_back("actors", "[]");
    return read_dataset(render_small(r));
  };
  struct Change {
    int static_pixels = 0, darker = 0, lighter = 0;
  };
  auto compare = [&](const Dataset& with, const Dataset& without) {
    Change c;
    const size_t last = frames - 1;
    cv::Mat a, b;
    cv::cvtColor(with.rgb(last), a, cv::COLOR_BGR2GRAY);
    cv::cvtColor(without.rgb(last), b, cv::COLOR_BGR2GRAY);
    const cv::Mat labels = with.labels_image(last), bare = without.labels_image(last);
    for (int y = 0; y < a.rows; ++y)
      for (int x = 0; x < a.cols; ++x) {
        // Pixels of an actor (or chair) in either render are not static.
        if (labels.at<uint16_t>(y, x) != bare.at<uint16_t>(y, x)) continue;
        ++c.static_pixels;
        const int d = a.at<uchar>(y, x) - b.at<uchar>(y, x);
        c.darker += d < -8;
        c.lighter += d > 2;
      }
    return c;
  };
  const Change off = compare(render(false, true), render(false, false));
  const Change on = compare(render(true, true), render(true, false));
  std::printf("static pixels %d: shadows off %d darker, %d lighter; on %d darker, %d lighter\n",
              on.static_pixels, off.darker, off.lighter, on.darker, on.lighter);
  ASSERT_GT(on.static_pixels, 5000);
  EXPECT_EQ(off.darker, 0);
  EXPECT_EQ(off.lighter, 0);
  EXPECT_GT(on.darker, on.static_pixels / 100) << "the actors cast no visible shadow";
  EXPECT_LT(on.lighter, on.static_pixels / 1000) << "a shadow only takes light away";
}

// A lamp switched off (`lamps`): the scene is lit without that ceiling light
// from its event on. Frames before it are byte-equal to a render without the
// lamp, frames after are darker where it lit and nowhere lighter; depth and
// labels never change. Two lamps on one light are one error line.
TEST(SimLight, ALampSwitchedOffDarkensWhatItLitAndNothingElse) {
  const int frames = 10;  // walking_xyz's stamps: frame 9 is 0.30 s after frame 0
  auto render = [&](bool lamp) {
    SmallRender r("depot_walking_xyz", frames, 160, true, 1);
    // The ceiling light ahead of the camera, off from 0.15 s.
    if (lamp) r.set = {{"lamps", "[{near: [0.2, 2.8], events: [[0.15, 1], [0.15, 0]]}]"}};
    return read_dataset(render_small(r));
  };
  const Dataset lit = render(false), dark = render(true);
  ASSERT_EQ(lit.frames.size(), static_cast<size_t>(frames));
  ASSERT_EQ(dark.frames.size(), static_cast<size_t>(frames));
  for (int i = 0; i < frames; ++i) {
    EXPECT_EQ(cv::norm(lit.depth_metres(i), dark.depth_metres(i), cv::NORM_INF), 0.0) << i;
    EXPECT_EQ(cv::norm(lit.labels_image(i), dark.labels_image(i), cv::NORM_INF), 0.0) << i;
  }
  EXPECT_EQ(cv::norm(lit.rgb(0), dark.rgb(0), cv::NORM_INF), 0.0) << "before the event";
  cv::Mat before, after;
  cv::cvtColor(lit.rgb(frames - 1), before, cv::COLOR_BGR2GRAY);
  cv::cvtColor(dark.rgb(frames - 1), after, cv::COLOR_BGR2GRAY);
  cv::Mat difference;
  cv::subtract(before, after, difference, cv::noArray(), CV_16S);
  double least = 0, most = 0;
  cv::minMaxLoc(difference, &least, &most);
  const double darker_share = cv::countNonZero(difference > 8) / double(difference.total());
  std::printf("lamp off: mean grey %.1f -> %.1f, %.1f %% of pixels darker by > 8, most %.0f\n",
              cv::mean(before)[0], cv::mean(after)[0], 100 * darker_share, most);
  EXPECT_GT(darker_share, 0.2) << "the lamp lit the view";
  EXPECT_GE(least, -1.0) << "switching a lamp off lights nothing";
  EXPECT_GT(cv::mean(before)[0] - cv::mean(after)[0], 5.0);

  const DepotResult twice =
      depot("sim render depot_static --frames 1 --width 64 -q -o " + temp_path("two_lamps") +
            " --set 'lamps=[{near: [0, 3], events: [[0, 0]]}, {near: [0.4, 3.2], events: [[0, "
            "0]]}]'");
  expect_one_error_line(twice, "lamps 1 and 2 both pick the ceiling light at (0.000000, 3.000000)");
}

// A roller door in the west wall opens to daylight at 0.25 s: the frames
// before are those of a hall without the opening; after, the door's pixels
// show the outside (saturated white, no depth, no instance), auto-exposure
// stops down so the hall darkens, and the outside stays saturated while it
// does (20 times white: it would not with the render's own white).
TEST(SimLight, ADoorOpeningToDaylightSaturatesStopsTheCameraDownAndHasNoDepth) {
  const int frames = 24, opens = 8;  // generated stamps at 30 Hz: frame 8 is 0.267 s
  auto render = [&](bool opening) {
    SmallRender r("depot_static", frames, 160, false, 1);
    r.set = {{"motion", "{type: static, position: [-6, 0.8, 1.5], look_at: [-10, 0.8, 1.5]}"},
             {"sensor.auto_exposure", "true"},
             {"sensor.exposure", "0.008"},
             {"sensor.max_exposure", "0.02"},
             {"sensor.ae_time_constant", "0.05"},
             {"sensor.rgb_noise", "0"}};
    // The opening is the door's own rectangle (scenes/depot.yaml door_west).
    if (opening)
      r.set.push_back({"openings",
                       "[{centre: [-10, 0.8], width: 2.4, height: 3, radiance: 20, events: "
                       "[[0.25, 0], [0.25, 1]]}]"});
    const std::string root = render_small(r);
    return std::make_pair(read_dataset(root), dataset::read_exposures(root));
  };
  const auto [hall, hall_exposures] = render(false);
  const auto [open, open_exposures] = render(true);
  ASSERT_EQ(open.frames.size(), static_cast<size_t>(frames));
  ASSERT_EQ(open_exposures.size(), static_cast<size_t>(frames));
  for (int i = 0; i < opens; ++i) {
    EXPECT_EQ(cv::norm(hall.rgb(i), open.rgb(i), cv::NORM_INF), 0.0) << i;
    EXPECT_EQ(cv::norm(hall.depth_metres(i), open.depth_metres(i), cv::NORM_INF), 0.0) << i;
    EXPECT_EQ(cv::norm(hall.labels_image(i), open.labels_image(i), cv::NORM_INF), 0.0) << i;
  }
  // The outside: where the hall had depth and the open door has none.
  const int last = frames - 1;
  const cv::Mat outside = (hall.depth_metres(last) > 0) & (open.depth_metres(last) == 0);
  const int area = cv::countNonZero(outside);
  const cv::Rect box = cv::boundingRect(outside);
  // The door's face, 2.4 x 3 m at 3.94 m (within the depth camera's 4.5 m),
  // f = 134.8 px: 82 x 103 px.
  std::printf("daylight: %d px in a %d x %d box; exposure x gain %.4f -> %.4f\n", area, box.width,
              box.height, hall_exposures[last].exposure * hall_exposures[last].gain,
              open_exposures[last].exposure * open_exposures[last].gain);
  EXPECT_NEAR(box.width, 82, 3);
  EXPECT_NEAR(box.height, 103, 3);
  EXPECT_GT(area, 0.97 * box.area()) << "one rectangle";
  cv::Mat labels_outside;
  open.labels_image(last).copyTo(labels_outside, outside);
  EXPECT_EQ(cv::countNonZero(labels_outside), 0) << "no instance where the outside shows";
  // Saturated, though the camera stopped down.
  cv::Mat grey_open, grey_hall;
  cv::cvtColor(open.rgb(last), grey_open, cv::COLOR_BGR2GRAY);
  cv::cvtColor(hall.rgb(last), grey_hall, cv::COLOR_BGR2GRAY);
  double darkest = 0;
  cv::minMaxLoc(grey_open, &darkest, nullptr, nullptr, nullptr, outside);
  EXPECT_GE(darkest, 250.0);
  const double stopped = open_exposures[last].exposure * open_exposures[last].gain;
  const double before = hall_exposures[last].exposure * hall_exposures[last].gain;
  EXPECT_LT(stopped, 0.6 * before);
  const cv::Mat inside = ~outside;
  EXPECT_GT(cv::mean(grey_hall, inside)[0] - cv::mean(grey_open, inside)[0], 10.0)
      << "the hall darkens";

  // Bad openings: one error line each, naming the entry.
  auto bad = [](const std::string& openings) {
    return depot("sim render depot_static --frames 1 --width 64 -q -o " + temp_path("bad_opening") +
                 " --set 'openings=" + openings + "'");
  };
  expect_one_error_line(bad("[{centre: [-5, 0], events: [[0, 1]]}]"),
                        "is 5.00 m from the nearest wall (west)");
  expect_one_error_line(bad("[{centre: [-10, 0], width: 13, events: [[0, 1]]}]"),
                        "comes within 0.10 m of the end of the west wall (12.00 m long)");
  expect_one_error_line(bad("[{centre: [-10, 0], height: 5, events: [[0, 1]]}]"),
                        "taller than the hall (4.50 m)");
  expect_one_error_line(bad("[{centre: [-10, 0], events: [[0, 1.5]]}]"),
                        "the share of an opening open must be within [0, 1]");
  expect_one_error_line(bad("[{centre: [-10, 0]}]"), "an opening needs 'centre: [x, y]'");
}

// Under the motion field, a frame whose exposure spans a lamp's change is
// rendered sub-frame by sub-frame (the one render cannot show the change);
// the frames before and after it are moved from one render as usual.
TEST(SimLight, AFrameSpanningALampChangeIsRenderedSubFrameBySubFrame) {
  sim::Scenario scenario = sim::load_scenario(
      scenario_path("depot_static"), {{"sensor.exposure", "0.02"},
                                      {"sensor.readout", "0.02"},
                                      {"sensor.motion_blur", "field"},
                                      {"lamps", "[{near: [0, 3], events: [[0.1, 1], [0.1, 0]]}]"}});
  scenario.frames = 6;
  sim::scale_camera(scenario.camera, 64);
  sim::SimulatedSequence sequence(scenario, sim::GlBackend::kOsMesa);
  sim::RenderedFrame frame;
  sim::FrameTruth truth;
  sim::SequenceTimings timings;
  std::vector<int> renders;
  while (sequence.next(frame, truth, &timings)) renders.push_back(timings.renders);
  ASSERT_EQ(renders.size(), 6u);
  // Frame 3 (0.1 s, its span 0.08-0.12 s) holds the switch.
  for (int i = 0; i < 6; ++i) {
    if (i == 3) {
      EXPECT_GT(renders[i], 1) << i;
    } else {
      EXPECT_EQ(renders[i], 1) << i;
    }
  }
}

TEST(SimLight, EveryStageOnGivesByteIdenticalDatasetsAndTheTruthStays) {
  SmallRender plain("depot_walking_xyz", 5, 128, false, 4);
  SmallRender formed = plain;
  formed.set = {
      {"sensor.light", "0.6"},      {"sensor.flicker", "0.3"},   {"sensor.readout", "0.02"},
      {"sensor.vignetting", "0.7"}, {"sensor.lens_blur", "0.8"}, {"sensor.demosaic", "edge_aware"},
      {"sensor.full_well", "6000"}, {"sensor.read_noise", "10"}, {"sensor.jpeg_quality", "85"}};
  const std::string a = render_small(formed);
  const std::string b = render_small(formed);
  EXPECT_EQ(compare_trees(a, b), "");
  const std::string c = render_small(plain);
  for (const char* name : {"groundtruth.txt", "object_poses.txt", "boxes.txt", "depth.txt"})
    EXPECT_EQ(file_text(a + "/" + name), file_text(c + "/" + name)) << name;
  EXPECT_NE(compare_trees(a + "/rgb", c + "/rgb"), "");
  EXPECT_FALSE(std::filesystem::exists(c + "/exposures.txt"));
  // Flicker under the rolling shutter: the light column is the middle row's.
  for (const auto& e : dataset::read_exposures(a)) {
    EXPECT_GE(e.light, 0.6 * 0.7 - 1e-9);
    EXPECT_LE(e.light, 0.6 * 1.3 + 1e-9);
  }
}

// The shipped sensor profiles (scenarios/sensors/) load and render, and
// calibration.yaml states what they set; the scenario's own keys win.
TEST(SimLight, ShippedSensorProfilesRenderAndStateTheirCamera) {
  for (const char* profile : {"kinect_v1", "realsense_d435"}) {
    SmallRender r("depot_walking_xyz", 3, 64, false, 2);
    r.set = {{"sensor.profile", profile}, {"sensor.max_subframes", "3"}};
    const std::string root = render_small(r);
    EXPECT_EQ(dataset::read_exposures(root).size(), 3u) << profile;
    const std::string calibration = file_text(root + "/calibration.yaml");
    EXPECT_THAT(calibration, ::testing::HasSubstr("  bayer: grbg")) << profile;
    EXPECT_THAT(calibration, ::testing::HasSubstr("  readout: 0.0")) << profile;
  }
}

}  // namespace
}  // namespace depot::test
