// depot: simulation, SLAM and evaluation for dynamic farm-depot scenes.
#include <cmath>
#include <cstdio>
#include <string>

#include <glog/logging.h>
#include <CLI/CLI.hpp>
#include <opencv2/core/utils/logger.hpp>

#include "common/error.h"
#include "common/interrupt.h"
#include "depot_version.h"
#include "tools/depot/cli_errors.h"
#include "tools/depot/commands.h"

namespace {

// CLI11's Range lets NaN through (every comparison with it is false), so
// every number option of every command refuses what is not finite here,
// once, rather than in each command.
void refuse_non_finite_numbers(CLI::App& app) {
  const CLI::Validator finite(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (end != text.c_str() && !std::isfinite(value))
          return "'" + text + "' is not a finite number";
        return "";
      },
      "", "finite");
  for (CLI::Option* option : app.get_options())
    if (option->get_type_name().find("FLOAT") != std::string::npos) option->check(finite);
  for (CLI::App* sub : app.get_subcommands({})) refuse_non_finite_numbers(*sub);
}

}  // namespace

int main(int argc, char** argv) {
  // Our errors name file and problem on one line; OpenCV's own warnings
  // (e.g. about an unreadable image) would come before it as noise.
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_ERROR);
  // Likewise Ceres' (through glog): a solver step it retries, e.g. "Linear
  // solver failure ... dense Cholesky" on a degenerate bundle, is not the
  // user's problem.
  FLAGS_minloglevel = google::GLOG_ERROR;

  CLI::App app{"depot: visual SLAM in dynamic farm-depot scenes, and the simulator that tests it"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Show help for all commands");
  app.set_version_flag("--version",
                       std::string("depot ") + DEPOT_VERSION + " (git " + DEPOT_GIT_COMMIT + ")");
  // Every option's default shows in --help.
  app.option_defaults()->always_capture_default();
  depot::cli::register_sim_commands(app);
  depot::cli::register_slam_commands(app);
  depot::cli::register_eval_commands(app);
  depot::cli::register_sweep_commands(app);
  depot::cli::register_export_commands(app);
  refuse_non_finite_numbers(app);
  depot::install_interrupt_handler();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return depot::cli::report_parse_error(app, e);
  } catch (const std::exception& e) {
    return depot::cli::report_failure(e);
  }
  return 0;
}
