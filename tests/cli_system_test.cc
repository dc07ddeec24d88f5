// Other SLAM systems under test (`depot slam run --system`, sweeps'
// `system:NAME`): the project's own masked mode wrapped as another program
// gives exactly the built-in figures (TUM and EuRoC trajectories); Open3D's
// odometry, the shipped example, runs through the same path; a system that
// fails in any way is one error line and no output, and in a sweep a failed
// run with its reason while the sweep goes on.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace fs = std::filesystem;

namespace depot::test {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The data lines of a trajectory file (comments differ between writers).
std::string poses_of(const std::string& path) {
  std::istringstream in(read_text(path));
  std::string line, out;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') out += line + "\n";
  return out;
}

std::string match(const std::string& text, const std::string& pattern) {
  std::smatch m;
  return std::regex_search(text, m, std::regex(pattern)) ? m.str(1) : "";
}

// 12 frames of walking people at 320x240, rendered once per process.
const std::string& walking() {
  static const std::string d = render_small({"depot_walking_xyz", 12, 320, false});
  return d;
}

std::string ate_rmse(const std::string& dataset, const std::string& trajectory) {
  const DepotResult r = depot("eval ate " + dataset + "/groundtruth.txt " + trajectory);
  EXPECT_EQ(r.code, 0) << r.output;
  return match(r.output, R"(rmse\s+([0-9.]+))");
}

TEST(CliSystem, OwnMaskedModeWrappedAsASystemGivesTheBuiltInFigures) {
  const std::string builtin = temp_path("builtin") + ".txt",
                    wrapped = temp_path("wrapped") + ".txt";
  const std::string builtin_keypoints = temp_path("kb") + ".csv";
  const DepotResult a = depot("slam run " + walking() + " --mode masked --mapping sync -q -o " +
                              builtin + " --keypoints " + builtin_keypoints);
  ASSERT_EQ(a.code, 0) << a.output;
  const std::string keypoints = temp_path("kw") + ".csv";
  const DepotResult b = depot("slam run " + walking() + " --system depot_masked -q -o " + wrapped +
                              " --keypoints " + keypoints);
  ASSERT_EQ(b.code, 0) << b.output;
  EXPECT_EQ(poses_of(wrapped), poses_of(builtin));
  EXPECT_EQ(ate_rmse(walking(), wrapped), ate_rmse(walking(), builtin));
  const std::string scores = "rejection vs ground truth: ([^\n]*)";
  ASSERT_NE(match(a.output, scores), "") << a.output;
  EXPECT_EQ(match(b.output, scores), match(a.output, scores)) << b.output;
  EXPECT_TRUE(read_text(keypoints) == read_text(builtin_keypoints)) << "keypoint files differ";
  // The states beside it and the system's own output.
  EXPECT_TRUE(fs::exists(fs::path(wrapped).replace_extension(".states.txt")));
  EXPECT_TRUE(fs::exists(fs::path(wrapped).replace_extension(".system.log")));

  // The same run written as EuRoC CSV (nanoseconds, qw first) reads back to
  // the same ATE.
  const std::string euroc = write_yaml("euroc", R"(command:
  - /bin/sh
  - -c
  - |
    "$0" slam run "$1" --mode masked --mapping sync -q -o "$2.tum" &&
    awk '!/^#/ { printf "%.0f,%s,%s,%s,%s,%s,%s,%s\n", $1 * 1e9, $2, $3, $4, $8, $5, $6, $7 }' "$2.tum" > "$2"
  - "{depot}"
  - "{dataset}"
  - "{trajectory}"
trajectory_format: euroc
)");
  const std::string from_euroc = temp_path("from_euroc") + ".txt";
  const DepotResult c =
      depot("slam run " + walking() + " --system " + euroc + " -q -o " + from_euroc);
  ASSERT_EQ(c.code, 0) << c.output;
  EXPECT_EQ(ate_rmse(walking(), from_euroc), ate_rmse(walking(), builtin));

  // And as KITTI poses (3x4 matrices) with a timestamps file.
  const std::string kitti = write_yaml("kitti", R"(command:
  - /bin/sh
  - -c
  - |
    "$0" slam run "$1" --mode masked --mapping sync -q -o "$2.tum" &&
    awk '!/^#/ { x = $5; y = $6; z = $7; w = $8;
      printf "%.12f %.12f %.12f %s %.12f %.12f %.12f %s %.12f %.12f %.12f %s\n",
        1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), $2,
        2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), $3,
        2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), $4 }' "$2.tum" > "$2" &&
    awk '!/^#/ { print $1 }' "$2.tum" > "$3"
  - "{depot}"
  - "{dataset}"
  - "{trajectory}"
  - "{timestamps}"
