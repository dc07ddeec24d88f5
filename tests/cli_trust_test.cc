// What a new user met on a fresh clone (issue 30), each through the real
// `depot` program: outputs that are one file, clouds assimp would pad,
// interrupted work, dense maps in every mode, percentiles of nothing and
// localisation in a foreign map. Every refusal is one error line, before any
// work, and leaves what was there as it was.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/cli_checks.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace depot::test {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

const std::string& tiny_static() {
  static const std::string d = render_small({"depot_static", 6, 64, false});
  return d;
}

// A binary PLY cloud of `n` points along a line (what write_ply writes).
std::string binary_cloud(size_t n) {
  std::string bytes = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(n) +
                      "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  for (size_t i = 0; i < n; ++i)
    for (float v : {0.001f * i, 1.0f, 2.0f})
      bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
  return bytes;
}

// Item 1: two outputs, or an output and an input, that are one file.
TEST(OneFileOneOutput, CollidingPathsAreAUsageErrorAndTouchNothing) {
  const std::string dir = temp_path("collide");
  fs::create_directories(dir + "/real");
  fs::create_directory_symlink(dir + "/real", dir + "/link");
  const std::string mine = "a user's file";
  for (const char* name : {"a.txt", "c.txt", "e.txt", "g.txt", "real/t.txt", "h1.txt"})
    write_text(dir + "/" + name, mine);
  fs::create_hard_link(dir + "/h1.txt", dir + "/h2.txt");
  const std::string run = "slam run " + tiny_static() + " -q ";
  const struct {
    std::string args;
    std::string needle;
  } cases[] = {
      {run + "-o " + dir + "/a.txt --save-map " + dir + "/a.txt",
       "--save-map: is the same file as -o"},
      {run + "--mode full -o " + dir + "/t1.txt --save-map " + dir + "/b.bin --dense-map " + dir +
           "/b.bin",
       "--save-map: is the same file as --dense-map"},
      {run + "-o " + dir + "/c.txt --save-map " + dir + "/c.states.txt",
       "--save-map: is the same file as the states file of -o"},
      {run + "--mode full --keypoints " + dir + "/e.txt -o " + dir + "/e.txt",
       "--keypoints: is the same file as -o"},
      {run + "--stats " + dir + "/g.txt -o " + dir + "/g.txt", "--stats: is the same file as -o"},
      {run + "-o " + dir + "/real/t.txt --stats " + dir + "/link/t.txt",
       "--stats: is the same file as -o"},
      {run + "-o " + dir + "/h1.txt --stats " + dir + "/h2.txt", "--stats: is the same file as -o"},
      {run + "--mode full -o " + dir + "/t2.txt --overlays " + dir + "/ov --stats " + dir +
           "/ov/s.csv",
       "lies inside the folder --overlays writes"},
      {run + "-o " + tiny_static() + "/rgb.txt --frames 2",
       "-o: would write over " + tiny_static() + "/rgb.txt, a file of the dataset it reads"},
      {"eval ate " + dir + "/a.txt " + dir + "/c.txt --json " + dir + "/a.txt",
       "--json: would write over the file GT reads"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    expect_one_error_line(depot(c.args), c.needle, 2);
  }
  for (const char* name : {"a.txt", "c.txt", "e.txt", "g.txt", "real/t.txt", "h1.txt"})
    EXPECT_EQ(read_text(dir + "/" + name), mine) << name;
  for (const char* name : {"t1.txt", "t2.txt", "b.bin", "c.states.txt", "a.states.txt", "ov"})
    EXPECT_FALSE(fs::exists(dir + "/" + name)) << name;
  EXPECT_THAT(read_text(tiny_static() + "/rgb.txt"), HasSubstr("rgb/"));
}

// Item 2: assimp pads a cut cloud with zeros; our own check refuses it.
TEST(CloudsAreChecked, ACutOrShortPlyIsOneErrorLine) {
  const std::string dir = temp_path("clouds");
  fs::create_directories(dir);
  const std::string eval = " --dataset " + tiny_static() + " --trajectory " + tiny_static() +
                           "/groundtruth.txt -q --json " + dir + "/score.json";
  write_text(dir + "/cut.ply", binary_cloud(1000).substr(0, 3000));
  expect_one_error_line(depot("eval cloud " + dir + "/cut.ply" + eval),
                        "cut.ply: is shorter than its header declares: element 'vertex' ends at "
                        "row 240 of 1000",
                        1);
  write_text(dir + "/rows.ply",
             "ply\nformat ascii 1.0\nelement vertex 100\nproperty float x\nproperty float y\n"
             "property float z\nend_header\n0 1 2\n1 1 2\n");
  expect_one_error_line(depot("eval cloud " + dir + "/rows.ply" + eval),
                        "rows.ply: is shorter than its header declares: element 'vertex' ends at "
                        "row 2 of 100",
                        1);
  // Item 14: --static must be a static render of the dataset, not the dataset.
  write_text(dir + "/whole.ply", binary_cloud(1000));
  expect_one_error_line(
      depot("eval cloud " + dir + "/whole.ply" + eval + " --static " + tiny_static()),
      "is not a static render of " + tiny_static() + ": its dynamic_load is 1", 1);
  EXPECT_FALSE(fs::exists(dir + "/score.json"));
}

// Item 8: work stopped by Ctrl-C exits 130 and leaves no output.
TEST(ExitCodes, AnInterruptedRenderExits130) {
  const std::string out = temp_path("interrupted");
  std::string printed;
  const int code =
      run_command(depot_binary() + " sim render depot_static --frames 400 --width 64 -q -o " + out +
                      " 2>&1 & pid=$!; for i in $(seq 1200); do ls -d " + out +
                      ".partial-*/rgb/*.png >/dev/null " +
                      "2>&1 && break; sleep 0.1; done; kill -INT $pid; wait $pid",
                  &printed);
  EXPECT_EQ(code, 130) << printed;
  EXPECT_THAT(printed, HasSubstr("interrupted"));
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(fs::path(out).parent_path()))
    EXPECT_THAT(e.path().string(), ::testing::Not(StartsWith(out + ".partial-")));
}

