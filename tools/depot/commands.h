#pragma once
// Each command group registers its subcommands on the root app.
#include <CLI/CLI.hpp>

namespace depot::cli {

void register_sim_commands(CLI::App& app);
void register_slam_commands(CLI::App& app);
void register_eval_commands(CLI::App& app);
// `depot eval detector|segmenter`, added to the eval group.
void register_perception_eval_commands(CLI::App* eval_group);
// `depot eval cloud`, added to the eval group.
void register_cloud_eval_command(CLI::App* eval_group);
// `depot eval realism`, added to the eval group.
void register_realism_eval_command(CLI::App* eval_group);
// `depot eval rejection`, added to the eval group.
void register_rejection_eval_command(CLI::App* eval_group);
void register_sweep_commands(CLI::App& app);
// `depot export mcap`.
void register_export_commands(CLI::App& app);
// `depot slam vocabulary train|info`, added to the slam group.
void register_vocabulary_commands(CLI::App* slam_group);
// `depot slam map info|export`, added to the slam group.
void register_map_commands(CLI::App* slam_group);

}  // namespace depot::cli
