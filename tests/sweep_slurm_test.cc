// `depot sweep --scheduler slurm` against a real Slurm (label `cluster`;
// tools/slurm/ci-cluster-test.sh starts a single-node one and sets
// DEPOT_SLURM=1). Without a reachable cluster the tests skip, unless
// DEPOT_SLURM=1 says one must be there. The sweep through Slurm gives the
// local pool's records to the last digit; a cancelled task is resumed
// without rewriting a record; a failing job is retried, then reported; bad
// input is one error line with nothing submitted; no resume, local or not,
// runs while the folder's tasks are queued; Ctrl-C says how to resume on Slurm.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/support/render_helpers.h"
#include "tools/harness/plan/sweep_job_state.h"
#include "tools/harness/schedule/command_output.h"
#include "tools/harness/schedule/slurm_submission.h"

namespace fs = std::filesystem;

namespace depot {
namespace {

const fs::path kRoot = fs::path(DEPOT_BINARY_DIR) / "sweep_slurm_test_scratch";
// 2 scenarios x 2 modes x 2 seeds, short and small, synchronous mapping (reproducible).
const std::string kGrid =
    "depot_walking_xyz depot_sitting_static --modes orb,full --seeds 2 --frames 10 --width 160 "
    "--mapping sync";

bool cluster_required() {
  const char* v = std::getenv("DEPOT_SLURM");
  return v && std::string(v) == "1";
}

bool cluster_reachable() {
  if (!harness::find_on_path("sinfo")) return false;
  try {
    return harness::run_for_output({"sinfo", "-h", "-o", "%T"}).exit_code == 0;
  } catch (const std::exception&) {
    return false;
  }
}

#define REQUIRE_CLUSTER()                                                                   \
  do {                                                                                      \
    if (!cluster_reachable()) {                                                             \
      if (cluster_required()) FAIL() << "DEPOT_SLURM=1 but no Slurm cluster answers sinfo"; \
      GTEST_SKIP() << "no Slurm cluster reachable (sinfo); tools/slurm/ci-cluster-test.sh " \
                      "starts a local one";                                                 \
    }                                                                                       \
  } while (0)

fs::path fresh(const std::string& name) {
  const fs::path p = kRoot / name;
  fs::remove_all(p);
  fs::create_directories(kRoot);
  return p;
}

std::vector<fs::path> run_records(const fs::path& sweep) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(sweep / "runs", ec))
    if (fs::is_regular_file(e.path() / "result.json")) out.push_back(e.path() / "result.json");
  std::sort(out.begin(), out.end());
  return out;
}

// A record without the wall-clock figures (at any depth), which differ from run to run.
void erase_timing(nlohmann::json& j) {
  if (!j.is_object()) return;
  for (const char* key : {"seconds", "median_frame_ms", "rejection_ms"}) j.erase(key);
  for (auto& [key, value] : j.items()) erase_timing(value);
}

nlohmann::json without_timing(const fs::path& record) {
  std::ifstream in(record);
  nlohmann::json j = nlohmann::json::parse(in);
  erase_timing(j);
  return j;
}

size_t error_lines(const std::string& output) {
  size_t n = 0;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) n += line.rfind("depot: error:", 0) == 0;
  return n;
}

size_t lines(const std::string& output) {
  size_t n = 0;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) n += !line.empty();
  return n;
}

