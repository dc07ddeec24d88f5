#pragma once
// Each command group registers its subcommands on the root app.
#include <CLI/CLI.hpp>

namespace depot::cli {

void register_sim_commands(CLI::App& app);
void register_slam_commands(CLI::App& app);
// `depot slam ablation` (registered under the slam group).
void register_ablation_command(CLI::App& slam);
void register_eval_commands(CLI::App& app);

}  // namespace depot::cli
