// No data lost, no run wasted: what a new user met (issue 11), each as a
// test through the real `depot` program. Nothing a user wrote is deleted,
// by any command, with or without --overwrite; outputs are checked before a
// long run; every refusal is one error line naming the file and the problem.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dataset/dataset_info.h"
#include "tests/support/cli_checks.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace fs = std::filesystem;

namespace depot::test {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A folder holding one file a user wrote.
std::string user_folder(const std::string& tag) {
  const std::string dir = temp_path(tag);
  fs::create_directories(dir);
  std::ofstream(dir + "/notes.txt") << "my notes";
  return dir;
}

const char* const kTinyRender = "sim render depot_static --frames 2 --width 64 -q";

// 1. --overwrite replaces only a folder depot wrote, and nothing else.
TEST(NoDataLost, OverwriteNeverDeletesAUserFolder) {
  const std::string dir = user_folder("mine");
  for (const char* overwrite : {"", " --overwrite"}) {
    expect_one_error_line(depot(std::string(kTinyRender) + overwrite + " -o " + dir), dir);
    expect_one_error_line(
        depot(std::string("sim truth depot_static --frames 2 -q") + overwrite + " -o " + dir), dir);
    EXPECT_EQ(read_text(dir + "/notes.txt"), "my notes");
  }
  // A sweep never takes over a folder that is not a sweep's.
  expect_one_error_line(
      depot("sweep run depot_static --modes orb --seeds 1 --frames 10 -q -o " + dir),
      "not a sweep folder");
  // A trajectory is a file: a folder given as -o is refused.
  expect_one_error_line(depot("slam run " + dir + " -o " + dir + " -q"), "is a folder");
  EXPECT_EQ(read_text(dir + "/notes.txt"), "my notes");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(NoDataLost, OverwriteRefusesTheCurrentFolder) {
  const std::string dir = user_folder("cwd");
  std::string output;
  const int code = run_command(
      "cd " + dir + " && " + depot_binary() + " " + kTinyRender + " --overwrite -o .", &output);
  EXPECT_NE(code, 0) << output;
  EXPECT_EQ(output.rfind("depot: error: ", 0), 0u) << output;
  EXPECT_EQ(read_text(dir + "/notes.txt"), "my notes");
}

TEST(NoDataLost, OverwriteReplacesADatasetButNotAUserFileInIt) {
  const std::string data = temp_path("data");
  ASSERT_EQ(depot(std::string(kTinyRender) + " -o " + data).code, 0);
  // Without --overwrite: refused; with it: replaced once the new one is whole.
  expect_one_error_line(depot(std::string(kTinyRender) + " -o " + data), "--overwrite");
  const DepotResult again =
      depot("sim render depot_static --frames 3 --width 64 -q --overwrite -o " + data);
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_EQ(dataset::read_info(data).value().frames, 3);
  // A user's file inside a dataset makes it theirs: refused, file kept.
  std::ofstream(data + "/notes.txt") << "my notes";
  expect_one_error_line(depot(std::string(kTinyRender) + " --overwrite -o " + data), "notes.txt");
  EXPECT_EQ(read_text(data + "/notes.txt"), "my notes");
  EXPECT_TRUE(fs::exists(data + "/rgb"));
}

// Every file a render can write counts as depot's: a dataset with them all
// (the shutter's per-row truth, the exposures of a formed colour image, the
// YOLO set) is replaced by --overwrite. exposures.txt was once missing from
// that list, so such a dataset could not be re-rendered in place.
TEST(NoDataLost, OverwriteReplacesADatasetWithEveryOptionalFile) {
  const std::string data = temp_path("every_file");
  const std::string render =
      "sim render depot_static --frames 2 --width 64 -q --yolo --set sensor.profile=kinect_v1 -o " +
      data;
  const DepotResult first = depot(render);
  ASSERT_EQ(first.code, 0) << first.output;
  for (const char* file : {"exposures.txt", "groundtruth_rows.txt", "yolo", "boxes_yolo"})
    ASSERT_TRUE(fs::exists(fs::path(data) / file)) << file;
  const DepotResult again = depot(render + " --overwrite");
  EXPECT_EQ(again.code, 0) << again.output;
}

// 3. A render killed with SIGKILL leaves OUT.partial-PID; the next run to
// the same OUT removes it, but never the partial folder of a live process.
TEST(NoDataLost, NextRunRemovesThePartialFolderOfAKilledRender) {
  const std::string out = temp_path("killed");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const std::string binary = depot_binary();
    execl(binary.c_str(), binary.c_str(), "sim", "render", "depot_static", "--frames", "400",
          "--width", "64", "-q", "-o", out.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  const std::string partial = out + ".partial-" + std::to_string(child);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(partial + "/rgb") || fs::is_empty(partial + "/rgb")) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "render never started";
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(fs::exists(partial)) << "SIGKILL cannot clean up";

  // A partial folder of a live process (this test) stays.
  const std::string live = out + ".partial-" + std::to_string(getpid());
  fs::create_directories(live);
  const DepotResult r = depot(std::string(kTinyRender) + " -o " + out);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_FALSE(fs::exists(partial));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(out + "/info.json"));
}

// 2. Every output of a SLAM run is checked before the run starts.
TEST(NoRunWasted, SlamOutputsAreCheckedBeforeTheRun) {
  const std::string data = render_small({"depot_static", 6, 64, false});
  const std::string missing_folder = temp_path("nowhere") + "/traj.txt";
  DepotResult r = depot("slam run " + data + " -o " + missing_folder + " -q");
  expect_one_error_line(r, "does not exist");
  EXPECT_THAT(r.output, ::testing::Not(::testing::HasSubstr("tracked")));
  const std::string traj = temp_path("traj") + ".txt";
  const std::string folder = user_folder("stats_folder");
  r = depot("slam run " + data + " -o " + traj + " --stats " + folder + " -q");
  expect_one_error_line(r, "is a folder");
  EXPECT_FALSE(fs::exists(traj));
  EXPECT_FALSE(fs::exists(traj.substr(0, traj.size() - 4) + ".states.txt"));
  EXPECT_EQ(read_text(folder + "/notes.txt"), "my notes");
}

// 4. A scenario copied anywhere renders: the scene and class table it does
// not name come from the project, paths it names from its own folder.
TEST(NoRunWasted, ACopiedScenarioRenders) {
  const std::string dir = temp_path("copied");
  fs::create_directories(dir);
  fs::copy_file(scenario_path("depot_static"), dir + "/mine.yaml");
  const DepotResult r = depot("sim truth " + dir + "/mine.yaml --frames 3 -q -o " + dir + "/out");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir + "/out/groundtruth.txt"));

  std::ofstream(dir + "/named.yaml")
      << read_text(dir + "/mine.yaml") << "classes: my_classes.yaml\n";
  expect_one_error_line(depot("sim truth " + dir + "/named.yaml -q -o " + dir + "/out2"),
                        "relative to the scenario's folder");
}

