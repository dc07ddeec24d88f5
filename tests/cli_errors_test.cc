// Bad invocations of every subcommand: each gives exactly one line
// "depot: error: <command>: <problem>" on the output and exit code 2 (a
// command-line error), before any work; --help and --version exit 0.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace fs = std::filesystem;

namespace depot::test {
namespace {

struct BadInvocation {
  std::string args;     // after "depot"
  std::string command;  // the command the error line names
  std::string needle;   // a word of the problem
};

std::ostream& operator<<(std::ostream& out, const BadInvocation& b) {
  return out << b.args;
}

class BadFlags : public ::testing::TestWithParam<BadInvocation> {};

TEST_P(BadFlags, OneErrorLineAndUsageExitCode) {
  const BadInvocation& b = GetParam();
  const DepotResult r = depot(b.args);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  const std::string prefix = "depot: error: " + b.command + (b.command.empty() ? "" : ": ");
  EXPECT_EQ(r.output.rfind(prefix, 0), 0u) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr(b.needle)) << r.output;
}

const std::vector<BadInvocation> kBadInvocations = {
    {"", "", "subcommand"},
    {"fly", "", "fly"},
    {"sim", "sim", "subcommand"},
    {"sim render", "sim render", "scenario"},
    {"sim render depot_static", "sim render", "--output"},
    {"sim render depot_static -o x --width 0", "sim render", "--width"},
    {"sim render depot_static -o x --width abc", "sim render", "--width"},
    {"sim render depot_static -o x --frames -3", "sim render", "--frames"},
    {"sim render depot_static -o x --load 9", "sim render", "--load"},
    {"sim render depot_static -o x --gl vulkan", "sim render", "--gl"},
    {"sim render depot_static -o x --png-level 12", "sim render", "--png-level"},
    {"sim render depot_static -o x --writers 0", "sim render", "--writers"},
    {"sim render depot_static -o x --no-such-flag", "sim render", "--no-such-flag"},
    {"sim truth depot_static", "sim truth", "--output"},
    {"sim truth depot_static -o x --frames 0", "sim truth", "--frames"},
    {"sim preview", "sim preview", "dataset"},
    {"sim preview data -o p.png --rows 0", "sim preview", "--rows"},
    {"sim list extra", "sim list", "extra"},
    {"slam", "slam", "subcommand"},
    {"slam run", "slam run", "dataset"},
    {"slam run data", "slam run", "--output"},
    {"slam run data -o t.txt --mode fancy", "slam run", "--mode"},
    {"slam run data -o t.txt --frames 0", "slam run", "--frames"},
    {"slam run data -o t.txt --mapping later", "slam run", "--mapping"},
    {"slam run data -o t.txt --background-margin -1", "slam run", "--background-margin"},
    // Found by a new user (issue 30): command-line mistakes that exited 1
    // after starting the work.
    {"slam run data -o t.txt --localise-only", "slam run", "--localise-only: needs a map"},
    {"slam run data -o t.txt --system x --mode full", "slam run",
     "--mode: has no effect with --system"},
    {"slam run data -o t.txt --keypoints k.csv", "slam run",
     "--keypoints: has no effect in --mode orb"},
    {"slam run data -o t.txt --dense-map d.ply --dense-voxel nan", "slam run",
     "--dense-voxel: 'nan' is not a finite number"},
    {"eval ate gt.txt est.txt --offset inf", "eval ate", "--offset: 'inf' is not a finite number"},
    {"slam run data -o t.txt --mode full --detector-set bogus=1", "slam run", "bogus"},
    {"slam run data -o t.txt --mode full --detector darknet --detector-set miss_rate=0.1",
     "slam run", "--detector-set: applies to the simulated detector only"},
    {"slam run data -o t.txt --dense-map d.ply --dense-mask rejection", "slam run",
     "--dense-mask rejection: mode orb leaves no moving mask"},
    {"slam run data -o t.txt --load-map m.map --localise-only --dense-map d.ply", "slam run",
     "--dense-map: has nothing to fuse with --localise-only"},
    {"slam run data -o a.txt --save-map a.txt", "slam run", "--save-map: is the same file as -o"},
    {"slam run data -o c.txt --save-map c.states.txt", "slam run",
     "--save-map: is the same file as the states file of -o (c.states.txt)"},
    {"slam run data -o g.txt --stats g.txt", "slam run", "--stats: is the same file as -o"},
    {"slam run data -o t.txt --mode full --save-map b.bin --dense-map b.bin", "slam run",
     "--save-map: is the same file as --dense-map"},
    {"slam vocabulary train -o v.voc", "slam vocabulary train", "give --images or --dataset"},
    {"eval ate gt.txt est.txt --json gt.txt", "eval ate",
     "--json: would write over the file GT reads"},
    {"eval ate gt.txt est.txt --json r.json --plot r.json", "eval ate",
     "--plot: is the same file as --json"},
    {"eval detector", "eval detector", "give a DATASET, --images LABELS.yaml, or both"},
    {"eval segmenter", "eval segmenter", "give a DATASET, --images LABELS.yaml, or both"},
    {"eval", "eval", "subcommand"},
    {"eval ate gt.txt", "eval ate", "EST"},
    {"eval ate gt.txt est.txt --max-dt 0", "eval ate", "--max-dt"},
    {"eval ate gt.txt est.txt --baseline-rmse -2", "eval ate", "--baseline-rmse"},
    {"eval rpe gt.txt est.txt --delta-unit m", "eval rpe", "--delta-unit"},
    {"eval rpe gt.txt est.txt --delta nan", "eval rpe", "--delta"},
    {"eval rejection data", "eval rejection", "KEYPOINTS"},
    {"eval rejection data k.csv --scale-factor 3", "eval rejection", "--scale-factor"},
    {"eval calibrate", "eval calibrate", "DATASET"},
    {"eval calibrate data", "eval calibrate", "--output"},
    {"eval calibrate data -o s.yaml --every 0", "eval calibrate", "--every"},
    {"eval calibrate data -o s.yaml --detector yolo9", "eval calibrate", "yolo9"},
    {"sweep", "sweep", "subcommand"},
    {"sweep run depot_static", "sweep run", "--output"},
    {"sweep run depot_static -o s --modes orb,magic", "sweep run", "magic"},
    {"sweep run depot_static -o s --seeds 0", "sweep run", "--seeds"},
    {"sweep run depot_static -o s --frames 5", "sweep run", "--frames"},
    {"sweep run depot_static -o s --width 8", "sweep run", "--width"},
    {"sweep run depot_static -o s -j 0", "sweep run", "--workers"},
    {"sweep run depot_static -o s --mapping maybe", "sweep run", "--mapping"},
    {"sweep resume", "sweep resume", "folder"},
    {"sweep job s", "sweep job", "id"},
    {"sweep report", "sweep report", "folder"},
};

INSTANTIATE_TEST_SUITE_P(EverySubcommand, BadFlags, ::testing::ValuesIn(kBadInvocations));

TEST(CliHelp, HelpAndVersionExitZero) {
  const DepotResult version = depot("--version");
  EXPECT_EQ(version.code, 0) << version.output;
  EXPECT_EQ(version.output.rfind("depot ", 0), 0u) << version.output;
  EXPECT_NE(version.output.find("(git "), std::string::npos) << version.output;
  EXPECT_THAT(version.output, ::testing::Not(::testing::HasSubstr("(git unknown)")))
      << version.output;
  EXPECT_EQ(depot("sim render --help").code, 0);
}

// Defaults are shown, so a user sees e.g. that --mode orb means no rejection.
TEST(CliHelp, ShowsDefaults) {
  const DepotResult slam = depot("slam run --help");
  ASSERT_EQ(slam.code, 0);
  for (const char* shown : {"}=orb\n", "}=threaded\n"})
    EXPECT_THAT(slam.output, ::testing::HasSubstr(shown)) << shown << "\n" << slam.output;
  const DepotResult sweep = depot("sweep run --help");
  ASSERT_EQ(sweep.code, 0);
  for (const char* shown : {"1000]=3\n", "100000]=300\n", "4096]=640\n", "256]=1\n", "}=sync\n"})
    EXPECT_THAT(sweep.output, ::testing::HasSubstr(shown)) << shown << "\n" << sweep.output;
  const DepotResult preview = depot("sim preview --help");
  EXPECT_NE(preview.output.find("50]=4\n"), std::string::npos) << preview.output;
  const DepotResult render = depot("sim render --help");
  EXPECT_NE(render.output.find("32]=2\n"), std::string::npos) << render.output;  // --writers
  EXPECT_NE(render.output.find("}=osmesa\n"), std::string::npos) << render.output;
}

}  // namespace
}  // namespace depot::test