trajectory_format: kitti
)");
  const std::string from_kitti = temp_path("from_kitti") + ".txt";
  const DepotResult k =
      depot("slam run " + walking() + " --system " + kitti + " -q -o " + from_kitti);
  ASSERT_EQ(k.code, 0) << k.output;
  EXPECT_NEAR(std::stod(ate_rmse(walking(), from_kitti)), std::stod(ate_rmse(walking(), builtin)),
              2e-6);
}

TEST(CliSystem, Open3dOdometryRunsAsASystem) {
  const std::string still = render_small({"depot_static", 10, 320, false});
  const std::string out = temp_path("open3d") + ".txt";
  const DepotResult r = depot("slam run " + still + " --system open3d_odometry -q -o " + out);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("tracked 10 of 10 frames")) << r.output;
  const std::string rmse = ate_rmse(still, out);
  ASSERT_NE(rmse, "");
  EXPECT_LT(std::stod(rmse), 0.03) << "Open3D odometry on a static scene, 10 frames";
}

// A system file whose command is a shell script; `script` sees the
// trajectory path as $1 and the first frame's timestamp as $2.
std::string script_system(const std::string& tag, const std::string& script,
                          const std::string& extra = "") {
  return write_yaml(tag, "command: [/bin/sh, -c, '" + script +
                             "', sh, \"{trajectory}\", \"{calibration}\"]\n" + extra);
}

struct Failure {
  std::string name, system, reason;
};

TEST(CliSystem, AFailingSystemIsOneErrorLineAndNoOutput) {
  // The dataset's first two frames, for trajectories that are wrong otherwise.
  std::istringstream rgb(read_text(walking() + "/rgb.txt"));
  std::string line, t0, t1;
  while (std::getline(rgb, line) && t1.empty())
    if (!line.empty() && line[0] != '#') (t0.empty() ? t0 : t1) = line.substr(0, line.find(' '));
  const std::string pose = " 0 0 0 0 0 0 1";
  const std::vector<Failure> failures = {
      {"unknown placeholder",
       write_yaml("placeholder", "command: [/bin/true, \"{trajectory}\", \"{frames}\"]\n"),
       "unknown placeholder '{frames}'"},
      {"command not found", write_yaml("missing", "command: [/no/such/slam, \"{trajectory}\"]\n"),
       "command not started: /no/such/slam: cannot start"},
      {"exits non-zero", script_system("exit3", "echo tracking failed >&2; exit 3"),
       "exited with code 3 (log "},
      {"writes nothing", script_system("nothing", "exit 0"), "wrote no trajectory"},
      {"NaN", script_system("nan", "echo " + t0 + " nan 0 0 0 0 0 1 > \"$1\""), "is not finite"},
      {"unsorted",
       script_system("unsorted", "printf \"" + t1 + pose + "\\n" + t0 + pose + "\\n\" > \"$1\""),
       "timestamps must increase"},
      {"foreign timestamps", script_system("foreign", "echo 12.5" + pose + " > \"$1\""),
       "timestamp 12.500000 is no frame of the dataset"},
      {"past its time limit", script_system("slow", "sleep 31.25", "time_limit_s: 1\n"),
       "stopped at its time limit of 1 s"},
  };
  for (const Failure& f : failures) {
    SCOPED_TRACE(f.name);
    const std::string out = temp_path("failed") + ".txt";
    const DepotResult r =
        depot("slam run " + walking() + " --system " + f.system + " -q -o " + out);
    EXPECT_NE(r.code, 0);
    EXPECT_THAT(r.output, ::testing::HasSubstr(f.reason)) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(fs::path(out).replace_extension(".states.txt")));
  }
  // The slow system's whole process group was stopped: no sleep left behind.
  std::string ps;
  run_command("ps -eo args | grep -c '^sleep 31.25$'", &ps);
  EXPECT_EQ(ps, "0\n") << "a process the system started outlived its time limit";
}

TEST(CliSystem, CtrlCStopsTheSystemAndEverythingItStarted) {
  // The system marks that it runs, so Ctrl-C comes while it does (however
  // slowly depot starts, e.g. under a sanitizer).
  const std::string marker = temp_path("started");
  const std::string slow =
      script_system("ctrl_c", "touch " + marker + "; sleep 32.5 & sleep 32.5; wait");
  const std::string out = temp_path("interrupted") + ".txt";
  std::string printed;
  const int code =
      run_command(depot_binary() + " slam run " + walking() + " --system " + slow + " -q -o " +
                      out + " 2>&1 & pid=$!; for i in $(seq 600); do [ -e " + marker +
                      " ] && break; sleep 0.1; done; kill -INT $pid; wait $pid",
                  &printed);
  // What matters is the outcome, not how fast (a sanitizer build is slow):
  // the interrupt's exit code, no output, and no process of the group left.
  EXPECT_EQ(code, 130) << printed;
  EXPECT_THAT(printed, ::testing::HasSubstr("interrupted")) << printed;
  EXPECT_FALSE(fs::exists(out));
  std::string ps;
  run_command("ps -eo args | grep -c '^sleep 32.5$'", &ps);
  EXPECT_EQ(ps, "0\n") << "a process the system started outlived Ctrl-C";
}

