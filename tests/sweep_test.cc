// `depot sweep` end to end on real renders and real SLAM runs: a small grid
// is killed while running, resumed without redoing finished runs, and its
// HTML report renders in headless Chromium.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gmock/gmock.h>
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

#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"
#include "tools/harness/plan/run_record.h"
#include "tools/harness/plan/sweep_job_state.h"
#include "tools/harness/schedule/slurm_submission.h"

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
  EXPECT_THAT(first, ::testing::HasSubstr("resume with `depot sweep resume")) << first;
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
    EXPECT_THAT(e.path().string(), ::testing::Not(::testing::HasSubstr(".partial-"))) << e.path();
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
  // Over the keypoints with depth (the ones that start map points) too.
  EXPECT_GT(by_id.at("depot_walking_xyz__load-1.5__s1__full").recall_with_depth, 0.5);
  EXPECT_GT(by_id.at("depot_walking_xyz__load-1.5__s1__full").precision_with_depth, 0.1);
  EXPECT_TRUE(std::isnan(by_id.at("depot_walking_xyz__load-1.5__s1__orb").precision));
  EXPECT_TRUE(std::isnan(by_id.at("depot_walking_xyz__load-1.5__s1__orb").recall_with_depth));

  const std::string tables = read(sweep / "report" / "tables.md");
  EXPECT_THAT(tables, ::testing::HasSubstr("| depot_walking_xyz | 1.5 |")) << tables;
  EXPECT_THAT(tables, ::testing::HasSubstr("recall with depth")) << tables;
  EXPECT_THAT(resumed.output, ::testing::HasSubstr("report: "));
  // The worlds rendered: each dataset's contact sheet outlives the dataset,
  // and the report shows it.
  const std::string html = read(sweep / "report" / "report.html");
  for (const std::string id :
       {"depot_walking_xyz__load-0__s1", "depot_walking_xyz__load-1.5__s1"}) {
    EXPECT_GT(fs::file_size(sweep / "data" / (id + ".jpg")), 10000u) << id;
    EXPECT_THAT(html, ::testing::HasSubstr("<img src=\"../data/" + id + ".jpg\"")) << id;
  }

  // A second resume has nothing to do.
  const test::DepotResult again = test::depot("sweep resume " + sweep.string());
  EXPECT_EQ(again.code, 0);
  EXPECT_THAT(again.output, ::testing::HasSubstr("0 to run")) << again.output;
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
  EXPECT_THAT(unknown.output, ::testing::HasSubstr("unknown parameter 'speed'")) << unknown.output;
  const test::DepotResult range =
      test::depot("sweep run depot_walking_xyz -o " + sweep.string() + " --vary load=0,9");
  EXPECT_NE(range.code, 0);
  EXPECT_THAT(range.output, ::testing::HasSubstr("dynamic")) << range.output;
  const test::DepotResult detector = test::depot("sweep run depot_walking_xyz -o " +
                                                 sweep.string() + " --vary detector=sim,yolo9");
  EXPECT_NE(detector.code, 0);
  EXPECT_THAT(detector.output,
              ::testing::HasSubstr("detector=yolo9: --detector: unknown detector 'yolo9'"))
      << detector.output;
  const test::DepotResult sim_only =
      test::depot("sweep run depot_walking_xyz -o " + sweep.string() +
                  " --vary detector=sim,darknet --set miss_rate=0.1");
  EXPECT_NE(sim_only.code, 0);
  EXPECT_THAT(sim_only.output,
              ::testing::HasSubstr("detector.miss_rate applies to the simulated detector only, "
                                   "not to detector=darknet"))
      << sim_only.output;
  EXPECT_FALSE(fs::exists(sweep / "sweep.json"));
  const test::DepotResult missing = test::depot("sweep resume " + (kRoot / "nowhere").string());
  EXPECT_NE(missing.code, 0);
  EXPECT_THAT(missing.output, ::testing::HasSubstr("sweep.json: cannot open")) << missing.output;
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

// `depot args` run in `folder` (a shell's cd first).
test::DepotResult depot_in(const fs::path& folder, const std::string& args) {
  test::DepotResult r;
  r.code = test::run_command("cd '" + folder.string() + "' && " + test::depot_binary() + " " + args,
                             &r.output);
  return r;
}