// 5. Without calibration.yaml the intrinsics used are named, and a size
// mismatch names the image, both sizes and where the camera came from.
TEST(NoRunWasted, MissingCalibrationIsNamed) {
  const std::string small = render_small({"depot_static", 4, 160, false});
  fs::remove(small + "/calibration.yaml");
  DepotResult r = depot("slam run " + small + " -o " + temp_path("t") + ".txt -q");
  expect_one_error_line(r, "160x120");
  EXPECT_THAT(r.output, ::testing::HasSubstr("640x480")) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("rgb/")) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("no calibration.yaml")) << r.output;

  const std::string full = render_small({"depot_static", 4, 640, true});
  fs::remove(full + "/calibration.yaml");
  r = depot("slam run " + full + " -o " + temp_path("t") + ".txt -q --mapping sync");
  EXPECT_NE(r.output.find("depot: warning: " + full +
                          ": no calibration.yaml; using the TUM fr3 Kinect intrinsics"),
            std::string::npos)
      << r.output;
}

// 6. Options work as asked or are refused, never silently overridden.
TEST(NoRunWasted, NoSilentOverrides) {
  const std::string data = render_small({"depot_static", 6, 64, false});
  const std::string traj = temp_path("t") + ".txt";
  expect_one_error_line(depot("slam run " + data + " -o " + traj + " --frames 50 -q"),
                        "has 6 frames; --frames asks for 50");
  expect_one_error_line(
      depot("slam run " + data + " -o " + traj + " --mode full --detector fastestdet " +
            "--detector-config " + DEPOT_SOURCE_DIR + "/scenes/detectors/yolo_fastest.yaml -q"),
      "configures a 'darknet' detector");
  expect_one_error_line(depot("slam run " + data + " -o " + traj +
                              " --mode orb --detector-config /nonexistent.yaml -q"),
                        "--detector-config: has no effect in --mode orb");
  expect_one_error_line(
      depot("slam run " + data + " -o " + traj + " --mode orb+lk --detector darknet -q"),
      "has no effect in --mode orb+lk");
  EXPECT_FALSE(fs::exists(traj));
}

