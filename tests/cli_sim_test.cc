// The `depot sim` command line: bad input gives one clear error line, a
// non-zero exit and no half-written dataset; EGL renders like OSMesa.
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/support/cli_checks.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace fs = std::filesystem;

namespace depot::test {
namespace {

std::string scene_lines() {
  return std::string("scene: ") + DEPOT_SOURCE_DIR +
         "/scenes/depot.yaml\nclasses: " + DEPOT_SOURCE_DIR + "/scenes/classes.yaml\n";
}

// One line, starting "depot: error:", containing `needle`; no output left.
void expect_clean_failure(const std::string& args, const std::string& out,
                          const std::string& needle) {
  DepotResult r = depot(args + " -o " + out + " -q");
  expect_one_error_line(r, needle);
  EXPECT_FALSE(fs::exists(out)) << "no output on failure";
  for (const auto& e : fs::directory_iterator(fs::path(out).parent_path()))
    EXPECT_EQ(e.path().string().find(fs::path(out).filename().string() + ".partial"),
              std::string::npos);
}

TEST(CliSim, BrokenYamlNamesFileAndLine) {
  std::string yaml = write_yaml("broken", "name: x\nmotion: {type: xyz\nactors: [\n");
  expect_clean_failure("sim render " + yaml, temp_path("out"), yaml + ":");
}

TEST(CliSim, UnknownActorType) {
  std::string yaml = write_yaml(
      "actor", scene_lines() + "motion: {type: static}\nactors:\n  - {name: d, type: dragon}\n");
  expect_clean_failure("sim render " + yaml, temp_path("out"), "unknown actor type 'dragon'");
}

TEST(CliSim, UnknownClassInTheClassTable) {
  std::string classes = temp_path("classes") + ".yaml";
  std::ofstream(classes) << "classes:\n  structure: {category: static}\n";
  std::string yaml = write_yaml("class", std::string("scene: ") + DEPOT_SOURCE_DIR +
                                             "/scenes/depot.yaml\nclasses: " + classes +
                                             "\nframes: 2\nmotion: {type: static}\n");
  expect_clean_failure("sim render " + yaml + " --width 64", temp_path("out"),
                       "unknown class 'rack'");
}

TEST(CliSim, MissingAssetFile) {
  std::string yaml = write_yaml(
      "asset", scene_lines() + "motion: {type: file, file: /nonexistent/trajectory.txt}\n");
  expect_clean_failure("sim render " + yaml, temp_path("out"), "/nonexistent/trajectory.txt");
}

TEST(CliSim, UnwritableOutput) {
  std::string file = temp_path("plainfile");
  std::ofstream(file) << "x";
  DepotResult r = depot("sim render depot_static --frames 2 --width 64 -q -o " + file + "/dataset");
  expect_one_error_line(r, file);
}

TEST(CliSim, OutOfRangeParameter) {
  std::string yaml = write_yaml("range", scene_lines() + "motion: {type: xyz, amplitude: 500}\n");
  expect_clean_failure("sim render " + yaml, temp_path("out"), "out of range");
}

TEST(CliSim, BadCameraCover) {
  std::string yaml = write_yaml("cover", scene_lines() +
                                             "frames: 30\nmotion: {type: static}\n"
                                             "camera_cover: [[0.2, 0.5], [0.4, 0.8]]\n");
  expect_clean_failure("sim render " + yaml, temp_path("out"),
                       yaml + ":5: 'camera_cover' interval 2 [0.4, 0.8] overlaps");
}

TEST(CliSim, ListsShippedScenarios) {
  DepotResult r = depot("sim list");
  EXPECT_EQ(r.code, 0) << r.output;
  for (const char* name :
       {"depot_walking_xyz", "depot_walking_halfsphere", "depot_walking_rpy",
        "depot_walking_static", "depot_sitting_xyz", "depot_sitting_static", "depot_patrol",
        "depot_patrol_two_laps", "depot_kidnapped", "depot_static"})
    EXPECT_THAT(r.output, ::testing::HasSubstr(name)) << name;
}

TEST(CliSim, EglRendersTheSameBytesAsOsMesa) {
  std::string a = temp_path("osmesa"), b = temp_path("egl");
  DepotResult ra =
      depot("sim render depot_walking_xyz --frames 3 --width 160 --ideal -q --gl osmesa -o " + a);
  ASSERT_EQ(ra.code, 0) << ra.output;
  DepotResult rb =
      depot("sim render depot_walking_xyz --frames 3 --width 160 --ideal -q --gl egl -o " + b);
  ASSERT_EQ(rb.code, 0) << rb.output;
  EXPECT_EQ(compare_trees(a, b), "");
}

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(CliSim, TruthExportMatchesTheRenderedDatasetWithoutImages) {
  std::string rendered = temp_path("rendered"), truth = temp_path("truth");
  ASSERT_EQ(depot("sim render depot_walking_xyz --frames 40 --width 64 -q -o " + rendered).code, 0);
  DepotResult r = depot("sim truth depot_walking_xyz --frames 40 -q -o " + truth);
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* f : {"groundtruth.txt", "object_poses.txt", "objects.json"})
    EXPECT_EQ(file_text(truth + "/" + f), file_text(rendered + "/" + f)) << f;
  EXPECT_FALSE(fs::exists(truth + "/rgb"));
  EXPECT_TRUE(fs::exists(truth + "/timestamps.txt"));
  // Bad input is rejected the same way as for render.
  EXPECT_NE(depot("sim truth nonexistent_scenario -q -o " + temp_path("x")).code, 0);
}

TEST(CliSim, PreviewWritesAContactSheet) {
  std::string data = temp_path("preview_data");
  ASSERT_EQ(depot("sim render depot_sitting_static --frames 4 --width 160 -q -o " + data).code, 0);
  std::string sheet = temp_path("sheet") + ".png";
  DepotResult r = depot("sim preview " + data + " -o " + sheet + " --rows 2");
  ASSERT_EQ(r.code, 0) << r.output;
  cv::Mat img = cv::imread(sheet);
  ASSERT_FALSE(img.empty());
  EXPECT_GE(img.cols, 3 * 320 - 1);  // RGB | depth | labels
  DepotResult bad = depot("sim preview /nonexistent -o " + sheet);
  EXPECT_NE(bad.code, 0);
}

}  // namespace
}  // namespace depot::test

