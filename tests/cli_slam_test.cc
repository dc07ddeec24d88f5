// `depot slam run` and `depot eval` on bad input: one clear error line, a
// non-zero exit, and no trajectory written.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include <assimp/scene.h>
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Geometry>
#include <assimp/Importer.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/tum_io.h"
#include "tests/support/cli_checks.h"
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

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void expect_error(const std::string& dataset, const std::string& needle) {
  const std::string out = temp_path("traj") + ".txt";
  DepotResult r = depot("slam run " + dataset + " -o " + out + " -q");
  expect_one_error_line(r, needle);
  EXPECT_FALSE(fs::exists(out)) << "no trajectory on failure";
  EXPECT_FALSE(fs::exists(out.substr(0, out.size() - 4) + ".states.txt")) << "no states either";
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
  EXPECT_NE(r.output.find("tracked 30 of 30 frames (100.0 %; 0 lost"), std::string::npos)
      << r.output;
  // Every frame's state beside the trajectory; its tracked frames are the
  // trajectory's.
  const std::string states = out.substr(0, out.size() - 4) + ".states.txt";
  const std::string atlas = out.substr(0, out.size() - 4) + ".atlas.txt";
  EXPECT_NE(r.output.find("wrote " + out + ", " + states + " and " + atlas), std::string::npos)
      << r.output;
  std::ifstream in(states);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("# depot-slam (orb) of ", 0), 0u) << line;
  int frames = 0, tracked = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    ++frames;
    std::istringstream fields(line);
    std::string stamp, state, map;
    fields >> stamp >> state >> map;
    tracked += state == "NEW_MAP" || state == "OK" || state == "RELOCALIZED";
    EXPECT_EQ(map, "0") << "one map: every frame in the trajectory's";
    if (frames == 1) {
      EXPECT_EQ(state, "NEW_MAP");
    }
  }
  EXPECT_EQ(frames, 30);
  EXPECT_EQ(tracked, static_cast<int>(read_tum_trajectory(out).size()));
  EXPECT_EQ(read_tum_trajectory(atlas).size(), read_tum_trajectory(out).size());
  DepotResult ate = depot("eval ate " + d + "/groundtruth.txt " + out);
  EXPECT_EQ(ate.code, 0) << ate.output;
  EXPECT_THAT(ate.output, ::testing::HasSubstr("rmse"));
  EXPECT_NE(ate.output.find("tracked share  100.0 % (30 of 30 frames given; states " + states),
            std::string::npos)
      << ate.output;
  EXPECT_THAT(ate.output, ::testing::HasSubstr("all maps       rmse ")) << ate.output;
  EXPECT_NE(ate.output.find("over the 30 frames with a pose in any of 1 maps (100.0 % of those "
                            "given), each map aligned on its own; the trajectory's map holds "
                            "100.0 %"),
            std::string::npos)
      << ate.output;
}

TEST(CliSlam, AteReportsTheTrackedShareOfAStatesFile) {
  std::string d = render_small({"depot_static", 8, 320, false});
  const std::string out = temp_path("traj") + ".txt";
  ASSERT_EQ(depot("slam run " + d + " -o " + out + " --mapping sync -q").code, 0);
  // Two frames given that never got a pose (e.g. before initialisation).
  const std::string states = temp_path("states") + ".txt";
  std::ofstream(states) << "# made up\n0.001 NOT_INITIALIZED\n0.002 LOST\n"
                        << read_text(out.substr(0, out.size() - 4) + ".states.txt");
  const std::string json = temp_path("ate") + ".json";
  DepotResult ate = depot("eval ate " + d + "/groundtruth.txt " + out + " --states " + states +
                          " --json " + json);
  ASSERT_EQ(ate.code, 0) << ate.output;
  EXPECT_NE(ate.output.find("tracked share  80.0 % (8 of 10 frames given"), std::string::npos)
      << ate.output;
  const std::string report = read_text(json);
  EXPECT_THAT(report, ::testing::HasSubstr("\"tracked_share\": 0.8")) << report;
  expect_one_error_line(
      depot("eval ate " + d + "/groundtruth.txt " + out + " --states " + d + "/groundtruth.txt"),
      "expected 2 or 3 fields (timestamp state [map])");
}