// Our tasks still in the queue.
size_t queued(const std::string& name) {
  const auto o = harness::run_for_output({"squeue", "--me", "-h", "-r", "-n", name, "-o", "%i"});
  return lines(o.out);
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

TEST(SweepSlurm, SameRecordsAsTheLocalPool) {
  REQUIRE_CLUSTER();
  const fs::path local = fresh("local"), slurm = fresh("slurm");
  auto t0 = std::chrono::steady_clock::now();
  const test::DepotResult a = test::depot("sweep run " + kGrid + " -o " + local.string() + " -j 2");
  const double local_s = seconds_since(t0);
  ASSERT_EQ(a.code, 0) << a.output;
  t0 = std::chrono::steady_clock::now();
  const test::DepotResult b = test::depot("sweep run " + kGrid + " -o " + slurm.string() +
                                          " --scheduler slurm --partition debug --poll 0.5");
  const double slurm_s = seconds_since(t0);
  ASSERT_EQ(b.code, 0) << b.output;
  std::printf("wall time: local pool (-j 2) %.1f s, Slurm %.1f s\n", local_s, slurm_s);
  EXPECT_THAT(b.output, ::testing::HasSubstr("submitted to Slurm")) << b.output;
  EXPECT_THAT(b.output, ::testing::HasSubstr("report: ")) << b.output;

  const auto local_records = run_records(local), slurm_records = run_records(slurm);
  ASSERT_EQ(local_records.size(), 8u) << a.output;
  ASSERT_EQ(slurm_records.size(), 8u) << b.output;
  for (size_t i = 0; i < local_records.size(); ++i) {
    ASSERT_EQ(local_records[i].parent_path().filename(), slurm_records[i].parent_path().filename());
    // dump() prints doubles round-trip exact: equal text is equal to the last digit.
    EXPECT_EQ(without_timing(local_records[i]).dump(), without_timing(slurm_records[i]).dump())
        << local_records[i];
  }
  // The tables are made of those records (ATE, RPE, rejection): equal too.
  for (const char* table :
       {"table2_ablation.csv", "table3_ate_vs_orb.csv", "table4_rpe_vs_orb.csv", "rejection.csv"}) {
    std::ifstream x(local / "report" / table), y(slurm / "report" / table);
    std::stringstream sx, sy;
    sx << x.rdbuf();
    sy << y.rdbuf();
    EXPECT_EQ(sx.str(), sy.str()) << table;
  }
  const test::DepotResult status = test::depot("sweep status " + slurm.string());
  EXPECT_THAT(status.output, ::testing::HasSubstr("12 jobs: 12 done")) << status.output;
}

// Starts `depot args...` in the background, its output in `log`.
pid_t start_depot(const std::string& args, const fs::path& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string cmd = test::depot_binary() + " " + args + " > " + log.string() + " 2>&1";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(SweepSlurm, CancelledTaskThenResumeWritesNoRecordTwice) {
  REQUIRE_CLUSTER();
  const fs::path sweep = fresh("cancel");
  const pid_t pid =
      start_depot("sweep run " + kGrid + " -o " + sweep.string() + " --scheduler slurm --poll 0.5",
                  kRoot / "cancel.log");
  // The first task seen running is cancelled, as a user's scancel would.
  const harness::SweepLayout layout{sweep.string()};
  std::string cancelled;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(3);
  while (cancelled.empty() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const auto submission = harness::read_submission(layout);
    if (!submission) continue;
    for (const auto& array : submission->arrays) {
      const auto o = harness::run_for_output(
          {"squeue", "--me", "-h", "-r", "-t", "RUNNING", "-j", array.job_id, "-o", "%i"});
      std::istringstream in(o.out);
      if (std::getline(in, cancelled) && !cancelled.empty()) break;
      cancelled.clear();
    }
  }
  ASSERT_FALSE(cancelled.empty()) << read(kRoot / "cancel.log");
  harness::run_for_output({"scancel", cancelled});
  int status = 0;
  waitpid(pid, &status, 0);
  const std::string first = read(kRoot / "cancel.log");
  ASSERT_TRUE(WIFEXITED(status)) << first;
  EXPECT_NE(WEXITSTATUS(status), 0) << "a cancelled task leaves the sweep unfinished\n" << first;
  EXPECT_THAT(first, ::testing::HasSubstr("FAILED")) << first;

  std::map<fs::path, fs::file_time_type> stamps;
  for (const auto& r : run_records(sweep)) stamps[r] = fs::last_write_time(r);
  ASSERT_LT(stamps.size(), 8u) << "the cancelled task's run(s) must be missing\n" << first;

  const test::DepotResult resumed =
      test::depot("sweep resume " + sweep.string() + " --scheduler slurm --poll 0.5");
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  EXPECT_EQ(run_records(sweep).size(), 8u) << resumed.output;
  for (const auto& [path, stamp] : stamps)
    EXPECT_EQ(fs::last_write_time(path), stamp) << path << " was written twice";
  EXPECT_THAT(resumed.output, ::testing::Not(::testing::HasSubstr(" 0 already finished")))
      << resumed.output;
  for (const auto& e : fs::recursive_directory_iterator(sweep))
    EXPECT_THAT(e.path().string(), ::testing::Not(::testing::HasSubstr(".partial-"))) << e.path();
}

// The local cluster's state folder (tools/slurm/ci-cluster-test.sh exports
// SLURM_CONF inside it), or "" for another cluster.
std::string local_cluster_state() {
  const char* conf = std::getenv("SLURM_CONF");
  if (!conf) return "";
  const fs::path state = fs::path(conf).parent_path();
  return fs::exists(state / "run") ? state.string() : "";
}

int local_cluster(const std::string& action, const std::string& state) {
  const std::string script = std::string(DEPOT_SOURCE_DIR) + "/tools/slurm/local-cluster.sh";
  return harness::run_for_output({script, action, state}).exit_code;
}

TEST(SweepSlurm, NodeLostWhileJobsWaitThenBackTheSweepCompletes) {
  REQUIRE_CLUSTER();
  const std::string state = local_cluster_state();
  if (state.empty()) GTEST_SKIP() << "needs the local cluster (tools/slurm/ci-cluster-test.sh)";
  const fs::path sweep = fresh("node_lost");
  // slurmd stops before the sweep submits: every job waits for the node.
  ASSERT_EQ(local_cluster("stop-node", state), 0);
  const pid_t pid =
      start_depot("sweep run " + kGrid + " -o " + sweep.string() + " --scheduler slurm --poll 0.5",
                  kRoot / "node_lost.log");
  const harness::SweepLayout layout{sweep.string()};
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  while (!harness::read_submission(layout) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const bool submitted = harness::read_submission(layout).has_value();
  std::this_thread::sleep_for(std::chrono::seconds(3));
  EXPECT_EQ(run_records(sweep).size(), 0u) << "no job can run without its node";
  ASSERT_EQ(local_cluster("start-node", state), 0);  // the node returns
  int status = 0;
  waitpid(pid, &status, 0);
  const std::string log = read(kRoot / "node_lost.log");
  ASSERT_TRUE(submitted) << log;
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 0) << log;
  EXPECT_EQ(run_records(sweep).size(), 8u) << log;
}

TEST(SweepSlurm, FailingJobIsRetriedThenReported) {
  REQUIRE_CLUSTER();
  const fs::path sweep = fresh("failing");
  const std::string grid =
      "depot_walking_xyz --modes orb,full --seeds 1 --frames 10 --width 160 --mapping sync -o " +
      sweep.string();
  // A file where the full run's folder goes: that job fails every attempt.
  ASSERT_EQ(test::depot("sweep run " + grid + " --plan-only").code, 0);
  const std::string bad = "depot_walking_xyz__s1__full";
  fs::create_directories(sweep / "runs");
  std::ofstream(sweep / "runs" / bad) << "in the way\n";

  const test::DepotResult r =
      test::depot("sweep run " + grid + " --scheduler slurm --retries 1 --poll 0.5");
  EXPECT_NE(r.code, 0) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr(bad + ": FAILED")) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("1 job(s) failed")) << r.output;
  const std::string log = read(sweep / "logs" / (bad + ".log"));
  EXPECT_THAT(log, ::testing::HasSubstr("attempt 1 of 2 exited")) << log;
  EXPECT_THAT(log, ::testing::HasSubstr("attempt 2 of 2 exited")) << log;
  const harness::SweepLayout layout{sweep.string()};
  ASSERT_TRUE(fs::exists(harness::failure_record_path(layout, bad)));
  const std::string failure = read(harness::failure_record_path(layout, bad));
  EXPECT_THAT(failure, ::testing::HasSubstr("attempt 2 of 2")) << failure;
  EXPECT_TRUE(fs::exists(sweep / "runs" / "depot_walking_xyz__s1__orb" / "result.json"));
  const test::DepotResult status = test::depot("sweep status " + sweep.string());
  EXPECT_THAT(status.output, ::testing::HasSubstr("1 failed")) << status.output;
  EXPECT_THAT(status.output, ::testing::HasSubstr("failed: " + bad)) << status.output;
}