namespace depot::test {
namespace {

// `depot eval realism`: a small render against the shipped real TUM frame
// (rgb/ and depth/ without lists), then bad input.
TEST(CliRealism, ComparesARenderWithTheRealFrameAndWritesAPage) {
  const std::string real = std::string(DEPOT_SHARED_DATA) + "/tum/fr3_walking_xyz_frame";
  if (!fs::exists(real)) GTEST_SKIP() << "shared data missing: " << real;
  const std::string data = render_small({"depot_walking_xyz", 4, 320, false, 3});
  const std::string page = temp_path("realism") + ".html";
  DepotResult r =
      depot("eval realism " + data + " --reference " + real + " --page " + page + " -q");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* row : {"sharpness median", "noise sigma, grey 96-127", "ORB keypoints median",
                          "depth holes at depth edges", "image motion median"})
    EXPECT_THAT(r.output, ::testing::HasSubstr(row)) << row << "\n" << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("fr3_walking_xyz_frame")) << r.output;
  std::ifstream in(page);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_THAT(html, ::testing::HasSubstr("<svg"));
  fs::remove(page);

  DepotResult missing = depot("eval realism " + data + " --reference /nonexistent/real -q");
  EXPECT_EQ(missing.code, 1) << missing.output;
  EXPECT_EQ(missing.output, "depot: error: /nonexistent/real: dataset folder not found\n");
  const std::string over = data + "/rgb.txt";
  DepotResult onto = depot("eval realism " + data + " --page " + over + " -q");
  EXPECT_EQ(onto.code, 2) << onto.output;
}

}  // namespace
}  // namespace depot::test