// The atlas: frames of a map that never joined the trajectory's are scored
// too, their map aligned on its own (eval/maps_ate.h). Made-up files: map 0
// holds frames 0-4, map 1 frames 6-8 in a frame turned and moved.
TEST(CliSlam, AteScoresTheFramesOfEveryMapOfTheAtlas) {
  const std::string dir = temp_path("atlas_eval");
  fs::create_directories(dir);
  std::ofstream gt(dir + "/gt.txt"), run(dir + "/run.txt"), states(dir + "/run.states.txt"),
      atlas(dir + "/run.atlas.txt");
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.8, Eigen::Vector3d(0.2, 1, 0).normalized()));
  for (int k = 0; k < 10; ++k) {
    const double t = 1.0 + 0.1 * k;
    const Eigen::Vector3d p(std::cos(0.5 * k), std::sin(0.5 * k), 0.1 * k);
    const std::string line =
        fmt::format("{:.6f} {:.9f} {:.9f} {:.9f} 0 0 0 1\n", t, p.x(), p.y(), p.z());
    gt << line;
    if (k < 5) {
      run << line;
      atlas << line;
      states << fmt::format("{:.6f} {} 0\n", t, k ? "OK" : "NEW_MAP");
    } else if (k >= 6 && k <= 8) {
      const Eigen::Vector3d q = turn * p + Eigen::Vector3d(3, -1, 2);
      const Eigen::Quaterniond r = turn;
      atlas << fmt::format("{:.6f} {:.9f} {:.9f} {:.9f} {:.9f} {:.9f} {:.9f} {:.9f}\n", t, q.x(),
                           q.y(), q.z(), r.x(), r.y(), r.z(), r.w());
      states << fmt::format("{:.6f} OTHER_MAP 1\n", t);
    } else {
      states << fmt::format("{:.6f} LOST\n", t);
    }
  }
  gt.close(), run.close(), states.close(), atlas.close();
  const std::string json = dir + "/ate.json";
  DepotResult ate = depot("eval ate " + dir + "/gt.txt " + dir + "/run.txt --json " + json);
  ASSERT_EQ(ate.code, 0) << ate.output;
  EXPECT_NE(ate.output.find("tracked share  50.0 % (5 of 10 frames given"), std::string::npos)
      << ate.output;
  EXPECT_NE(ate.output.find("all maps       rmse 0.000000 m over the 8 frames with a pose in any "
                            "of 2 maps (80.0 % of those given), each map aligned on its own; the "
                            "trajectory's map holds 50.0 %"),
            std::string::npos)
      << ate.output;
  EXPECT_THAT(read_text(json), ::testing::HasSubstr("\"posed_share\": 0.8")) << read_text(json);
  // An atlas trajectory of another run: said, and left out.
  std::ofstream(dir + "/run.atlas.txt") << "1.0 0 0 0 0 0 0 1\n";
  ate = depot("eval ate " + dir + "/gt.txt " + dir + "/run.txt");
  ASSERT_EQ(ate.code, 0) << ate.output;
  EXPECT_NE(ate.output.find("holds 1 poses but " + dir + "/run.states.txt names 8 frames"),
            std::string::npos)
      << ate.output;
  EXPECT_THAT(ate.output, ::testing::Not(::testing::HasSubstr("all maps       rmse")))
      << ate.output;
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
    EXPECT_GT(instance, 0) << line;            // every pixel belongs to some instance
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
  EXPECT_THAT(orb.output, ::testing::HasSubstr("has no effect in --mode orb")) << orb.output;
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
  EXPECT_THAT(orb.output, ::testing::HasSubstr("--no-run-ahead: has no effect in --mode orb+lk"))
      << orb.output;
}