TEST(SweepSlurm, BadInputIsOneErrorLineAndSubmitsNothing) {
  const fs::path sweep = fresh("bad");
  const std::string grid =
      "sweep run depot_walking_xyz --modes orb --seeds 1 --frames 10 "
      "--width 160 -o " +
      sweep.string() + " --scheduler slurm";
  const harness::SweepLayout layout{sweep.string()};
  {  // No Slurm clients on PATH.
    const char* old = std::getenv("PATH");
    const std::string saved = old ? old : "";
    setenv("PATH", "/nonexistent", 1);
    const test::DepotResult r = test::depot(grid);
    setenv("PATH", saved.c_str(), 1);
    EXPECT_NE(r.code, 0);
    EXPECT_EQ(lines(r.output), 1u) << r.output;
    EXPECT_EQ(error_lines(r.output), 1u) << r.output;
    EXPECT_THAT(r.output, ::testing::HasSubstr("sbatch not found on PATH")) << r.output;
    EXPECT_FALSE(harness::read_submission(layout));
  }
  if (!cluster_reachable()) {
    if (cluster_required()) FAIL() << "DEPOT_SLURM=1 but no Slurm cluster answers sinfo";
    GTEST_SKIP() << "no Slurm cluster reachable: only the missing-sbatch case ran";
  }
  const std::string name = "depot-sweep:" + sweep.filename().string();
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {" --partition nosuch", "no such Slurm partition"},
           {" --time bogus", "sbatch rejected the submission"},
           {" --sbatch-arg=--no-such-option", "sbatch rejected the submission"}}) {
    const test::DepotResult r = test::depot(grid + args);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_EQ(lines(r.output), 1u) << args << "\n" << r.output;
    EXPECT_EQ(error_lines(r.output), 1u) << args << "\n" << r.output;
    EXPECT_THAT(r.output, ::testing::HasSubstr(message)) << args << "\n" << r.output;
    EXPECT_EQ(queued(name), 0u) << args;
    EXPECT_FALSE(harness::read_submission(layout)) << args;
  }
  // Still resumable: the same sweep then runs.
  const test::DepotResult ok = test::depot(grid + " --poll 0.5");
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_EQ(run_records(sweep).size(), 1u) << ok.output;
}

