#include "tools/harness/schedule/slurm_client.h"

#include <sstream>

#include "common/error.h"
#include "tools/harness/schedule/command_output.h"

namespace depot::harness {
namespace {

std::string first_line(const std::string& text) {
  std::string line;
  std::istringstream in(text);
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t") != std::string::npos) return line;
  return "";
}

std::string trimmed(const std::string& text) {
  const size_t a = text.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  return text.substr(a, text.find_last_not_of(" \t\r\n") - a + 1);
}

// The message of a failed command: its first error line, or its exit code.
std::string failure_of(const CommandOutput& o) {
  std::string line = first_line(o.err);
  if (line.empty()) line = first_line(o.out);
  if (line.empty()) line = "exit " + std::to_string(o.exit_code);
  return line;
}

}  // namespace

void require_slurm_clients() {
  for (const char* program : {"sbatch", "squeue", "scancel", "sinfo"})
    if (!find_on_path(program))
      fail("--scheduler slurm", std::string(program) +
                                    " not found on PATH (install slurm-client, or load the "
                                    "cluster's Slurm module)");
}

void require_partition(const std::string& partition) {
  const CommandOutput o = run_for_output({"sinfo", "-h", "-p", partition, "-o", "%P"});
  if (o.exit_code != 0) fail("sinfo", failure_of(o));
  if (trimmed(o.out).empty()) {
    const CommandOutput all = run_for_output({"sinfo", "-h", "-o", "%P"});
    std::string names;
    std::istringstream in(all.out);
    for (std::string line; std::getline(in, line);)
      if (!trimmed(line).empty()) names += (names.empty() ? "" : ", ") + trimmed(line);
    fail("--partition " + partition,
         "no such Slurm partition" + (names.empty() ? "" : " (the cluster has: " + names + ")"));
  }
}

std::string sbatch(const std::vector<std::string>& args) {
  std::vector<std::string> argv = {"sbatch", "--parsable"};
  argv.insert(argv.end(), args.begin(), args.end());
  const CommandOutput o = run_for_output(argv);
  if (o.exit_code != 0) fail("sbatch rejected the submission", failure_of(o));
  // --parsable prints "<id>" or "<id>;<cluster>"; --test-only prints to stderr.
  const std::string id = trimmed(o.out).substr(0, trimmed(o.out).find(';'));
  return id;
}

std::vector<QueuedTask> queued_tasks(const std::set<std::string>& array_job_ids) {
  std::vector<QueuedTask> tasks;
  if (array_job_ids.empty()) return tasks;
  // --me and no -j: ended jobs (unknown ids) must not make squeue fail.
  const CommandOutput o = run_for_output({"squeue", "--me", "-h", "-r", "-o", "%F|%K|%T|%r"});
  if (o.exit_code != 0) fail("squeue", failure_of(o));
  std::istringstream in(o.out);
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    QueuedTask t;
    std::string index;
    std::getline(fields, t.array_job_id, '|');
    std::getline(fields, index, '|');
    std::getline(fields, t.state, '|');
    std::getline(fields, t.reason, '|');
    if (!array_job_ids.count(t.array_job_id)) continue;
    try {
      t.index = std::stoi(index);
    } catch (const std::exception&) {
      t.index = -1;  // "N/A": not an array task
    }
    tasks.push_back(t);
  }
  return tasks;
}

void scancel(const std::vector<std::string>& job_ids) {
  if (job_ids.empty()) return;
  std::vector<std::string> argv = {"scancel", "--quiet"};
  argv.insert(argv.end(), job_ids.begin(), job_ids.end());
  run_for_output(argv);
}

}  // namespace depot::harness