TEST(CliSlam, MaskedModeScoresBothWaysAndDrawsPictures) {
  std::string d = render_small({"depot_walking_xyz", 20, 640, false});
  const std::string out = temp_path("traj") + ".txt", pictures = temp_path("pictures");
  DepotResult r = depot("slam run " + d + " -o " + out + " --mode masked --mapping sync -q " +
                        "--overlays " + pictures + " --overlays-every 5");
  ASSERT_EQ(r.code, 0) << r.output;
  double precision = 0, recall = 0, precision_static = 0;
  const size_t at = r.output.find("rejection vs ground truth: ");
  ASSERT_NE(at, std::string::npos) << r.output;
  ASSERT_EQ(std::sscanf(r.output.c_str() + at,
                        "rejection vs ground truth: precision %lf recall %lf with boundary points "
                        "left out; precision %lf",
                        &precision, &recall, &precision_static),
            3)
      << r.output;
  EXPECT_GT(precision, 0.8) << r.output;  // people segmented from depth inside their boxes
  EXPECT_GT(recall, 0.8) << r.output;
  EXPECT_LE(precision_static, precision);  // boundary points counted as static only lower it
  // Pictures of frames 0, 5, 10, 15 and their index.
  for (const char* f : {"000000", "000005", "000010", "000015"})
    EXPECT_TRUE(fs::is_regular_file(pictures + "/frames/" + f + ".png")) << f;
  EXPECT_FALSE(fs::exists(pictures + "/frames/000001.png"));
  std::ifstream index(pictures + "/index.txt");
  const std::string text(std::istreambuf_iterator<char>(index), {});
  EXPECT_THAT(text, ::testing::HasSubstr("15 ")) << text;
  const cv::Mat picture = cv::imread(pictures + "/frames/000010.png");
  EXPECT_EQ(picture.cols, 640);

  // A folder holding a user's file is never written into; options of other
  // modes or sources are refused.
  const std::string mine = temp_path("mine");
  fs::create_directories(mine);
  std::ofstream(mine + "/notes.txt") << "mine";
  DepotResult refused =
      depot("slam run " + d + " -o " + temp_path("t") + ".txt --mode masked -q --overlays " + mine);
  EXPECT_NE(refused.code, 0);
  EXPECT_TRUE(fs::is_regular_file(mine + "/notes.txt"));
  DepotResult full =
      depot("slam run " + d + " -o " + temp_path("t") + ".txt --mode full -q --person-mask both");
  EXPECT_THAT(full.output, ::testing::HasSubstr("--person-mask: has no effect in --mode full"))
      << full.output;
  DepotResult seg = depot("slam run " + d + " -o " + temp_path("t") +
                          ".txt --mode masked -q --segmenter scenes/segmenters/selfie.yaml");
  EXPECT_NE(seg.output.find("--segmenter: has no effect with --person-mask depth"),
            std::string::npos)
      << seg.output;
  DepotResult key = depot("slam run " + d + " -o " + temp_path("t") +
                          ".txt --mode masked -q --rejection-set mask.nonsense=1");
  EXPECT_NE(key.code, 0);
  EXPECT_THAT(key.output, ::testing::HasSubstr("unknown rejection setting 'mask.nonsense'"))
      << key.output;
}

}  // namespace
}  // namespace depot::test

namespace depot::test {
namespace {

// `--vocabulary` on bad files, and `depot slam vocabulary train|info`.
void expect_vocabulary_error(const std::string& vocabulary, const std::string& needle) {
  const std::string dataset = render_small({"depot_static", 6, 160, false});
  const std::string out = temp_path("traj") + ".txt";
  DepotResult r = depot("slam run " + dataset + " -o " + out + " -q --vocabulary " + vocabulary);
  EXPECT_NE(r.code, 0) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_EQ(r.output.rfind("depot: error: " + vocabulary, 0), 0u) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr(needle)) << r.output;
  EXPECT_FALSE(fs::exists(out)) << "no trajectory on failure";
}

std::string default_vocabulary_bytes() {
  std::ifstream in(std::string(DEPOT_BINARY_DIR) + "/vocabulary/depot_orb.voc", std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(CliSlam, BadVocabularyFilesAreOneErrorLine) {
  const std::string bytes = default_vocabulary_bytes();
  ASSERT_GT(bytes.size(), 1000u) << "the build trains the default vocabulary";
  expect_vocabulary_error(temp_path("missing") + ".voc", "no such vocabulary file");
  const std::string truncated = temp_path("truncated") + ".voc";
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() - 100);
  expect_vocabulary_error(truncated, "truncated");
  std::string wide_bytes = bytes;
  wide_bytes[12] = 64;  // descriptor bytes: ORB-SLAM2's are 32, other binary features 64
  const std::string wide = temp_path("wide") + ".voc";
  std::ofstream(wide, std::ios::binary) << wide_bytes;
  expect_vocabulary_error(wide, "64-byte descriptors");
}

TEST(CliSlam, TrainsAndDescribesAVocabulary) {
  const std::string dataset = render_small({"depot_static", 6, 160, false});
  const std::string voc = temp_path("trained") + ".voc";
  DepotResult r =
      depot("slam vocabulary train -o " + voc + " --images " + std::string(DEPOT_SHARED_DATA) +
            "/photos --dataset " + dataset + " --dataset-every 2 --branching 6 --levels 3 -q");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("words (k 6, 3 levels)")) << r.output;
  DepotResult info = depot("slam vocabulary info " + voc);
  ASSERT_EQ(info.code, 0) << info.output;
  EXPECT_NE(info.output.find("branching 6, 3 levels"), std::string::npos) << info.output;
  // The same inputs give the same file.
  const std::string again = temp_path("again") + ".voc";
  ASSERT_EQ(
      depot("slam vocabulary train -o " + again + " --images " + std::string(DEPOT_SHARED_DATA) +
            "/photos --dataset " + dataset + " --dataset-every 2 --branching 6 --levels 3 -q")
          .code,
      0);
  std::ifstream a(voc, std::ios::binary), b(again, std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}),
            std::string(std::istreambuf_iterator<char>(b), {}));
  // A folder without images fails before anything is written.
  const std::string empty_dir = temp_path("no_images");
  fs::create_directories(empty_dir);
  const std::string none = temp_path("none") + ".voc";
  DepotResult bad = depot("slam vocabulary train -o " + none + " --images " + empty_dir + " -q");
  EXPECT_NE(bad.code, 0);
  EXPECT_THAT(bad.output, ::testing::HasSubstr("holds no .png/.jpg/.bmp images")) << bad.output;
  EXPECT_FALSE(fs::exists(none));
}