TEST(CliSystem, ASweepRecordsAFailedSystemAndGoesOn) {
  const std::string broken = script_system("broken", "echo no map >&2; exit 2");
  const std::string out = temp_path("sweep");
  const DepotResult r = depot("sweep run depot_static -o " + out + " --modes orb,system:" + broken +
                              " --seeds 1 --frames 10 --width 160 -q");
  ASSERT_EQ(r.code, 0) << r.output;
  int failed = 0, ok = 0;
  for (const auto& run : fs::directory_iterator(out + "/runs")) {
    const nlohmann::json j = nlohmann::json::parse(read_text(run.path().string() + "/result.json"));
    if (j["mode"] == "orb") {
      ok += j["ok"].get<bool>();
      continue;
    }
    EXPECT_FALSE(j["ok"].get<bool>());
    EXPECT_THAT(j["error"].get<std::string>(), ::testing::HasSubstr("exited with code 2"));
    EXPECT_THAT(j["log_tail"].get<std::string>(), ::testing::HasSubstr("no map"));
    ++failed;
  }
  EXPECT_EQ(ok, 1);
  EXPECT_EQ(failed, 1);
  EXPECT_TRUE(fs::exists(out + "/report/report.html"));
}

// ---- Nothing a system starts outlives depot; errors name paths that exist ----

// How many processes run exactly `args` (zombies have none).
int processes_running(const std::string& args) {
  std::string ps;
  run_command("ps -eo args | grep -c '^" + args + "$'", &ps);
  return std::stoi(ps);
}

// processes_running once those already dying have had up to 5 s to go: a
// parent-death signal reaches the child after its parent is reaped, not
// before (CI run 12 saw the program still there right after `wait`).
int processes_running_after_dying(const std::string& args) {
  for (int i = 0; i < 100 && processes_running(args) > 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  return processes_running(args);
}

// A system that writes an identity pose for every frame of the dataset after
// `before` (shell commands ending in ';' or '&') ran; the trajectory is $1,
// the dataset $2.
std::string identity_system(const std::string& tag, const std::string& before,
                            const std::string& extra = "") {
  return write_yaml(tag, "command: [/bin/sh, -c, '" + before +
                             " awk \"!/^#/ { print \\$1, 0, 0, 0, 0, 0, 0, 1 }\" \"$2/rgb.txt\" "
                             "> \"$1\"', sh, \"{trajectory}\", \"{dataset}\"]\n" +
                             extra);
}

TEST(CliSystem, NothingTheSystemStartedOutlivesTheRun) {
  // One in its session, one that leaves it (setsid), and the program exits.
  const std::string system =
      identity_system("leaves", "sleep 778.125 & setsid sleep 778.25 & (sleep 778.375 &);");
  const std::string out = temp_path("leaves") + ".txt";
  const DepotResult r = depot("slam run " + walking() + " --system " + system + " -q -o " + out);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("tracked 12 of 12 frames")) << r.output;
  EXPECT_EQ(processes_running("sleep 778.125"), 0);
  EXPECT_EQ(processes_running("sleep 778.25"), 0) << "setsid escaped the system's process group";
  EXPECT_EQ(processes_running("sleep 778.375"), 0);
}

TEST(CliSystem, AKilledDepotsSystemAndScratchGoWithTheNextRun) {
  // Scratch folders in a temp directory of this test's own, to see them all.
  const std::string temp = temp_path("tmpdir");
  fs::create_directories(temp);
  const std::string marker = temp_path("running");
  const std::string system = script_system(
      "killed", "setsid sleep 779.125 & sleep 779.25 & touch " + marker + "; exec sleep 779.375");
  std::string pid;
  run_command("TMPDIR=" + temp + " " + depot_binary() + " slam run " + walking() + " --system " +
                  system + " -q -o " + temp_path("killed") +
                  ".txt >/dev/null 2>&1 & pid=$!; for i in $(seq 600); do [ -e " + marker +
                  " ] && break; sleep 0.1; done; kill -9 $pid; wait $pid; echo $pid",
              &pid);
  pid = pid.substr(0, pid.find('\n'));
  ASSERT_TRUE(fs::exists(marker)) << "the system never ran";
  // Left behind for now: the killed depot's scratch (named with its pid)
  // and what its system started (the program itself died with depot).
  std::vector<std::string> scratch;
  for (const auto& e : fs::directory_iterator(temp)) scratch.push_back(e.path().filename());
  ASSERT_EQ(scratch.size(), 1u);
  EXPECT_EQ(scratch[0].rfind("depot-system-" + pid + "-", 0), 0u) << scratch[0];
  EXPECT_EQ(processes_running_after_dying("sleep 779.375"), 0) << "the program outlived depot";

  // The next run of any system.
  std::string printed;
  const int code = run_command("TMPDIR=" + temp + " " + depot_binary() + " slam run " + walking() +
                                   " --system " + identity_system("next", "true;") + " -q -o " +
                                   temp_path("next") + ".txt",
                               &printed);
  EXPECT_EQ(code, 0) << printed;
  EXPECT_EQ(processes_running("sleep 779.125"), 0);
  EXPECT_EQ(processes_running("sleep 779.25"), 0);
  EXPECT_TRUE(fs::is_empty(temp)) << "the dead depot's scratch folder is still there";
}

