#pragma once
// Runs a program to completion and captures what it prints: for the short
// commands of a cluster scheduler (sbatch, squeue, scancel, sinfo). The
// program gets its arguments as argv (no shell) and is found on PATH.
#include <optional>
#include <string>
#include <vector>

namespace depot::harness {

struct CommandOutput {
  int exit_code = 0;  // or 128 + signal number
  std::string out, err;
};

// Throws Error when the program cannot be started.
CommandOutput run_for_output(const std::vector<std::string>& argv);

// The full path of an executable `name` on PATH, if there is one.
std::optional<std::string> find_on_path(const std::string& name);

}  // namespace depot::harness