// Map reuse through the program: --save-map, then --load-map
// --localise-only adds no keyframe; bad maps and flags are one error line
// with nothing written.
TEST(CliSlam, SavesAMapAndLocalisesInIt) {
  const std::string dataset = render_small({"depot_static", 40, 160, false});
  const std::string map = temp_path("depot") + ".map";
  DepotResult save = depot("slam run " + dataset + " --mapping sync -q -o " + temp_path("a") +
                           ".txt --save-map " + map);
  ASSERT_EQ(save.code, 0) << save.output;
  ASSERT_TRUE(fs::exists(map));
  const std::string out = temp_path("localised") + ".txt";
  DepotResult again = depot("slam run " + dataset + " --mapping sync -q -o " + out +
                            " --load-map " + map + " --localise-only");
  ASSERT_EQ(again.code, 0) << again.output;
  // The same number of keyframes before and after: "in mode orb: N keyframes".
  auto keyframes = [](const std::string& text) {
    const size_t at = text.find(" keyframes,");
    const size_t from = text.rfind(' ', at - 1);
    return text.substr(from + 1, at - from - 1);
  };
  EXPECT_EQ(keyframes(again.output), keyframes(save.output)) << again.output;
  EXPECT_TRUE(fs::exists(out));

  // The map's points as PLY, read back by assimp (a library the simulator
  // uses): as many points as the map has, each observed at least twice.
  DepotResult info = depot("slam map info " + map);
  ASSERT_EQ(info.code, 0) << info.output;
  EXPECT_NE(info.output.find(": map format 3, "), std::string::npos) << info.output;
  EXPECT_NE(info.output.find(" in 1 map of the atlas, camera "), std::string::npos) << info.output;
  const std::string ply = temp_path("points") + ".ply";
  DepotResult exported = depot("slam map export " + map + " -o " + ply);
  ASSERT_EQ(exported.code, 0) << exported.output;
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(ply, 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const size_t at = info.output.find(" map points");
  const std::string n_points = info.output.substr(info.output.rfind(' ', at - 1) + 1,
                                                  at - info.output.rfind(' ', at - 1) - 1);
  EXPECT_EQ(std::to_string(scene->mMeshes[0]->mNumVertices), n_points) << info.output;
  EXPECT_TRUE(scene->mMeshes[0]->HasVertexColors(0));
  std::string damaged = read_text(map);
  damaged[damaged.size() / 3] ^= 4;
  const std::string damaged_map = temp_path("damaged") + ".map";
  std::ofstream(damaged_map, std::ios::binary) << damaged;
  expect_one_error_line(depot("slam map export " + damaged_map + " -o " + ply + ".x"),
                        "checksum mismatch");
  EXPECT_FALSE(fs::exists(ply + ".x"));

  const std::string never = temp_path("never") + ".txt";
  auto expect_map_error = [&](const std::string& flags, const std::string& needle) {
    DepotResult r = depot("slam run " + dataset + " -q -o " + never + " " + flags);
    expect_one_error_line(r, needle);
    EXPECT_FALSE(fs::exists(never)) << "no trajectory on failure";
  };
  expect_map_error("--localise-only", "needs a map to localise in (--load-map M)");
  expect_map_error("--load-map " + temp_path("missing") + ".map", "no such map file");
  const std::string bytes = read_text(map);
  const std::string corrupt = temp_path("corrupt") + ".map";
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 1;
  std::ofstream(corrupt, std::ios::binary) << flipped;
  expect_map_error("--load-map " + corrupt, "checksum mismatch");
  const std::string truncated = temp_path("truncated") + ".map";
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() - 1000);
  expect_map_error("--load-map " + truncated, "checksum mismatch");
  const std::string other_size = render_small({"depot_static", 6, 320, false});
  DepotResult camera = depot("slam run " + other_size + " -q -o " + never + " --load-map " + map);
  expect_one_error_line(camera, "another camera");
  expect_map_error("--save-map /nonexistent-folder/depot.map", "/nonexistent-folder");
}

}  // namespace
}  // namespace depot::test

