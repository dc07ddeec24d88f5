// `depot slam run` and `depot eval` on bad input: one clear error line, a
// non-zero exit, and no trajectory written.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace fs = std::filesystem;

namespace depot::test {
namespace {

// A small valid dataset to break in different ways.
std::string small_dataset() {
  std::string src = render_small({"depot_static", 6, 160, false});
  std::string copy = temp_path("broken");
  fs::copy(src, copy, fs::copy_options::recursive);
  return copy;
}

void expect_error(const std::string& dataset, const std::string& needle) {
  const std::string out = temp_path("traj") + ".txt";
  DepotResult r = depot("slam run " + dataset + " -o " + out + " -q");
  EXPECT_NE(r.code, 0) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_EQ(r.output.rfind("depot: error: ", 0), 0u) << r.output;
  EXPECT_NE(r.output.find(needle), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out)) << "no trajectory on failure";
}

std::string first_image(const std::string& dataset, const char* list) {
  std::ifstream in(dataset + "/" + list);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') return line.substr(line.find(' ') + 1);
  return "";
}

TEST(CliSlam, MissingImage) {
  std::string d = small_dataset();
  std::string rgb = first_image(d, "rgb.txt");
  fs::remove(d + "/" + rgb);
  expect_error(d, rgb);
}

TEST(CliSlam, UnreadablePng) {
  std::string d = small_dataset();
  std::string rgb = first_image(d, "rgb.txt");
  std::ofstream(d + "/" + rgb) << "not a png";
  expect_error(d, "unreadable image");
}

TEST(CliSlam, DepthOfTheWrongType) {
  std::string d = small_dataset();
  std::string depth = first_image(d, "depth.txt");
  cv::imwrite(d + "/" + depth, cv::Mat(120, 160, CV_8UC3, cv::Scalar(1, 2, 3)));
  expect_error(d, "16-bit");
}

TEST(CliSlam, MismatchedTimestampLists) {
  std::string d = small_dataset();
  fs::remove(d + "/associations.txt");
  std::ofstream(d + "/depth.txt") << "# shifted\n1.0 depth/a.png\n2.0 depth/b.png\n";
  expect_error(d, "no rgb timestamp has a depth timestamp");
}

TEST(CliSlam, EmptyFolder) {
  std::string d = temp_path("empty");
  fs::create_directories(d);
  expect_error(d, "not a TUM RGB-D folder");
}

TEST(CliSlam, MissingFolder) {
  expect_error("/nonexistent/dataset", "not found");
}

TEST(CliSlam, RunsAndWritesATumTrajectory) {
  std::string d = render_small({"depot_static", 30, 320, false});
  const std::string out = temp_path("traj") + ".txt";
  DepotResult r = depot("slam run " + d + " -o " + out + " --mapping sync -q");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("tracked 30 frames (0 lost"), std::string::npos) << r.output;
  DepotResult ate = depot("eval ate " + d + "/groundtruth.txt " + out);
  EXPECT_EQ(ate.code, 0) << ate.output;
  EXPECT_NE(ate.output.find("rmse"), std::string::npos);
}

TEST(CliSlam, WritesOneRowPerKeypointConsistentWithTheStatistics) {
  std::string d = render_small({"depot_walking_xyz", 12, 320, false});
  const std::string out = temp_path("traj") + ".txt", rows = temp_path("kps") + ".csv",
                    stats = temp_path("stats") + ".csv";
  DepotResult r = depot("slam run " + d + " -o " + out +
                        " --mode full --mapping sync -q --keypoints " + rows + " --stats " + stats);
  ASSERT_EQ(r.code, 0) << r.output;
  // Per frame from the statistics: keypoints and kept.
  std::map<int, std::pair<int, int>> expected;  // frame -> (keypoints, kept)
  std::ifstream s(stats);
  std::string line;
  std::getline(s, line);
  while (std::getline(s, line)) {
    int frame, total, kept;
    char state[32];
    double t;
    ASSERT_EQ(std::sscanf(line.c_str(), "%d,%lf,%31[^,],%d,%d", &frame, &t, state, &total, &kept),
              5)
        << line;
    expected[frame] = {total, kept};
  }
  ASSERT_EQ(expected.size(), 12u);
  std::map<int, std::pair<int, int>> seen;
  int on_moving = 0, rejected_z = 0;
  std::ifstream k(rows);
  std::getline(k, line);
  EXPECT_EQ(line, "frame,timestamp,x,y,octave,set,kept,depth_m,on_moving,boundary,instance");
  while (std::getline(k, line)) {
    int frame, octave, kept, moving, boundary, instance;
    double t, x, y, depth;
    char set;
    ASSERT_EQ(std::sscanf(line.c_str(), "%d,%lf,%lf,%lf,%d,%c,%d,%lf,%d,%d,%d", &frame, &t, &x, &y,
                          &octave, &set, &kept, &depth, &moving, &boundary, &instance),
              11)
        << line;
    EXPECT_TRUE(set == 'Z' || set == 'Q' || set == 'P') << line;
    if (set == 'Z') {
      EXPECT_EQ(kept, 0) << line;  // Z is always rejected
    }
    EXPECT_GE(depth, 0.0);
    EXPECT_FALSE(moving && boundary) << line;  // on a mover is never on its boundary
    EXPECT_GT(instance, 0) << line;             // every pixel belongs to some instance
    seen[frame].first++;
    seen[frame].second += kept;
    on_moving += moving;
    rejected_z += set == 'Z';
  }
  EXPECT_EQ(seen, expected);
  EXPECT_GT(on_moving, 0);  // people walk through this scene
  EXPECT_GT(rejected_z, 0);

  // orb has no rejection to describe: a clear error and no file.
  const std::string none = temp_path("none") + ".csv";
  DepotResult orb = depot("slam run " + d + " -o " + temp_path("t2") + ".txt --mode orb -q " +
                          "--keypoints " + none);
  EXPECT_NE(orb.code, 0);
  EXPECT_NE(orb.output.find("has no effect in --mode orb"), std::string::npos) << orb.output;
  EXPECT_FALSE(fs::exists(none));
}

// The detection thread running ahead changes when detections are made, not
// which: the simulated detector gives the same trajectory either way, also
// with an emulated 60 Hz camera.
TEST(CliSlam, RunAheadLeavesTheTrajectoryUnchanged) {
  std::string d = render_small({"depot_walking_xyz", 20, 640, false});
  auto run = [&](const std::string& options) {
    const std::string out = temp_path("traj") + ".txt";
    DepotResult r =
        depot("slam run " + d + " -o " + out + " --mode full --mapping sync -q " + options);
    EXPECT_EQ(r.code, 0) << r.output;
    std::ifstream in(out);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string ahead = run(""), not_ahead = run("--no-run-ahead");
  EXPECT_FALSE(ahead.empty());
  EXPECT_EQ(ahead, not_ahead);
  EXPECT_EQ(run("--rate 60"), ahead);
  EXPECT_EQ(run("--rate 60 --no-run-ahead"), ahead);
  // Only detector modes have a detection thread to run ahead.
  DepotResult orb = depot("slam run " + d + " -o " + temp_path("t") + ".txt --mode orb+lk -q " +
                          "--no-run-ahead");
  EXPECT_NE(orb.code, 0);
  EXPECT_NE(orb.output.find("--no-run-ahead: has no effect in --mode orb+lk"), std::string::npos)
      << orb.output;
}

}  // namespace
}  // namespace depot::test