void write_file(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

size_t count_of(const std::string& text, const std::string& word) {
  size_t n = 0;
  for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
  return n;
}

// Issue 30, item 4: a system file given by a relative path is stored
// absolute, so the sweep's status, resume and jobs find it from any folder.
TEST(Sweep, ASystemFileGivenRelativeIsFoundFromAnyFolder) {
  const fs::path work = kRoot / "relative_system";
  fs::remove_all(work);
  write_file(work / "s" / "broken.yaml",
             "command: [/bin/sh, -c, 'echo no map >&2; exit 2', sh, \"{trajectory}\"]\n");
  const test::DepotResult plan =
      depot_in(work,
               "sweep run depot_static -o out --modes orb,system:s/broken.yaml --seeds 1 "
               "--frames 10 --width 160 --plan-only");
  ASSERT_EQ(plan.code, 0) << plan.output;
  EXPECT_NE(read(work / "out" / "sweep.json").find((work / "s" / "broken.yaml").string()),
            std::string::npos)
      << read(work / "out" / "sweep.json");

  // From another folder (this test's): status, resume and the jobs find the file.
  const std::string out = (work / "out").string();
  const test::DepotResult status = test::depot("sweep status " + out);
  ASSERT_EQ(status.code, 0) << status.output;
  EXPECT_THAT(status.output, ::testing::HasSubstr("3 jobs: 0 done")) << status.output;
  const test::DepotResult resumed = test::depot("sweep resume " + out + " -q");
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  const harness::RunRecord r = harness::read_run_record(
      (work / "out" / "runs" / "depot_static__s1__system_s_broken.yaml" / "result.json").string());
  EXPECT_FALSE(r.ok);
  EXPECT_THAT(r.error, ::testing::HasSubstr("exited with code 2")) << r.error;  // it ran
}

// Issue 30, item 6: one state per job (harness/plan/sweep_job_state.h) for
// status, resume and report: a run without a trajectory, a failed job, a
// running one and a corrupt record, each in the same words everywhere.
TEST(Sweep, StatusResumeAndReportAgreeOnEachJobsState) {
  const fs::path work = kRoot / "states";
  fs::remove_all(work);
  const fs::path started = work / "started", release = work / "release";
  // A system that runs until told to stop, then ends without a trajectory.
  write_file(work / "wait.yaml", "command: [/bin/sh, -c, 'touch " + started.string() +
                                     "; while [ ! -e " + release.string() +
                                     " ]; do sleep 0.1; done; exit 2', sh, \"{trajectory}\"]\n");
  const fs::path sweep = work / "out";
  const std::string grid = "sweep run depot_static -o " + sweep.string() +
                           " --modes orb,system:" + (work / "wait.yaml").string() +
                           " --seeds 1 --frames 10 --width 160 -j 1";
  ASSERT_EQ(test::depot(grid + " --plan-only").code, 0);
  const std::string orb = "depot_static__s1__orb";
  // A file where orb's run folder goes: that job fails.
  write_file(sweep / "runs" / orb, "in the way\n");

  const pid_t pid = start_depot({"sweep", "run", "depot_static", "-o", sweep.string(), "--modes",
                                 "orb,system:" + (work / "wait.yaml").string(), "--seeds", "1",
                                 "--frames", "10", "--width", "160", "-j", "1"},
                                work / "run.log");
  struct Release {  // whatever happens below, the system stops and the sweep ends
    fs::path file;
    pid_t pid;
    ~Release() {
      write_file(file, "");
      waitpid(pid, nullptr, 0);
    }
  };
  {
    Release guard{release, pid};
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
    while (!fs::exists(started) && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_TRUE(fs::exists(started)) << read(work / "run.log");
    // The render is done, orb failed (the pool runs one job at a time), the system runs.
    const test::DepotResult running = test::depot("sweep status " + sweep.string());
    EXPECT_EQ(running.code, 0) << running.output;
    EXPECT_NE(running.output.find("3 jobs: 1 done, 1 running, 0 waiting in a local `depot sweep`"),
              std::string::npos)
        << running.output;
    EXPECT_NE(running.output.find(", 1 failed, 0 not started"), std::string::npos)
        << running.output;
    EXPECT_THAT(running.output, ::testing::HasSubstr("failed: " + orb)) << running.output;
  }
  const std::string first = read(work / "run.log");
  EXPECT_THAT(first, ::testing::HasSubstr("1 job(s) failed")) << first;

  // Status and report: one without a trajectory, one failed.
  test::DepotResult status = test::depot("sweep status " + sweep.string());
  EXPECT_NE(status.output.find("3 jobs: 2 done (1 without a trajectory), 1 failed, 0 not started"),
            std::string::npos)
      << status.output;
  EXPECT_NE(read(sweep / "report" / "tables.md").find("1 of 2 (1 without a trajectory, 1 failed)"),
            std::string::npos)
      << read(sweep / "report" / "tables.md");

  // Resume runs the failed job (the obstacle gone) and keeps the system's run.
  fs::remove(sweep / "runs" / orb);
  test::DepotResult resumed = test::depot("sweep resume " + sweep.string() + " -q");
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  status = test::depot("sweep status " + sweep.string());
  EXPECT_NE(status.output.find("3 jobs: 3 done (1 without a trajectory), 0 failed, 0 not started"),
            std::string::npos)
      << status.output;
  EXPECT_FALSE(fs::exists(sweep / "failed" / (orb + ".json")));

  // A corrupt record is named, not counted done, left out of the report and run again.
  const fs::path record = sweep / "runs" / orb / "result.json";
  const std::string whole = read(record);
  write_file(record, whole.substr(0, whole.size() / 2));
  status = test::depot("sweep status " + sweep.string());
  EXPECT_NE(status.output.find("3 jobs: 2 done (1 without a trajectory), 0 failed, 1 corrupt"),
            std::string::npos)
      << status.output;
  EXPECT_NE(status.output.find("corrupt: " + record.string() + ": corrupt record"),
            std::string::npos)
      << status.output;
  const test::DepotResult report = test::depot("sweep report " + sweep.string());
  EXPECT_EQ(report.code, 0) << report.output;
  EXPECT_NE(report.output.find("depot: warning: " + record.string() + ": corrupt record"),
            std::string::npos)
      << report.output;
  EXPECT_THAT(report.output, ::testing::HasSubstr("(1 of 2 runs)")) << report.output;
  EXPECT_THAT(report.output, ::testing::HasSubstr("1 of 2 (1 without a trajectory, 1 corrupt)"))
      << report.output;
  resumed = test::depot("sweep resume " + sweep.string() + " -q");
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("depot: warning: " + record.string() + ": corrupt record"),
            std::string::npos)
      << resumed.output;
  EXPECT_NE(resumed.output.find("job " + orb + " runs again and its new record replaces this one"),
            std::string::npos)
      << resumed.output;
  EXPECT_TRUE(harness::read_run_record(record.string()).ok);
  EXPECT_THAT(resumed.output, ::testing::HasSubstr("(2 of 2 runs)")) << resumed.output;
}

// Issue 30, item 3: a folder submitted to Slurm is not run locally while
// its tasks are queued, nor when the queue cannot be read. Here a stand-in
// squeue answers; tests/sweep_slurm_test.cc does the same on a real cluster.
TEST(Sweep, ResumeRefusesWhileItsSlurmTasksMayStillRun) {
  const fs::path work = kRoot / "queued";
  fs::remove_all(work);
  const fs::path sweep = work / "out";
  ASSERT_EQ(test::depot("sweep run depot_static -o " + sweep.string() +
                        " --modes orb --seeds 1 --frames 10 --width 160 --plan-only")
                .code,
            0);
  const harness::SweepLayout layout{sweep.string()};
  harness::SlurmSubmission submission;
  submission.arrays.push_back(
      {"4242", harness::JobKind::kRender, false, {{0, "depot_static__s1"}}});
  submission.arrays.push_back(
      {"4243", harness::JobKind::kSlam, true, {{0, "depot_static__s1__orb"}}});
  fs::create_directories(harness::slurm_dir(layout));
  harness::write_submission(layout, submission);
  const fs::path bin = work / "bin";
  auto stand_in_squeue = [&](const std::string& script) {
    write_file(bin / "squeue", "#!/bin/sh\n" + script + "\n");
    fs::permissions(bin / "squeue", fs::perms::owner_all);
  };
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  auto resume_with_path = [&](const std::string& path, const std::string& extra = "") {
    setenv("PATH", path.c_str(), 1);
    const test::DepotResult r = test::depot("sweep resume " + sweep.string() + " -q" + extra);
    setenv("PATH", saved.c_str(), 1);
    return r;
  };
  auto nothing_ran = [&] {
    for (const char* sub : {"data", "runs", "logs"}) EXPECT_FALSE(fs::exists(sweep / sub)) << sub;
  };

  // Queued: one error line with the count, nothing run.
  stand_in_squeue(
      "echo '4242|0|PENDING|Priority'; echo '4243|0|PENDING|Dependency'; "
      "echo '77|0|RUNNING|None'");
  test::DepotResult r = resume_with_path(bin.string() + ":" + saved);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_EQ(r.output, "depot: error: " + sweep.string() +
                          ": 2 task(s) of its Slurm submission (job 4242,4243) are still queued "
                          "or running, so nothing was run; follow them with `depot sweep status " +
                          sweep.string() + "` or cancel them with `scancel 4242 4243`\n");
  nothing_ran();
  // squeue fails (the controller is down): refused too.
  stand_in_squeue("echo 'squeue: error: Unable to contact slurm controller' >&2; exit 1");
  r = resume_with_path(bin.string() + ":" + saved);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_EQ(count_of(r.output, "\n"), 1u) << r.output;
  EXPECT_NE(r.output.find("was submitted to Slurm but its queue cannot be read (squeue: "),
            std::string::npos)
      << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("Unable to contact slurm controller")) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("--assume-queue-empty")) << r.output;
  nothing_ran();
  // No squeue here at all: refused, saying why.
  r = resume_with_path((work / "nowhere").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_EQ(count_of(r.output, "\n"), 1u) << r.output;
  EXPECT_NE(r.output.find("was submitted to Slurm (" + sweep.string() +
                          "/slurm/submission.json) but squeue is not on PATH"),
            std::string::npos)
      << r.output;
  nothing_ran();
  // The tasks have ended (the queue no longer lists them): the jobs run here.
  stand_in_squeue("echo '77|0|RUNNING|None'");
  r = resume_with_path(bin.string() + ":" + saved);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(records(sweep).size(), 1u) << r.output;
}

