#include "tools/harness/schedule/process_pool.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "common/testing/scratch_folder.h"

namespace fs = std::filesystem;

namespace depot::harness {
namespace {

struct PoolTest : ::testing::Test {
  testkit::ScratchFolder scratch{"pool_test"};
  const fs::path& dir = scratch.path();
  ProcessJob shell(const std::string& script, const std::string& log,
                   std::vector<size_t> needs = {}) {
    return {{"/bin/sh", "-c", script}, (dir / log).string(), needs};
  }
  std::string read(const std::string& log) {
    std::ifstream in(dir / log);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
};

TEST_F(PoolTest, RunsJobsLogsOutputAndBlocksOnFailedNeeds) {
  std::vector<ProcessJob> jobs = {shell("echo hello; echo oops >&2", "a.log"),
                                  shell("exit 3", "b.log"), shell("echo after a", "c.log", {0}),
                                  shell("echo never", "d.log", {1})};
  std::vector<JobOutcome> seen(jobs.size());
  std::atomic<bool> stop{false};
  const PoolSummary s = run_process_jobs(
      jobs, 2, [&](size_t i, const JobOutcome& o) { seen[i] = o; }, stop);
  EXPECT_EQ(s.succeeded, 2u);
  EXPECT_EQ(s.failed, 1u);
  EXPECT_EQ(s.blocked, 1u);
  EXPECT_FALSE(s.interrupted);
  EXPECT_EQ(seen[1].exit_code, 3);
  EXPECT_EQ(seen[3].state, JobState::kBlocked);
  EXPECT_EQ(read("a.log"), "hello\noops\n");
  EXPECT_EQ(read("c.log"), "after a\n");
  EXPECT_FALSE(fs::exists(dir / "d.log"));
}

TEST_F(PoolTest, NeverRunsMoreThanTheWorkerCount) {
  // Each job appends "+" on start and "-" on exit; with one worker the log
  // must alternate.
  const std::string trace = (dir / "trace").string();
  std::vector<ProcessJob> jobs;
  for (int i = 0; i < 4; ++i)
    jobs.push_back(shell("printf + >> " + trace + "; sleep 0.1; printf - >> " + trace,
                         "j" + std::to_string(i) + ".log"));
  std::atomic<bool> stop{false};
  run_process_jobs(jobs, 1, nullptr, stop);
  std::ifstream in(trace);
  std::string text;
  in >> text;
  EXPECT_EQ(text, "+-+-+-+-");
}

TEST_F(PoolTest, StopTerminatesRunningChildren) {
  std::vector<ProcessJob> jobs = {shell("sleep 30", "a.log"), shell("sleep 30", "b.log"),
                                  shell("sleep 30", "c.log")};
  std::atomic<bool> stop{false};
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    stop = true;
  });
  const auto start = std::chrono::steady_clock::now();
  const PoolSummary s = run_process_jobs(jobs, 2, nullptr, stop);
  stopper.join();
  EXPECT_TRUE(s.interrupted);
  EXPECT_EQ(s.succeeded, 0u);
  EXPECT_EQ(s.not_started, 1u);
  // Returned because the children were terminated, not because they ended.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 25.0);
}

}  // namespace
}  // namespace depot::harness
