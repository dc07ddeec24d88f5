// `depot slam ablation`: the paper's Table 2 for simulated scenarios. Renders
// each scenario with several seeds, runs the four modes on each dataset, and
// writes a Markdown and CSV table of ATE RMSE (mean and std over seeds), the
// improvement of `full` over `orb` (Eq. 9), and rejection precision/recall.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include "common/error.h"
#include "common/tum_io.h"
#include "eval/ate.h"
#include "eval/improvement.h"
#include "eval/matched_trajectories.h"
#include "sim/pipeline/render_dataset.h"
#include "sim/scenario/scenario_loader.h"
#include "tools/depot/commands.h"
#include "tools/depot/paths.h"
#include "tools/depot/slam_runner.h"

namespace fs = std::filesystem;

namespace depot::cli {
namespace {

struct AblationArgs {
  std::vector<std::string> scenarios;
  std::vector<std::string> modes = {"orb", "orb+yolo", "orb+lk", "full"};
  int seeds = 3;
  int frames = 300;
  int width = 640;
  std::string output;
  bool keep_data = false;
};

struct Cell {
  std::vector<double> ate, precision, recall;
  int lost = 0;
  size_t tracked = 0, frames = 0;  // frames in the final trajectory / given
};

double mean(const std::vector<double>& v) {
  double s = 0;
  int n = 0;
  for (double x : v)
    if (std::isfinite(x)) s += x, ++n;
  return n ? s / n : NAN;
}

double stddev(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0;
  int n = 0;
  for (double x : v)
    if (std::isfinite(x)) s += (x - m) * (x - m), ++n;
  return n > 1 ? std::sqrt(s / n) : 0.0;
}

void run_ablation(const AblationArgs& a) {
  fs::create_directories(a.output);
  for (const auto& m : a.modes) slam::parse_rejection_mode(m);
  std::map<std::string, std::map<std::string, Cell>> table;  // scenario -> mode -> cell
  std::ofstream runs(fs::path(a.output) / "runs.csv");
  runs << "scenario,seed,mode,ate_rmse_m,precision,recall,lost,tracked,frames\n";
  for (const auto& name : a.scenarios) {
    sim::Scenario scenario = sim::load_scenario(resolve_scenario(name));
    for (int seed = 1; seed <= a.seeds; ++seed) {
      const std::string data =
          (fs::path(a.output) / "data" / (scenario.name + "_seed" + std::to_string(seed))).string();
      sim::RenderRequest r;
      r.dataset.output = data;
      r.dataset.overwrite = true;
      r.frames = a.frames;
      r.seed = static_cast<uint64_t>(seed);
      r.width = a.width;
      r.progress = false;
      std::fprintf(stderr, "ablation: %s seed %d: rendering %d frames\n", scenario.name.c_str(),
                   seed, a.frames);
      sim::render_dataset(scenario, r);
      const auto gt = read_tum_trajectory(data + "/groundtruth.txt");
      for (const auto& mode : a.modes) {
        RunOptions o;
        o.dataset = data;
        o.mode = mode;
        o.sync = true;  // reproducible
        o.quiet = true;
        o.detector_seed = static_cast<uint64_t>(seed);
        RunSummary s = run_sequence(o);
        auto matched = eval::match_trajectories(gt, s.trajectory, {}, "groundtruth", mode);
        const double ate = eval::compute_ate(matched).statistics.rmse;
        Cell& c = table[scenario.name][mode];
        c.ate.push_back(ate);
        c.precision.push_back(s.score.precision());
        c.recall.push_back(s.score.recall());
        c.lost += s.lost;
        c.tracked += s.trajectory.size();
        c.frames += s.frames;
        runs << scenario.name << "," << seed << "," << mode << "," << ate << ","
             << s.score.precision() << "," << s.score.recall() << "," << s.lost << ","
             << s.trajectory.size() << "," << s.frames << "\n";
        runs.flush();
        std::fprintf(stderr,
                     "ablation: %s seed %d %-8s ATE %.4f m  precision %.3f recall %.3f  lost %d\n",
                     scenario.name.c_str(), seed, mode.c_str(), ate, s.score.precision(),
                     s.score.recall(), s.lost);
      }
      if (!a.keep_data) fs::remove_all(data);
    }
  }
  // Markdown: Table 2 style.
  std::ostringstream md;
  md << "# Ablation: ATE RMSE (m), mean ± std over " << a.seeds << " seeds, " << a.frames
     << " frames at " << a.width << " px\n\n| scenario |";
  for (const auto& m : a.modes) md << " " << m << " |";
  const bool has_full = std::count(a.modes.begin(), a.modes.end(), "full") &&
                        std::count(a.modes.begin(), a.modes.end(), "orb");
  if (has_full) md << " full vs orb (Eq. 9) |";
  md << "\n|---|";
  for (size_t i = 0; i < a.modes.size() + (has_full ? 1 : 0); ++i) md << "---|";
  md << "\n";
  for (const auto& [scenario, modes] : table) {
    md << "| " << scenario << " |";
    for (const auto& m : a.modes) {
      char buf[64];
      std::snprintf(buf, sizeof(buf), " %.4f ± %.4f |", mean(modes.at(m).ate),
                    stddev(modes.at(m).ate));
      md << buf;
    }
    if (has_full) {
      char buf[32];
      std::snprintf(
          buf, sizeof(buf), " %.1f %% |",
          eval::improvement_percent(mean(modes.at("orb").ate), mean(modes.at("full").ate)));
      md << buf;
    }
    md << "\n";
  }
  md << "\n## Rejection against ground truth (simulated detector at its default error level)\n\n"
     << "| scenario | mode | precision | recall | lost frames | frames in trajectory "
        "|\n|---|---|---|---|---|---|\n";
  for (const auto& [scenario, modes] : table)
    for (const auto& m : a.modes) {
      char buf[200];
      std::snprintf(buf, sizeof(buf), "| %s | %s | %.3f ± %.3f | %.3f ± %.3f | %d | %zu of %zu |\n",
                    scenario.c_str(), m.c_str(), mean(modes.at(m).precision),
                    stddev(modes.at(m).precision), mean(modes.at(m).recall),
                    stddev(modes.at(m).recall), modes.at(m).lost, modes.at(m).tracked,
                    modes.at(m).frames);
      md << buf;
    }
  write_text_file_atomic((fs::path(a.output) / "ablation.md").string(), md.str());
  std::printf("%s\nwrote %s/ablation.md and runs.csv\n", md.str().c_str(), a.output.c_str());
}

}  // namespace

void register_ablation_command(CLI::App& slam) {
  auto args = std::make_shared<AblationArgs>();
  CLI::App* cmd =
      slam.add_subcommand("ablation", "The paper's ablation (Table 2) on simulated scenarios");
  cmd->add_option("scenarios", args->scenarios, "Scenario names or YAML files")->required();
  cmd->add_option("-o,--output", args->output, "Output folder (ablation.md, runs.csv)")->required();
  cmd->add_option("--seeds", args->seeds, "Seeds per scenario")->check(CLI::Range(1, 100));
  cmd->add_option("--frames", args->frames, "Frames per run")->check(CLI::Range(10, 100000));
  cmd->add_option("--width", args->width, "Image width")->check(CLI::Range(64, 4096));
  cmd->add_option("--modes", args->modes, "Modes")->delimiter(',');
  cmd->add_flag("--keep-data", args->keep_data, "Keep the rendered datasets");
  cmd->callback([args] { run_ablation(*args); });
}

}  // namespace depot::cli
