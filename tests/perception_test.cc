// Perception measured: `depot eval detector|segmenter` on a rendered walking
// scenario and on the real TUM frame (with its hand labels), and bad input.
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "eval/image_labels.h"
#include "slam/detect/detector_config.h"
#include "slam/detect/detector_factory.h"
#include "slam/detect/person_segmenter.h"
#include "slam/detect/sim_detector_config.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"
#include "tools/perception/detector_eval.h"
#include "tools/perception/segmenter_eval.h"

namespace fs = std::filesystem;

namespace depot::test {
namespace {

const std::string kSource = DEPOT_SOURCE_DIR;
const std::string kLabels = kSource + "/eval/data/real_labels.yaml";
const std::string kTumFrame = "fr3_walking_xyz_frame";

// The shipped hand labels of the real TUM frame only.
eval::ImageLabels tum_frame_labels() {
  eval::ImageLabels labels = eval::read_image_labels(kLabels);
  std::vector<eval::LabelledImage> tum;
  for (const eval::LabelledImage& image : labels.images)
    if (image.path.find(kTumFrame) != std::string::npos) tum.push_back(image);
  labels.images = tum;
  return labels;
}

bool have_shared_data() {
  return fs::exists(std::string(DEPOT_SHARED_DATA) + "/tum/" + kTumFrame);
}

#define REQUIRE_SHARED_DATA() \
  if (!have_shared_data()) GTEST_SKIP() << "shared real data missing: " << DEPOT_SHARED_DATA

const std::string& walking_dataset() {
  static const std::string d = render_small({"depot_walking_xyz", 6, 320, false});
  return d;
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(Perception, PerfectSimulatedDetectorScoresOne) {
  const std::string json = temp_path("perfect") + ".json";
  const std::string report = temp_path("report");
  const DepotResult r = depot("eval detector " + walking_dataset() +
                              " --detector sim --detector-set perfect=true -q --json " + json +
                              " --report " + report);
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json person = read_json(json)["sides"][0]["classes"]["person"];
  EXPECT_GT(person["recall_all"]["total"].get<int>(), 5) << "people in every frame";
  EXPECT_EQ(person["recall_all"]["rate"].get<double>(), 1.0);
  EXPECT_EQ(person["precision"]["rate"].get<double>(), 1.0);
  EXPECT_EQ(read_json(json)["sides"][0]["false_positives"].get<int>(), 0);
  EXPECT_TRUE(fs::exists(report + "/report.html"));
  EXPECT_TRUE(fs::exists(report + "/recall_vs_height_1.svg"));
  EXPECT_THAT(r.output, ::testing::HasSubstr("person"));
  // Recall per catalogue model: the mesh people are listed by the model
  // they wear (objects.json), each found every time.
  const size_t models = r.output.find("Recall per model");
  ASSERT_NE(models, std::string::npos) << r.output;
  const std::string table = r.output.substr(models, r.output.find("Recall by box") - models);
  EXPECT_THAT(table, ::testing::HasSubstr("person")) << table;
  EXPECT_THAT(table, ::testing::HasSubstr("1.00")) << table;
  EXPECT_THAT(table, ::testing::Not(::testing::HasSubstr("0.00"))) << table;
}

TEST(Perception, YoloFastestFindsBothPeopleOfTheRealTumFrame) {
  REQUIRE_SHARED_DATA();
  auto detector = slam::make_dnn_detector(
      slam::load_detector_config(kSource + "/scenes/detectors/yolo_fastest.yaml"));
  const eval::ImageLabels labels = tum_frame_labels();
  ASSERT_EQ(labels.images.size(), 1u);
  const perception::DetectorEval e = perception::evaluate_on_images(
      *detector, labels, perception::class_mapping_for("darknet", ""), true);
  EXPECT_EQ(e.score.tally("person").all.total, 2);
  EXPECT_EQ(e.score.tally("person").all.found, 2);
  EXPECT_EQ(e.score.tally("person").precision.rate(), 1.0);
}

TEST(Perception, SelfieSegmentationMasksThePeopleOfTheRealTumFrame) {
  REQUIRE_SHARED_DATA();
  slam::PersonSegmenter segmenter(
      slam::load_segmenter_config(kSource + "/scenes/segmenters/selfie.yaml"));
  const perception::SegmenterEval e =
      perception::evaluate_segmenter_on_images(segmenter, tum_frame_labels(), true);
  ASSERT_EQ(e.frames.size(), 1u);
  const eval::BoxCoverage& c = e.frames[0].coverage;
  // Measured 0.97 inside and 0.73 covered: a person's box holds background
  // between arms and legs, so the mask covers most of it but not all.
  EXPECT_GT(c.inside(), 0.9) << "little of the mask lies outside the people's boxes";
  EXPECT_GT(c.covered(), 0.6) << "the mask covers most of the people's boxes";
}

TEST(Perception, SegmenterOnARenderedDataset) {
  REQUIRE_SHARED_DATA();
  const std::string json = temp_path("segmenter") + ".json";
  // Two seconds of walking, every 6th frame: a few frames at the start alone
  // may show only a person's edge, which says little about the model.
  const std::string data = render_small({"depot_walking_xyz", 60, 320, false});
  const DepotResult r = depot("eval segmenter " + data + " --every 6 -q --json " + json);
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json d = read_json(json)["dataset"];
  EXPECT_EQ(d["frames"].size(), 10u);
  // Measured 0.64 here (seed 2: 0.75; 0.54 over 300 frames at 640 px in an
  // earlier world): the selfie model masks some primitive people well and
  // others poorly.
  EXPECT_GT(d["mean_iou"].get<double>(), 0.4);
  EXPECT_LE(d["mean_iou"].get<double>(), 1.0);
}

// One error line naming the file, a non-zero exit, no output written.
void expect_error(const std::string& args, const std::string& needle) {
  const std::string json = temp_path("out") + ".json";
  const DepotResult r = depot(args + " -q --json " + json);
  EXPECT_NE(r.code, 0) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_EQ(r.output.rfind("depot: error: " + needle, 0), 0u) << r.output;
  EXPECT_FALSE(fs::exists(json)) << "nothing written on failure";
}

TEST(Perception, BadInputIsOneErrorLine) {
  REQUIRE_SHARED_DATA();
  const std::string missing = temp_path("missing") + ".onnx";
  const std::string detector_yaml = write_yaml("detector", "type: fastestdet\nmodel: " + missing +
                                                               "\nnames: " + DEPOT_SHARED_DATA +
                                                               "/models/fastestdet/coco.names\n");
  expect_error("eval detector --images " + kLabels + " --detector fastestdet --detector-config " +
                   detector_yaml,
               missing + ": model file not found");
  const std::string segmenter_yaml = write_yaml("segmenter", "model: " + missing + "\n");
  expect_error("eval segmenter --images " + kLabels + " --segmenter-config " + segmenter_yaml,
               missing + ": model file not found");
  const std::string corrupt = write_yaml("labels", "classes: [person]\nimages:\n  a.png: [\n");
  expect_error("eval detector --images " + corrupt, corrupt + ":4: YAML syntax error");
  const std::string typo = write_yaml("map", "map:\n  person: persn\n");
  expect_error("eval detector --images " + kLabels + " --class-map " + typo,
               typo + ":2: class 'persn' is not a class of " + kLabels);
  expect_error("eval detector " + walking_dataset() + " --class-map " + typo,
               typo + ":2: class 'persn' is not a class of " + walking_dataset() + "/classes.txt");
  // Command-line mistakes: exit 2, before any work (cli_errors_test checks the code).
  expect_error("eval detector --images " + kLabels + " --detector sim",
               "eval detector: --detector sim: needs a simulated DATASET");
  expect_error("eval detector", "eval detector: give a DATASET, --images LABELS.yaml, or both");
  const std::string real = std::string(DEPOT_SHARED_DATA) + "/tum/" + kTumFrame;
  expect_error("eval detector " + real, real + ": no ground-truth boxes (boxes.txt)");
}

// Mesh people, small frames: what `depot eval calibrate` is fitted on.
const std::string& mesh_walking_dataset() {
  static const std::string d = [] {
    SmallRender r{"depot_walking_xyz", 30, 320, false};
    r.set = {{"actors_style", "mesh"}};
    return render_small(r);
  }();
  return d;
}

TEST(Perception, CalibrateFitsTheSimulatedDetectorToYoloFastest) {
  REQUIRE_SHARED_DATA();
  const std::string out = temp_path("calibrated") + ".yaml";
  const DepotResult r = depot("eval calibrate " + mesh_walking_dataset() + " -q -o " + out);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("person")) << r.output;
  // The file is a simulated detector config ...
  const slam::SimDetectorConfig c = slam::load_sim_detector_config_file(out);
  EXPECT_DOUBLE_EQ(c.min_confidence, 0.3) << "Yolo-Fastest's threshold";
  // Measured here: person miss rate 0 (the rest is explained by size and
  // occlusion), jitter 0.066, scale error 0.16, 0.4 false positives a frame.
  EXPECT_LT(c.class_miss_rate.at("person"), 0.3) << "people are found";
  EXPECT_GT(c.class_miss_rate.at("desk"), 0.9) << "desks are not";
  EXPECT_GT(c.jitter, 0.01);
  EXPECT_LT(c.jitter, 0.2);
  EXPECT_GT(c.scale_error, 0.02);
  EXPECT_LT(c.scale_error, 0.4);
  EXPECT_GT(c.max_confidence, 0.5);
  EXPECT_LT(c.false_positive_rate, 2.0);
  // ... beside the measurement it came from.
  const YAML::Node cal = YAML::LoadFile(out)["calibration"];
  ASSERT_TRUE(cal.IsMap());
  EXPECT_EQ(cal["detector"].as<std::string>(), "darknet");
  EXPECT_EQ(cal["detector_config"].as<std::string>(), "scenes/detectors/yolo_fastest.yaml");
  EXPECT_EQ(cal["command"].as<std::string>(),
            "depot eval calibrate " + mesh_walking_dataset() + " --detector darknet -o " + out);
  const YAML::Node d = cal["datasets"][0];
  EXPECT_EQ(d["scenario"].as<std::string>(), "depot_walking_xyz");
  EXPECT_EQ(d["actors_style"].as<std::string>(), "mesh");
  EXPECT_EQ(d["frames"].as<int>(), 30);
  EXPECT_EQ(d["size"].as<std::string>(), "320x240");
  EXPECT_THAT(d["render"].as<std::string>(), ::testing::HasSubstr("--width 320"));
  EXPECT_THAT(d["render"].as<std::string>(), ::testing::Not(::testing::HasSubstr("_style")))
      << "mesh is the default style: no --set needed";
  const YAML::Node person = cal["classes"]["person"];
  EXPECT_GT(person["boxes"].as<int>(), 20);
  EXPECT_GT(person["detections"].as<int>(), 10);
  // The fitted simulated detector finds people about as often as the real
  // one on the same frames (measured 0.77 and 0.80).
  EXPECT_GT(person["recall_real"].as<double>(), 0.5);
  EXPECT_NEAR(person["recall_sim"].as<double>(), person["recall_real"].as<double>(), 0.15);
}

TEST(Perception, CalibrateRecoversTheSimulatedDetectorsOwnParameters) {
  // The simulated detector fitted to itself, through the command.
  const std::string known =
      write_yaml("known",
                 "miss_rate: 0.2\nsmall_miss_boost: 0.5\nsmall_area: 0.02\nocclusion_miss: 0.4\n"
                 "jitter: 0.05\nscale_error: 0.08\nhard_jitter_gain: 0\nmax_confidence: 0.9\n"
                 "confidence_noise: 0.05\nfalse_positive_rate: 0.5\nclass_confusion: 0\n");
  const std::string out = temp_path("self") + ".yaml";
  const DepotResult r = depot("eval calibrate " + mesh_walking_dataset() +
                              " --detector sim --detector-config " + known + " -q -o " + out);
  ASSERT_EQ(r.code, 0) << r.output;
  const slam::SimDetectorConfig c = slam::load_sim_detector_config_file(out);
  // 171 boxes only: coarse.
  EXPECT_NEAR(c.class_miss_rate.at("person"), 0.2, 0.15);
  EXPECT_NEAR(c.jitter, 0.05, 0.015);
  EXPECT_NEAR(c.scale_error, 0.08, 0.025);
  EXPECT_NEAR(c.max_confidence, 0.9, 0.05);
  EXPECT_NEAR(c.false_positive_rate, 0.5, 0.3);
  EXPECT_TRUE(c.confusions.empty());
  EXPECT_EQ(YAML::LoadFile(out)["calibration"]["class_map"].as<std::string>(), "identity");
}

TEST(Perception, CalibrateBadInputIsOneErrorLineAndNoFile) {
  REQUIRE_SHARED_DATA();
  const std::string dir = temp_path("calibrate_out");
  fs::create_directories(dir);
  const std::string out = dir + "/sim.yaml";
  auto expect_calibrate_error = [&](const std::string& args, const std::string& needle, int code) {
    const DepotResult r = depot("eval calibrate " + args + " -q -o " + out);
    EXPECT_EQ(r.code, code) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_EQ(r.output.rfind("depot: error: " + needle, 0), 0u) << r.output;
    EXPECT_TRUE(fs::is_empty(dir)) << "no output, not even a partial one: " << args;
  };
  const std::string data = mesh_walking_dataset();
  expect_calibrate_error(
      data + " --detector yolo9",
      "eval calibrate: --detector: yolo9 not in {darknet,xl,fastestdet,yolov5,sim}", 2);
  const std::string real = std::string(DEPOT_SHARED_DATA) + "/tum/" + kTumFrame;
  expect_calibrate_error(data + " " + real,
                         real +
                             ": no ground-truth boxes (boxes.txt): the calibration needs a "
                             "simulated dataset (depot sim render)",
                         1);
  expect_calibrate_error(data +
                             " --detector sim --detector-set miss_rate=1 --detector-set "
                             "false_positive_rate=0",
                         data + ": the detector matched none of the", 1);
}

}  // namespace
}  // namespace depot::test
