// Nothing a system under test starts outlives its run: every process of its
// tree is found (in a cgroup and by the /proc scan alike, also those that
// leave its session or drop its mark), what a depot killed by SIGKILL left is
// stopped by the next run, and run_system's scratch goes with the run.
#include "tools/system/process_tree.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <regex>
#include <sstream>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/stale_partials.h"
#include "common/testing/scratch_folder.h"
#include "tools/system/system_run.h"
#include "tools/system/system_spec.h"

namespace fs = std::filesystem;

namespace depot::system {

// How ctest lists the parameter (gtest would print the enum's bytes).
void PrintTo(Tracking tracking, std::ostream* out) {
  *out << (tracking == Tracking::kAuto ? "cgroup where available" : "process scan only");
}

namespace {

// A folder of this test's own: `tag` in the test's scratch folder, which
// removes it with all in it when the test ends.
fs::path test_folder(const testkit::ScratchFolder& scratch, const std::string& tag) {
  const fs::path p = scratch.path() / tag;
  fs::create_directories(p);
  return p;
}

// A /proc file's bytes, "" when the process is gone. Read with read(2):
// the file of a process that exits meanwhile fails with ESRCH, which
// libstdc++'s filebuf throws through istreambuf_iterator.
std::string read_proc_file(const fs::path& path) {
  std::string out;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return out;
  char buffer[4096];
  ssize_t n = 0;
  while ((n = ::read(fd, buffer, sizeof buffer)) > 0) out.append(buffer, static_cast<size_t>(n));
  ::close(fd);
  return n < 0 ? std::string() : out;
}

// Running processes (zombies have no command line) whose command line is
// exactly `args` (words joined by spaces).
std::vector<pid_t> processes_running(const std::string& args) {
  std::vector<pid_t> out;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = read_proc_file(entry.path() / "cmdline");
    if (cmdline.empty()) continue;
    if (cmdline.back() == '\0') cmdline.pop_back();
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (cmdline == args) out.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return out;
}

// Waits (against a hang only) until `n` processes run `args`.
bool wait_for_processes(const std::string& args, size_t n) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (processes_running(args).size() < n) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

bool wait_for_file(const fs::path& path) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(path)) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

// Our adopted orphans, once killed, are zombies until reaped.
void reap_children() {
  while (waitpid(-1, nullptr, WNOHANG) > 0) {
  }
}

ChildSpec shell(const std::string& script, const fs::path& folder) {
  ChildSpec spec;
  spec.argv = {"/bin/sh", "-c", script};
  spec.log_path = (folder / "log.txt").string();
  return spec;
}

std::string tracking_name(const testing::TestParamInfo<Tracking>& info) {
  return info.param == Tracking::kAuto ? "CgroupWhereAvailable" : "ProcessScanOnly";
}

class ProcessTreeTest : public testing::TestWithParam<Tracking> {
 protected:
  // Distinct durations per tracking mode: tests may run side by side.
  std::string sleep_args(int i) const {
    return "sleep " + std::to_string(GetParam() == Tracking::kAuto ? 700 : 800) + "." +
           std::to_string(i);
  }
};

TEST_P(ProcessTreeTest, WhatTheSystemLeftRunningIsFoundAndKilled) {
  const testkit::ScratchFolder scratch("process_tree_test");
  const fs::path folder =
      test_folder(scratch, std::string("left_") + tracking_name({GetParam(), 0}));
  // Its own session's child, one in a session of its own, a double-forked
  // one, and one that also drops the mark.
  const std::vector<std::string> sleeps = {sleep_args(1), sleep_args(2), sleep_args(3),
                                           sleep_args(4)};
  ProcessTree tree(shell(sleeps[0] + " & setsid " + sleeps[1] + " & (" + sleeps[2] +
                             " &); env -u DEPOT_SYSTEM_RUN setsid " + sleeps[3] + " & exit 0",
                         folder),
                   GetParam());
  // Which way this machine tracked it, for the log.
  std::printf("tracked %s\n", tree.cgroup().empty() ? "by the /proc scan only"
                                                    : ("in cgroup " + tree.cgroup()).c_str());
  if (GetParam() == Tracking::kProcessScan) {
    EXPECT_EQ(tree.cgroup(), "");
  }
  for (const std::string& s : sleeps) ASSERT_TRUE(wait_for_processes(s, 1)) << s;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::optional<int> status;
  while (!(status = tree.poll()) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(exit_code_of(*status), 0);
  // The program has ended; all it started is still the tree's.
  const std::vector<pid_t> members = tree.members();
  for (const std::string& s : sleeps)
    for (pid_t pid : processes_running(s))
      EXPECT_NE(std::find(members.begin(), members.end(), pid), members.end()) << s;
  tree.kill_all();
  reap_children();
  for (const std::string& s : sleeps) EXPECT_TRUE(processes_running(s).empty()) << s;
  EXPECT_TRUE(tree.members().empty());
}

TEST_P(ProcessTreeTest, StopEndsAProgramThatIgnoresSigtermAndAllItStarted) {
  const testkit::ScratchFolder scratch("process_tree_test");
  const fs::path folder =
      test_folder(scratch, std::string("stop_") + tracking_name({GetParam(), 0}));
  const std::string a = sleep_args(5), b = sleep_args(6);
  ProcessTree tree(
      shell("trap '' TERM; " + a + " & setsid " + b + " & while true; do sleep 0.05; done", folder),
      GetParam());
  ASSERT_TRUE(wait_for_processes(a, 1));
  ASSERT_TRUE(wait_for_processes(b, 1));
  tree.stop(std::chrono::milliseconds(200));
  reap_children();
  EXPECT_TRUE(processes_running(a).empty());
  EXPECT_TRUE(processes_running(b).empty());
  const std::optional<int> status = tree.poll();
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(exit_code_of(*status), 128 + SIGKILL);
}

// A depot killed by SIGKILL while its system runs: the program dies with it
// (parent-death signal), what it started is stopped by the next run.
TEST_P(ProcessTreeTest, TheNextRunStopsWhatAKilledDepotLeft) {
  const testkit::ScratchFolder scratch("process_tree_test");
  const fs::path folder =
      test_folder(scratch, std::string("killed_") + tracking_name({GetParam(), 0}));
  const std::string a = sleep_args(7), b = sleep_args(8);
  const fs::path started = folder / "started", cgroup_file = folder / "cgroup";
  const pid_t depot = fork();
  if (depot == 0) {
    // The stand-in for depot: a tree, then wait to be killed.
    try {
      ProcessTree tree(
          shell("setsid " + a + " & " + b + " & touch " + started.string() + "; wait", folder),
          GetParam());
      std::ofstream(cgroup_file.string() + ".new") << tree.cgroup();
      fs::rename(cgroup_file.string() + ".new", cgroup_file);
      while (true) pause();
    } catch (...) {
    }
    _exit(1);
  }
  ASSERT_GT(depot, 0);
  ASSERT_TRUE(wait_for_file(started));
  ASSERT_TRUE(wait_for_file(cgroup_file));
  ASSERT_TRUE(wait_for_processes(a, 1));
  ASSERT_TRUE(wait_for_processes(b, 1));
  kill(depot, SIGKILL);
  waitpid(depot, nullptr, 0);
  std::string cgroup;
  std::getline(std::ifstream(cgroup_file), cgroup);
  if (GetParam() == Tracking::kProcessScan) {
    EXPECT_EQ(cgroup, "");
  }
  EXPECT_FALSE(processes_running(a).empty()) << "left behind until the next run";

  EXPECT_GE(remove_stale_process_trees(), 2);
  reap_children();
  EXPECT_TRUE(processes_running(a).empty());
  EXPECT_TRUE(processes_running(b).empty());
  if (!cgroup.empty()) {
    EXPECT_FALSE(fs::exists(cgroup)) << cgroup;
  }
}

INSTANTIATE_TEST_SUITE_P(Tracking, ProcessTreeTest,
                         testing::Values(Tracking::kAuto, Tracking::kProcessScan), tracking_name);

TEST(ProcessTree, StaleScratchFoldersOfGoneProcessesAreRemoved) {
  const testkit::ScratchFolder scratch("process_tree_test");
  const fs::path folder = test_folder(scratch, "scratch");
  // A pid that is surely gone: a child that ended and was reaped.
  const pid_t gone = fork();
  if (gone == 0) _exit(0);
  waitpid(gone, nullptr, 0);
  const std::string dead = "depot-system-" + std::to_string(gone) + "-Ab12Cd";
  const std::string own = "depot-system-" + std::to_string(getpid()) + "-Ab12Cd";
  for (const std::string& name : {dead, own, std::string("depot-system-Ab12Cd")})
    fs::create_directories(folder / name / "inside");
  EXPECT_EQ(remove_stale_scratch(folder.string(), "depot-system-"), 1);
  EXPECT_FALSE(fs::exists(folder / dead));
  EXPECT_TRUE(fs::exists(folder / own));
  EXPECT_TRUE(fs::exists(folder / "depot-system-Ab12Cd")) << "not named by a pid: not ours";
}

// A dataset of three frames' lists (run_system reads no image).
std::string tiny_dataset(const fs::path& folder) {
  const fs::path d = folder / "dataset";
  fs::create_directories(d);
  std::ofstream(d / "rgb.txt") << "1.0 rgb/1.png\n2.0 rgb/2.png\n3.0 rgb/3.png\n";
  std::ofstream(d / "depth.txt") << "1.0 depth/1.png\n2.0 depth/2.png\n3.0 depth/3.png\n";
  return d.string();
}

SystemSpec script_spec(const fs::path& folder, const std::string& name, const std::string& script) {
  const fs::path path = folder / (name + ".yaml");
  std::ofstream(path) << "command: [/bin/sh, -c, '" << script
                      << "', sh, \"{trajectory}\", \"{work}\"]\n";
  return load_system_spec(path.string());
}

TEST(RunSystem, ScratchIsNamedWithThePidAndGoesWithTheRun) {
  const testkit::ScratchFolder scratch("process_tree_test");
  const fs::path folder = test_folder(scratch, "scratch_run");
  const std::string dataset = tiny_dataset(folder);
  const char* old_tmpdir = std::getenv("TMPDIR");
  const std::string saved = old_tmpdir ? old_tmpdir : "";
  const fs::path temp = folder / "tmp";
  fs::create_directories(temp);
  setenv("TMPDIR", temp.c_str(), 1);
  SystemRunRequest request;
  request.dataset = dataset;
  request.log_path = (folder / "ok.log").string();
  {
    const SystemRunResult r = run_system(
        script_spec(folder, "ok", "echo \"$2\"; echo 2.0 0 0 0 0 0 0 1 > \"$1\""), request);
    ASSERT_TRUE(r.work);
    EXPECT_EQ(fs::path(r.work->path()).parent_path(), temp);
    EXPECT_EQ(fs::path(r.work->path())
                  .filename()
                  .string()
                  .rfind("depot-system-" + std::to_string(getpid()) + "-", 0),
              0u)
        << r.work->path();
    EXPECT_EQ(log_tail(request.log_path, 1), r.work->path());
    EXPECT_TRUE(fs::is_regular_file(r.trajectory_path));
  }
  EXPECT_TRUE(fs::is_empty(temp)) << "the result let go of its scratch";
  // A failing run: no scratch left, and the error names no path in it.
  request.log_path = (folder / "nan.log").string();
  std::string error;
  try {
    run_system(script_spec(folder, "nan", "echo 2.0 nan 0 0 0 0 0 1 > \"$1\""), request);
  } catch (const Error& e) {
    error = e.what();
  }
  EXPECT_THAT(error, ::testing::HasSubstr("its trajectory: {trajectory}:1:")) << error;
  EXPECT_THAT(error, ::testing::Not(::testing::HasSubstr(temp.string()))) << error;
  EXPECT_TRUE(fs::is_empty(temp));
  if (old_tmpdir)
    setenv("TMPDIR", saved.c_str(), 1);
  else
    unsetenv("TMPDIR");
}

TEST(RunSystem, ProgressReportsTheLogsLastLineWhenTheSystemEnds) {
  const testkit::ScratchFolder scratch("process_tree_test");
  const fs::path folder = test_folder(scratch, "progress");
  SystemRunRequest request;
  request.dataset = tiny_dataset(folder);
  request.log_path = (folder / "progress.log").string();
  std::vector<SystemProgress> reports;
  request.on_progress = [&](const SystemProgress& p) { reports.push_back(p); };
  run_system(script_spec(folder, "progress",
                         "echo 1.0 0 0 0 0 0 0 1 > \"$1\"; echo 2.0 0 0 0 0 0 0 1 >> \"$1\"; "
                         "echo frame 2 of 3 done"),
             request);
  ASSERT_FALSE(reports.empty());
  EXPECT_TRUE(reports.back().finished);
  EXPECT_EQ(reports.back().log_line, "frame 2 of 3 done");
  EXPECT_EQ(reports.back().poses, 2u);
  EXPECT_EQ(reports.back().frames, 3u);
}

}  // namespace
}  // namespace depot::system