TEST(CliSystem, ProgressShowsTheSystemsLogUnlessQuiet) {
  const std::string system = identity_system("progress", "echo frame 12 of 12 tracked;");
  const std::string name = fs::path(system).stem();
  const DepotResult r =
      depot("slam run " + walking() + " --system " + system + " -o " + temp_path("p") + ".txt");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(
      std::regex_search(r.output, std::regex("system " + name +
                                             ": ended after [0-9]+ s, 12 of 12 frames in "
                                             "its trajectory, log: frame 12 of 12 tracked")))
      << r.output;
  const DepotResult quiet =
      depot("slam run " + walking() + " --system " + system + " -q -o " + temp_path("p") + ".txt");
  ASSERT_EQ(quiet.code, 0) << quiet.output;
  EXPECT_THAT(quiet.output, ::testing::Not(::testing::HasSubstr("frame 12 of 12"))) << quiet.output;
}

// Every absolute path a message names.
std::vector<std::string> paths_in(const std::string& text) {
  std::vector<std::string> out;
  const std::regex path(R"((?:^|[\s(])(/[^\s:()]+))");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), path); it != std::sregex_iterator();
       ++it)
    out.push_back((*it)[1]);
  return out;
}

TEST(CliSystem, ErrorsNameOnlyPathsThatStillExist) {
  const std::vector<std::string> systems = {
      script_system("nothing_written", "exit 0"),
      script_system("nan_written", "echo 1.0 nan 0 0 0 0 0 1 > \"$1\""),
      script_system("exit_4", "echo no luck >&2; exit 4"),
      // Its trajectory is right, the keypoint file it promised is missing.
      write_yaml("no_keypoints",
                 "command: [/bin/sh, -c, 'awk \"!/^#/ { print \\$1, 0, 0, 0, 0, 0, 0, 1 }\" "
                 "\"$1/rgb.txt\" > \"$0\"', \"{trajectory}\", \"{dataset}\", \"{keypoints}\"]\n"),
  };
  for (size_t i = 0; i < systems.size(); ++i) {
    SCOPED_TRACE(systems[i]);
    const DepotResult r = depot("slam run " + walking() + " --system " + systems[i] + " -q -o " +
                                temp_path("named") + ".txt");
    ASSERT_EQ(r.code, 1) << r.output;
    for (const std::string& p : paths_in(r.output))
      EXPECT_TRUE(fs::exists(p)) << "names " << p << " which is gone: " << r.output;
  }
}

TEST(CliSystem, ASweepLeavesNoProcessNoScratchAndNamesTheFinalLog) {
  const std::string good = identity_system("sweep_good", "setsid sleep 780.125 &");
  const std::string bad =
      script_system("sweep_bad", "setsid sleep 780.25 & echo no map >&2; exit 2");
  const std::string out = temp_path("sweep_clean");
  const DepotResult r = depot("sweep run depot_static -o " + out + " --modes system:" + good +
                              ",system:" + bad + " --seeds 1 --frames 10 --width 160 -q");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(processes_running("sleep 780.125"), 0);
  EXPECT_EQ(processes_running("sleep 780.25"), 0);
  int failed = 0;
  for (const auto& run : fs::directory_iterator(out + "/runs")) {
    SCOPED_TRACE(run.path().string());
    EXPECT_FALSE(fs::exists(run.path() / "system")) << "the system's scratch was left";
    const nlohmann::json j = nlohmann::json::parse(read_text(run.path().string() + "/result.json"));
    if (j["ok"].get<bool>()) continue;
    ++failed;
    const std::string error = j["error"].get<std::string>();
    EXPECT_NE(
        error.find("(log " + fs::absolute(run.path() / "system.log").lexically_normal().string() +
                   " ends: no map)"),
        std::string::npos)
        << error;
    for (const std::string& p : paths_in(error)) EXPECT_TRUE(fs::exists(p)) << error;
  }
  EXPECT_EQ(failed, 1);
}

}  // namespace
}  // namespace depot::test
