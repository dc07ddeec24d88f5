#pragma once
// Each command group registers its subcommands on the root app.
#include <CLI/CLI.hpp>

namespace depot::cli {

void register_sim_commands(CLI::App& app);
void register_slam_commands(CLI::App& app);
void register_eval_commands(CLI::App& app);
void register_sweep_commands(CLI::App& app);

}  // namespace depot::cli