// Issue 30, item 16: --plan-only's commands are for another machine: the
// folder absolute, each line exactly what a shell reads back.
TEST(Sweep, PlanOnlyPrintsCommandsAShellRunsAsTheyAre) {
  const fs::path work = kRoot / "plan only";  // a space: quoted
  fs::remove_all(work);
  fs::create_directories(work);
  const test::DepotResult plan =
      depot_in(work,
               "sweep run depot_static -o out --modes orb --seeds 1 --frames 10 --width 160 "
               "--plan-only");
  ASSERT_EQ(plan.code, 0) << plan.output;
  std::vector<std::string> lines;
  std::istringstream in(plan.output);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 2u) << plan.output;
  const std::string folder = "'" + (work / "out").string() + "'";
  EXPECT_EQ(lines[0], test::depot_binary() + " sweep job " + folder + " depot_static__s1");
  EXPECT_EQ(lines[1], test::depot_binary() + " sweep job " + folder + " depot_static__s1__orb");
  // Run as printed, from elsewhere.
  for (const auto& line : lines) {
    std::string output;
    EXPECT_EQ(test::run_command("cd / && " + line, &output), 0) << line << "\n" << output;
  }
  EXPECT_EQ(records(work / "out").size(), 1u);
}

// A sweep written down (--file): its grid is the command line's, a scenario
// file beside it is found from any folder, options given override it, and a
// bad file is one error line naming it.
TEST(Sweep, ASweepFileIsTheCommandLineWrittenDown) {
  const fs::path work = kRoot / "sweep file";
  fs::remove_all(work);
  fs::create_directories(work);
  fs::copy_file(std::string(DEPOT_SOURCE_DIR) + "/scenarios/depot_static.yaml",
                work / "my_static.yaml");
  std::ofstream(work / "grid.yaml") << "scenarios: [my_static.yaml, depot_walking_xyz]\n"
                                       "vary: {load: [0, 1]}\n"
                                       "modes: [orb, full]\nseeds: 2\nframes: 10\nwidth: 160\n";
  const test::DepotResult plan =
      test::depot("sweep run --file '" + (work / "grid.yaml").string() + "' -o '" +
                  (work / "out").string() + "' --seeds 1 --plan-only");
  ASSERT_EQ(plan.code, 0) << plan.output;
  // 2 scenarios x 2 loads x 1 seed (the command line's) renders; orb once per
  // dataset, full per dataset.
  EXPECT_THAT(plan.output, ::testing::HasSubstr("depot_static__load-1__s1__full"));
  EXPECT_THAT(plan.output, ::testing::HasSubstr("depot_walking_xyz__load-0__s1__orb"));
  EXPECT_THAT(plan.output, ::testing::Not(::testing::HasSubstr("__s2")));
  const std::string spec = read(work / "out" / "sweep.json");
  EXPECT_THAT(spec, ::testing::HasSubstr((work / "my_static.yaml").string()));
  EXPECT_THAT(spec, ::testing::HasSubstr("\"frames\": 10"));

  std::ofstream(work / "bad.yaml") << "scenarios: [depot_static]\nseeds: 0\n";
  const test::DepotResult bad = test::depot("sweep run --file '" + (work / "bad.yaml").string() +
                                            "' -o '" + (work / "bad_out").string() + "'");
  EXPECT_NE(bad.code, 0);
  EXPECT_THAT(bad.output, ::testing::HasSubstr((work / "bad.yaml").string() +
                                               ":2: 'seeds' = 0 is out of range [1, 1000]"));
  EXPECT_FALSE(fs::exists(work / "bad_out"));
}

}  // namespace
}  // namespace depot