// 7. The one-line promise holds for damaged files, folders given as files,
// file-system errors and bad sweep levels.
TEST(OneErrorLine, DamagedInputsAndBadLevels) {
  const std::string data = temp_path("damaged");
  fs::copy(render_small({"depot_static", 4, 64, false}), data, fs::copy_options::recursive);
  std::string first;
  for (const auto& e : fs::directory_iterator(data + "/rgb")) first = e.path().string();
  const std::string png = read_text(first);
  std::ofstream(first, std::ios::binary) << png.substr(0, png.size() / 2);  // truncated
  expect_one_error_line(depot("slam run " + data + " -o " + temp_path("t") + ".txt -q"),
                        fs::path(first).filename().string());

  const std::string gt = render_small({"depot_static", 4, 64, false}) + "/groundtruth.txt";
  expect_one_error_line(depot("eval ate " + gt + " " + data), "is a folder");

  const std::string file = temp_path("plain");
  std::ofstream(file) << "x";
  expect_one_error_line(
      depot("sweep run depot_static --modes orb --seeds 1 --frames 10 -q -o " + file + "/sweep"),
      file);
  expect_one_error_line(
      depot("sweep run depot_walking_xyz --vary load=1,abc --plan-only -o " + temp_path("levels")),
      "--vary load: level 'abc' is not a number");
}

// 8. One size rule: what the simulator renders, SLAM accepts.
TEST(OneErrorLine, OneRuleForImageSizes) {
  expect_one_error_line(
      depot("sim render depot_static --frames 2 --width 40 -q -o " + temp_path("w40")), "40x30");
  const DepotResult ok =
      depot("sim render depot_static --frames 3 --width 43 -q -o " + temp_path("w43"));
  EXPECT_EQ(ok.code, 0) << ok.output;
  const std::string data = render_small({"depot_static", 3, 64, false});
  std::string calibration = read_text(data + "/calibration.yaml");
  calibration.replace(calibration.find("height: 48"), 10, "height: 20");
  std::ofstream(data + "/calibration.yaml") << calibration;
  expect_one_error_line(depot("slam run " + data + " -o " + temp_path("t") + ".txt -q"),
                        "calibration.yaml");
}

// 10. The contact sheet is written in the format its name asks for.
TEST(Help, PreviewWritesTheFormatOfItsExtension) {
  const std::string data = render_small({"depot_static", 3, 64, false});
  const std::string jpg = temp_path("sheet") + ".jpg";
  ASSERT_EQ(depot("sim preview " + data + " -o " + jpg).code, 0);
  const std::string bytes = read_text(jpg);
  ASSERT_GE(bytes.size(), 3u);
  EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0xFF);  // JPEG's SOI marker
  EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0xD8);
  expect_one_error_line(depot("sim preview " + data + " -o " + temp_path("sheet") + ".bmp"),
                        "unsupported image format '.bmp'");
}

TEST(Help, SweepShowsProgressFromTheStartAndIsQuietWithQ) {
  const std::string base = "sweep run depot_static --modes orb --seeds 1 --frames 10 --width 64 ";
  const DepotResult loud = depot(base + "-o " + temp_path("loud"));
  ASSERT_EQ(loud.code, 0) << loud.output;
  const size_t started = loud.output.find("started depot_static__s1");
  ASSERT_NE(started, std::string::npos) << loud.output;
  EXPECT_LT(started, loud.output.find("[1/")) << "a line before the first job ends";
  const DepotResult quiet = depot(base + "-q -o " + temp_path("quiet"));
  ASSERT_EQ(quiet.code, 0) << quiet.output;
  EXPECT_THAT(quiet.output, ::testing::Not(::testing::HasSubstr("sweep:"))) << quiet.output;
}

}  // namespace
}  // namespace depot::test
