// depot: simulation, SLAM and evaluation for dynamic farm-depot scenes.
#include <csignal>
#include <cstdio>

#include <CLI/CLI.hpp>

#include "common/error.h"
#include "common/interrupt.h"
#include "tools/depot/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"depot: visual SLAM in dynamic farm-depot scenes, and the simulator that tests it"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Show help for all commands");
  depot::cli::register_sim_commands(app);
  depot::cli::register_slam_commands(app);
  depot::cli::register_eval_commands(app);
  depot::cli::register_sweep_commands(app);
  depot::install_interrupt_handler();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const depot::Error& e) {
    std::fprintf(stderr, "depot: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "depot: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