// Cancels a submission's arrays and waits until the queue no longer lists them.
struct CancelAtEnd {
  std::vector<std::string> ids;
  void now() {
    if (ids.empty()) return;
    std::vector<std::string> argv = {"scancel"};
    argv.insert(argv.end(), ids.begin(), ids.end());
    harness::run_for_output(argv);
    std::vector<std::string> ask = {"squeue", "--me", "-h", "-r", "-o", "%i", "-j"};
    std::string list;
    for (const auto& id : ids) list += (list.empty() ? "" : ",") + id;
    ask.push_back(list);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
    while (lines(harness::run_for_output(ask).out) > 0 &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ids.clear();
  }
  ~CancelAtEnd() { now(); }
};

std::vector<std::string> array_ids(const harness::SweepLayout& layout) {
  std::vector<std::string> ids;
  if (const auto s = harness::read_submission(layout))
    for (const auto& a : s->arrays) ids.push_back(a.job_id);
  return ids;
}

// Issue 30, item 3: a folder submitted to Slurm knows it; any resume, local
// or not, asks the queue first and runs nothing while its tasks are there.
TEST(SweepSlurm, NoResumeRunsWhileTheFoldersTasksAreQueued) {
  REQUIRE_CLUSTER();
  const fs::path sweep = fresh("held");
  const std::string grid =
      "depot_walking_xyz --modes orb --seeds 1 --frames 10 --width 160 --mapping sync -o " +
      sweep.string();
  // Held tasks stay queued until released or cancelled.
  const test::DepotResult submitted =
      test::depot("sweep run " + grid + " --scheduler slurm --detach --sbatch-arg=--hold");
  ASSERT_EQ(submitted.code, 0) << submitted.output;
  const harness::SweepLayout layout{sweep.string()};
  CancelAtEnd cancel{array_ids(layout)};
  ASSERT_EQ(cancel.ids.size(), 2u) << submitted.output;  // render, then orb

  for (const std::string scheduler : {"", " --scheduler slurm"}) {
    const test::DepotResult r = test::depot("sweep resume " + sweep.string() + scheduler);
    EXPECT_EQ(r.code, 1) << scheduler << "\n" << r.output;
    EXPECT_EQ(lines(r.output), 1u) << scheduler << "\n" << r.output;
    EXPECT_EQ(error_lines(r.output), 1u) << scheduler << "\n" << r.output;
    EXPECT_NE(r.output.find(sweep.string() + ": 2 task(s) of its Slurm submission"),
              std::string::npos)
        << r.output;
    EXPECT_THAT(r.output, ::testing::HasSubstr("`depot sweep status " + sweep.string() + "`"))
        << r.output;
    EXPECT_NE(r.output.find("`scancel " + cancel.ids[0] + " " + cancel.ids[1] + "`"),
              std::string::npos)
        << r.output;
  }
  EXPECT_FALSE(fs::exists(sweep / "runs"));
  EXPECT_FALSE(fs::exists(sweep / "data"));
  EXPECT_FALSE(fs::exists(sweep / "logs"));
  EXPECT_EQ(array_ids(layout), cancel.ids) << "nothing submitted again";
  const test::DepotResult status = test::depot("sweep status " + sweep.string());
  EXPECT_NE(status.output.find("2 jobs: 0 done, 0 running, 2 pending in Slurm"), std::string::npos)
      << status.output;

  // Once they are gone, a plain local resume runs the jobs.
  cancel.now();
  const test::DepotResult local = test::depot("sweep resume " + sweep.string() + " -q");
  EXPECT_EQ(local.code, 0) << local.output;
  EXPECT_EQ(run_records(sweep).size(), 1u) << local.output;
}

// Issue 30, item 16: Ctrl-C of a sweep on Slurm cancels its tasks and says
// how to resume it there (with the options that placed its jobs).
TEST(SweepSlurm, CtrlCCancelsAndItsHintResumesOnSlurm) {
  REQUIRE_CLUSTER();
  const fs::path sweep = fresh("interrupted");
  const fs::path log = kRoot / "interrupted.log";
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    std::vector<std::string> words = {test::depot_binary(),
                                      "sweep",
                                      "run",
                                      "depot_walking_xyz",
                                      "--modes",
                                      "orb",
                                      "--seeds",
                                      "1",
                                      "--frames",
                                      "10",
                                      "--width",
                                      "160",
                                      "-o",
                                      sweep.string(),
                                      "--scheduler",
                                      "slurm",
                                      "--poll",
                                      "0.5",
                                      "--sbatch-arg=--hold"};
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  const harness::SweepLayout layout{sweep.string()};
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  while (!harness::read_submission(layout) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  CancelAtEnd cancel{array_ids(layout)};  // should the sweep fail to
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  const std::string printed = read(log);
  ASSERT_FALSE(cancel.ids.empty()) << printed;
  ASSERT_TRUE(WIFEXITED(status)) << printed;
  EXPECT_NE(WEXITSTATUS(status), 0) << printed;
  EXPECT_NE(printed.find("resume with `depot sweep resume " + sweep.string() +
                         " --scheduler slurm --sbatch-arg=--hold`"),
            std::string::npos)
      << printed;
  EXPECT_EQ(queued("depot-sweep:" + sweep.filename().string()), 0u) << "Ctrl-C cancels the tasks";
}

}  // namespace
}  // namespace depot
