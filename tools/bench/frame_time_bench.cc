// depot_frame_time_bench: the per-frame time of tracking on every shipped
// scenario in every mode (threaded mapping, a 30 Hz camera by default):
// median, p95 and their ratio, lost frames and a lost frame's
// relocalisation time. Each scenario is rendered once (the
// first --frames frames, seed 1) and run in every mode through the runner's
// one sequence loop, the same as `depot slam run`.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/error.h"
#include "sim/pipeline/render_dataset.h"
#include "sim/scenario/scenario_loader.h"
#include "tools/runner/slam_runner.h"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  CLI::App app{"Per-frame tracking time on every shipped scenario and mode"};
  std::vector<std::string> scenarios = {"all"};
  std::vector<std::string> mode_list = {"orb", "orb+yolo", "orb+lk", "full"};
  int frames = 300;
  double rate_hz = 30;
  app.add_option("--scenarios", scenarios, "Comma-separated shipped scenarios, or all")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--modes", mode_list, "Comma-separated modes")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--frames", frames, "Frames of each scenario")
      ->check(CLI::Range(30, 100000))
      ->capture_default_str();
  app.add_option("--rate", rate_hz, "Camera rate in Hz (0 = as fast as possible)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  const std::string folder = std::string(DEPOT_SOURCE_DIR) + "/scenarios";
  const std::vector<std::string> names =
      scenarios == std::vector<std::string>{"all"} ? depot::sim::list_scenarios(folder) : scenarios;
  const fs::path scratch =
      fs::temp_directory_path() / ("depot_frame_time_bench_" + std::to_string(getpid()));
  int over_goal = 0, runs = 0;
  try {
    std::printf("depot_frame_time_bench: first %d frames of each scenario, threaded mapping, %s\n",
                frames,
                rate_hz > 0 ? (std::to_string(static_cast<int>(rate_hz)) + " Hz camera").c_str()
                            : "input as fast as possible");
    std::printf("  %-28s %-9s %9s %9s %8s %6s %10s\n", "scenario", "mode", "median ms", "p95 ms",
                "p95/med", "lost", "lost ms");
    for (const std::string& name : names) {
      const depot::sim::Scenario scenario =
          depot::sim::load_scenario(folder + "/" + name + ".yaml");
      depot::sim::RenderRequest request;
      request.dataset.output = (scratch / name).string();
      request.frames = frames;
      request.progress = false;
      std::fprintf(stderr, "rendering %d frames of %s...\n", frames, name.c_str());
      depot::sim::render_dataset(scenario, request);
      for (const std::string& mode : mode_list) {
        depot::runner::RunOptions options;
        options.input.dataset = request.dataset.output;
        options.rejection.mode = mode;
        options.input.frames = frames;
        options.quiet = true;
        options.pacing.rate_hz = rate_hz;
        const depot::runner::RunSummary s = depot::runner::run_sequence(options);
        const double ratio = s.median_ms > 0 ? s.p95_ms / s.median_ms : 0;
        over_goal += ratio > 3.0;
        ++runs;
        std::printf("  %-28s %-9s %9.2f %9.2f %8.2f %6d %10.1f\n", name.c_str(), mode.c_str(),
                    s.median_ms, s.p95_ms, ratio, s.lost, s.lost_ms);
        std::fflush(stdout);
      }
      fs::remove_all(scratch / name);
    }
  } catch (const depot::Error& e) {
    std::fprintf(stderr, "depot_frame_time_bench: error: %s\n", e.what());
    fs::remove_all(scratch);
    return 1;
  }
  fs::remove_all(scratch);
  std::printf("  %d of %d runs with p95 over 3x the median (goal: none)\n", over_goal, runs);
  return 0;
}
