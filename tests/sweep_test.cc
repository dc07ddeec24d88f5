// `depot sweep` end to end on real renders and real SLAM runs: a small grid
// is killed while running, resumed without redoing finished runs, and its
// HTML report renders in headless Chromium.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/support/render_helpers.h"
#include "tools/harness/run_record.h"

namespace fs = std::filesystem;

namespace depot {
namespace {

const fs::path kRoot = fs::path(DEPOT_BINARY_DIR) / "sweep_test_scratch";

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<fs::path> records(const fs::path& sweep) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(sweep / "runs", ec))
    if (fs::is_regular_file(e.path() / "result.json")) out.push_back(e.path() / "result.json");
  std::sort(out.begin(), out.end());
  return out;
}

// Starts `depot args...` in the background with its output in `log`.
pid_t start_depot(const std::vector<std::string>& args, const fs::path& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    std::vector<std::string> words = {test::depot_binary()};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

// Pixels within a small distance of an RGB colour.
int pixels_near(const cv::Mat& bgr, int r, int g, int b) {
  int n = 0;
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
      if (std::abs(p[2] - r) + std::abs(p[1] - g) + std::abs(p[0] - b) < 30) ++n;
    }
  return n;
}

TEST(Sweep, ResumesAfterBeingKilledAndReports) {
  // Each test has its own folder: CTest runs them in parallel. 320 px wide:
  // at 160 px the people of load 1.5 can leave `full` too few keypoints to
  // initialise in 40 frames (seeds vary where they walk). miss_rate 0.05 for
  // every class: with the default calibrated to Yolo-Fastest, which finds no
  // desk or chair, every person box is rejected whole and load 1.5's crowd
  // leaves `full` nothing to initialise on in 40 frames at 320 px; the
  // harness is tested here, not the detector.
  const fs::path sweep = kRoot / "load";
  fs::remove_all(sweep);
  fs::create_directories(kRoot);
  const std::vector<std::string> args = {"sweep",      "run",          "depot_walking_xyz",
                                         "-o",         sweep.string(), "--vary",
                                         "load=0,1.5", "--set",        "miss_rate=0.05",
                                         "--modes",    "orb,full",     "--seeds",
                                         "1",          "--frames",     "40",
                                         "--width",    "320",          "-j",
                                         "2"};

  // Kill the sweep (SIGTERM, as a scheduler or `kill` would) after its first run.
  const pid_t pid = start_depot(args, kRoot / "load.log");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (records(sweep).empty() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  const std::string first = read(kRoot / "load.log");
  ASSERT_TRUE(WIFEXITED(status)) << first;
  ASSERT_NE(WEXITSTATUS(status), 0) << first;
  EXPECT_NE(first.find("resume with `depot sweep resume"), std::string::npos) << first;
  const std::vector<fs::path> before = records(sweep);
  ASSERT_FALSE(before.empty());
  ASSERT_LT(before.size(), 4u) << "the sweep finished before it could be killed";
  std::map<fs::path, fs::file_time_type> stamps;
  for (const auto& r : before) stamps[r] = fs::last_write_time(r);

  // Resume: finished runs are skipped, the rest run, the report is written.
  const test::DepotResult resumed = test::depot("sweep resume " + sweep.string() + " -j 2");
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  const std::vector<fs::path> after = records(sweep);
  ASSERT_EQ(after.size(), 4u) << resumed.output;
  for (const auto& [path, stamp] : stamps)
    EXPECT_EQ(fs::last_write_time(path), stamp) << path << " was run again";
  for (const auto& e : fs::recursive_directory_iterator(sweep))
    EXPECT_EQ(e.path().string().find(".partial-"), std::string::npos) << e.path();
  EXPECT_FALSE(fs::exists(sweep / "data" / "depot_walking_xyz__load-0__s1"))
      << "consumed datasets are removed";

  // The records say what the grid did: no movers at load 0, many at 1.5.
  std::map<std::string, harness::RunRecord> by_id;
  for (const auto& p : after) {
    const harness::RunRecord r = harness::read_run_record(p.string());
    by_id[r.id] = r;
    EXPECT_TRUE(r.ok) << r.id << ": " << r.error;
    EXPECT_TRUE(std::isfinite(r.ate_rmse)) << r.id;
  }
  EXPECT_EQ(by_id.at("depot_walking_xyz__load-0__s1__full").moving_share, 0.0);
  EXPECT_GT(by_id.at("depot_walking_xyz__load-1.5__s1__full").moving_share, 0.1);
  EXPECT_GT(by_id.at("depot_walking_xyz__load-1.5__s1__full").recall, 0.5);
  EXPECT_TRUE(std::isnan(by_id.at("depot_walking_xyz__load-1.5__s1__orb").precision));

  const std::string tables = read(sweep / "report" / "tables.md");
  EXPECT_NE(tables.find("| depot_walking_xyz | 1.5 |"), std::string::npos) << tables;
  EXPECT_NE(resumed.output.find("report: "), std::string::npos);

  // A second resume has nothing to do.
  const test::DepotResult again = test::depot("sweep resume " + sweep.string());
  EXPECT_EQ(again.code, 0);
  EXPECT_NE(again.output.find("0 to run"), std::string::npos) << again.output;
  for (const auto& p : after) EXPECT_TRUE(fs::exists(p));

  // A dataset left behind by a runner stopped between its last run and the
  // clean-up (a kill can land there) is removed by the next resume.
  const fs::path left = sweep / "data" / "depot_walking_xyz__load-0__s1";
  fs::create_directories(left);
  std::ofstream(left / "rgb.txt") << "# left behind\n";
  const test::DepotResult tidy = test::depot("sweep resume " + sweep.string());
  EXPECT_EQ(tidy.code, 0) << tidy.output;
  EXPECT_FALSE(fs::exists(left)) << tidy.output;
  EXPECT_TRUE(fs::exists(sweep / "data" / "depot_walking_xyz__load-0__s1.json"));
}

TEST(Sweep, RefusesBadGridsBeforeRunningAnything) {
  const fs::path sweep = kRoot / "bad";
  fs::remove_all(sweep);
  fs::create_directories(kRoot);
  const test::DepotResult unknown =
      test::depot("sweep run depot_walking_xyz -o " + sweep.string() + " --vary speed=1,2");
  EXPECT_NE(unknown.code, 0);
  EXPECT_NE(unknown.output.find("unknown parameter 'speed'"), std::string::npos) << unknown.output;
  const test::DepotResult range =
      test::depot("sweep run depot_walking_xyz -o " + sweep.string() + " --vary load=0,9");
  EXPECT_NE(range.code, 0);
  EXPECT_NE(range.output.find("dynamic"), std::string::npos) << range.output;
  EXPECT_FALSE(fs::exists(sweep / "sweep.json"));
  const test::DepotResult missing = test::depot("sweep resume " + (kRoot / "nowhere").string());
  EXPECT_NE(missing.code, 0);
  EXPECT_NE(missing.output.find("sweep.json: cannot open"), std::string::npos) << missing.output;
}

TEST(Sweep, ReportRendersInHeadlessChromium) {
  const fs::path sweep = kRoot / "report";
  fs::remove_all(sweep);
  fs::create_directories(kRoot);
  const test::DepotResult run =
      test::depot("sweep run depot_walking_xyz -o " + sweep.string() +
                  " --vary load=0,1.5 --set miss_rate=0.05 --modes orb,full --seeds 1 --frames 40 "
                  "--width 320 -j 2");  // miss_rate: see ResumesAfterBeingKilledAndReports
  ASSERT_EQ(run.code, 0) << run.output;
  const fs::path html = sweep / "report" / "report.html";
  ASSERT_TRUE(fs::exists(html)) << run.output;
  const fs::path shot = kRoot / "report.png";
  fs::remove(shot);
  const std::string cmd =
      "chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync "
      "--hide-scrollbars --user-data-dir=" +
      (kRoot / "chromium-profile").string() +
      " --window-size=1280,1400 --screenshot=" + shot.string() + " file://" + html.string() +
      " > " + (kRoot / "chromium.log").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0)
      << "headless chromium failed (tools/install-deps.sh installs it): "
      << read(kRoot / "chromium.log");
  const cv::Mat image = cv::imread(shot.string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(image.empty()) << "no screenshot";
  EXPECT_EQ(image.cols, 1280);
  // The plots were drawn: the orb (red) and full (green) series lines and
  // markers are on screen, not only text.
  EXPECT_GT(pixels_near(image, 0xd6, 0x27, 0x28), 200);
  EXPECT_GT(pixels_near(image, 0x2c, 0xa0, 0x2c), 200);
  // And the page has content (text, tables, frames): not a blank page.
  cv::Mat grey;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  EXPECT_GT(cv::countNonZero(grey < 128), 5000);
}

}  // namespace
}  // namespace depot
