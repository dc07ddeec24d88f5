#pragma once
// What a sweep submitted to Slurm, kept in OUT/slurm/ so that the running
// `depot sweep`, a later `status` or `resume` and the array tasks themselves
// agree on it:
//   task.sh            the batch script of every task (fixed text, no paths in it)
//   array-<k>.tasks    line i + 1: the sweep job id of array index i
//   submission.json    the arrays: Slurm job id, kind, index -> sweep job id;
//                      that it exists is how every later `run` or `resume`
//                      (whatever its --scheduler) knows to ask the queue first
//   out/               Slurm's own output of each task (depot's is in logs/)
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tools/harness/plan/sweep_plan.h"

namespace depot::harness {

struct SlurmArray {
  std::string job_id;  // empty until submitted
  JobKind kind = JobKind::kRender;
  bool after_render = false;         // task i starts after render task i succeeded (aftercorr)
  std::map<int, std::string> tasks;  // array index -> sweep job id
};

struct SlurmSubmission {
  std::vector<SlurmArray> arrays;
};

std::string slurm_dir(const SweepLayout& layout);
std::string task_script_path(const SweepLayout& layout);
std::string task_list_path(const SweepLayout& layout, size_t array);

// task.sh and one list per array.
void write_task_files(const SweepLayout& layout, const SlurmSubmission& submission);

// `--array=` text for the indices: "0-3,7,9-10".
std::string array_indices(const SlurmArray& array);

void write_submission(const SweepLayout& layout, const SlurmSubmission& submission);
// Nothing when the sweep was never submitted to Slurm.
std::optional<SlurmSubmission> read_submission(const SweepLayout& layout);

// The last `lines` lines of a text file ("" when it cannot be read).
std::string file_tail(const std::string& path, int lines);

}  // namespace depot::harness