namespace depot::test {
namespace {

// The dense static map of a walking scene from `full`, scored against the
// simulator's truth: with the rejection's masks few points lie on the
// movers, the same fusion without masks many more, the truth's labels as
// masks hardly any. Measured at 320x240, 120 frames: 1.9 %, 12.0 %, 0.03 %
// before the atlas; 0.70 %, 7.8 %, 0.03 % with it (the main map's keyframes).
TEST(CliSlam, DenseStaticMapLeavesTheMoversOut) {
  const std::string dataset = render_small({"depot_walking_xyz", 120, 320, false});
  SmallRender static_request{"depot_walking_xyz", 120, 320, true};
  static_request.set = {{"dynamic_load", "0"}};
  const std::string scene = render_small(static_request);
  const std::string trajectory = temp_path("dense") + ".txt";
  const std::string run = "slam run " + dataset + " --mode full --mapping sync -q -o " + trajectory;
  auto fuse = [&](const std::string& mask) {
    const std::string cloud = temp_path(mask) + ".ply";
    DepotResult r = depot(run + " --dense-map " + cloud + " --dense-mask " + mask);
    EXPECT_EQ(r.code, 0) << r.output;
    return cloud;
  };
  auto score = [&](const std::string& cloud) {
    const std::string json = cloud + ".json";
    DepotResult r = depot("eval cloud " + cloud + " --dataset " + dataset + " --trajectory " +
                          trajectory + " --static " + scene + " -q --json " + json);
    EXPECT_EQ(r.code, 0) << r.output;
    std::printf("%s", r.output.c_str());
    return read_text(json);
  };
  auto number = [](const std::string& json, const std::string& key) {
    const size_t at = json.find("\"" + key + "\":");
    EXPECT_NE(at, std::string::npos) << key;
    return std::stod(json.substr(json.find(':', at) + 1));
  };
  const std::string masked = fuse("rejection");
  const std::string masked_score = score(masked), unmasked_score = score(fuse("none")),
                    labels_score = score(fuse("labels"));
  const double masked_share = number(masked_score, "on_moving_share");
  const double unmasked_share = number(unmasked_score, "on_moving_share");
  EXPECT_LT(masked_share, 0.04) << masked_score;
  EXPECT_GT(unmasked_share, 0.05) << unmasked_score;
  EXPECT_LT(masked_share, 0.3 * unmasked_share);
  EXPECT_LT(number(labels_score, "on_moving_share"), 0.005) << labels_score;
  EXPECT_LT(number(masked_score, "median_m"), 0.02) << masked_score;
  Assimp::Importer importer;
  const aiScene* cloud = importer.ReadFile(masked, 0);
  ASSERT_NE(cloud, nullptr) << importer.GetErrorString();
  EXPECT_EQ(static_cast<double>(cloud->mMeshes[0]->mNumVertices), number(masked_score, "points"));
  EXPECT_TRUE(cloud->mMeshes[0]->HasVertexColors(0));

  // Bad input: one error line, nothing written.
  const std::string none = temp_path("none") + ".ply";
  expect_one_error_line(depot("slam run " + dataset + " -q -o " + temp_path("o") +
                              ".txt --dense-mask rejection --dense-map " + none),
                        "--dense-mask rejection: mode orb leaves no moving mask");
  expect_one_error_line(
      depot("slam run " + dataset + " -q -o " + temp_path("o") + ".txt --dense-voxel 0.05"),
      "--dense-voxel: has no effect without --dense-map");
  expect_one_error_line(depot("slam run " + dataset + " -q -o " + temp_path("o") +
                              ".txt --dense-map " + temp_path("missing") + "/x.ply"),
                        "x.ply");
  EXPECT_FALSE(fs::exists(none));
  const std::string not_a_cloud = temp_path("notacloud") + ".ply";
  std::ofstream(not_a_cloud) << "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2\n";
  const std::string json = temp_path("bad") + ".json";
  expect_one_error_line(depot("eval cloud " + not_a_cloud + " --dataset " + dataset +
                              " --trajectory " + trajectory + " --json " + json),
                        not_a_cloud);
  const std::string other = render_small({"depot_static", 20, 320, true});
  expect_one_error_line(depot("eval cloud " + masked + " --dataset " + dataset + " --trajectory " +
                              trajectory + " --static " + other + " --json " + json),
                        "is not a static render of");
  EXPECT_FALSE(fs::exists(json));
}

}  // namespace
}  // namespace depot::test