// Item 9: plain orb's dense map keeps every pixel by default (it has no
// masks) and says so; asking for its masks is a usage error.
TEST(DenseMaps, TheDefaultMaskFollowsTheMode) {
  const std::string data = render_small({"depot_static", 30, 160, false});
  const std::string out = temp_path("orb-dense");
  const DepotResult r = depot("slam run " + data + " --mapping sync -o " + out +
                              ".txt --dense-map " + out + ".ply --dense-min-views 1");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("mode orb rejects nothing, so the dense map keeps every pixel"));
  EXPECT_THAT(r.output, HasSubstr("(masks: none)"));
  EXPECT_GT(fs::file_size(out + ".ply"), 200u);
  expect_one_error_line(depot("slam run " + data + " -q -o " + out + "2.txt --dense-map " + out +
                              "2.ply --dense-mask rejection"),
                        "--dense-mask rejection: mode orb leaves no moving mask", 2);
  EXPECT_FALSE(fs::exists(out + "2.ply"));
}

// Item 14: frames without people have no IoU percentiles to print.
TEST(Segmenter, FramesWithoutPeoplePrintNoPercentiles) {
  const DepotResult r = depot("eval segmenter " + tiny_static() + " -q");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("over 0 frames with people (median -, p10 -, p90 -)"));
}

// Item 12: a map of another place: no frame relocalises, and the error says so.
TEST(Localisation, AForeignMapSaysNoFrameRelocalised) {
  const std::string map = temp_path("static") + ".map";
  const std::string data = render_small({"depot_static", 30, 160, false});
  ASSERT_EQ(depot("slam run " + data + " --mapping sync -q -o " + temp_path("m") +
                  ".txt --save-map " + map)
                .code,
            0);
  SmallRender away("depot_static", 10, 160, false);
  away.set = {{"motion.look_at", "[0.0, -4.5, 0.9]"}};
  const std::string elsewhere = render_small(away);
  const std::string out = temp_path("foreign") + ".txt";
  expect_one_error_line(
      depot("slam run " + elsewhere + " -q -o " + out + " --load-map " + map + " --localise-only"),
      "no frame relocalised in the loaded map " + map, 1);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace depot::test
