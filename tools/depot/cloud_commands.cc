// `depot eval cloud CLOUD --dataset D --trajectory T [--static S]`: a static
// map's point cloud scored against a simulated dataset's truth
// (tools/perception/cloud_eval.h).
#include <cstdio>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/staged_file.h"
#include "tools/depot/commands.h"
#include "tools/depot/output_paths.h"
#include "tools/perception/cloud_eval.h"

namespace depot::cli {
namespace {

struct CloudArgs {
  perception::CloudScoreOptions options;
  std::string json;
};

void run_cloud_eval(const CloudArgs& a) {
  OutputPaths outputs;
  outputs.add_input("CLOUD", a.options.cloud);
  outputs.add_input("--trajectory", a.options.trajectory);
  outputs.add_input_folder("--dataset", a.options.dataset);
  outputs.add_input_folder("--static", a.options.static_dataset);
  outputs.add_file("--json", a.json);
  outputs.check();
  if (!a.json.empty()) check_output_file(a.json);
  const perception::CloudScore s = perception::score_static_cloud(a.options);
  std::printf("%s: %zu points (aligned by the trajectory, ATE %.4f m)\n", a.options.cloud.c_str(),
              s.points, s.alignment_rmse);
  std::printf("on moving objects: %zu points (%.2f %%), checked in %zu frames", s.on_moving,
              100.0 * s.on_moving_share(), s.frames_checked);
  for (const auto& [name, n] : s.on_moving_by_class)
    std::printf("%s %s %zu", &name == &s.on_moving_by_class.begin()->first ? ";" : ",",
                name.c_str(), n);
  std::printf("\n");
  if (s.has_accuracy)
    std::printf(
        "distance to the true static surface (%zu points): median %.4f m, mean %.4f m, p90 %.4f "
        "m, max %.4f m; %.1f %% within %.3f m\n",
        s.surface_points, s.distance.median, s.distance.mean, s.p90_m, s.distance.max,
        100.0 * s.near_share, a.options.near_m);
  if (a.json.empty()) return;
  nlohmann::json doc = {{"cloud", a.options.cloud},
                        {"dataset", a.options.dataset},
                        {"trajectory", a.options.trajectory},
                        {"points", s.points},
                        {"on_moving", s.on_moving},
                        {"on_moving_share", s.on_moving_share()},
                        {"on_moving_by_class", s.on_moving_by_class},
                        {"frames_checked", s.frames_checked},
                        {"alignment_ate_rmse_m", s.alignment_rmse}};
  if (s.has_accuracy)
    doc["accuracy"] = {{"static_dataset", a.options.static_dataset},
                       {"surface_points", s.surface_points},
                       {"median_m", s.distance.median},
                       {"mean_m", s.distance.mean},
                       {"rmse_m", s.distance.rmse},
                       {"p90_m", s.p90_m},
                       {"max_m", s.distance.max},
                       {"near_m", a.options.near_m},
                       {"near_share", s.near_share}};
  StagedFile json(a.json);
  json.stream() << doc.dump(2) << "\n";
  json.commit();
  std::printf("wrote %s\n", a.json.c_str());
}

}  // namespace

void register_cloud_eval_command(CLI::App* eval_group) {
  auto args = std::make_shared<CloudArgs>();
  perception::CloudScoreOptions& o = args->options;
  CLI::App* cmd = eval_group->add_subcommand(
      "cloud",
      "A static map's point cloud against a simulated dataset's truth: share of points on moving "
      "objects, distance to the true static surface");
  cmd->add_option("CLOUD", o.cloud, "Point cloud (PLY: slam run --dense-map, slam map export)")
      ->required();
  cmd->add_option("--dataset", o.dataset, "The simulated dataset the cloud was made from")
      ->required();
  cmd->add_option("--trajectory", o.trajectory,
                  "The run's trajectory (TUM): aligned to the ground truth, it brings the cloud "
                  "into the truth's world")
      ->required();
  cmd->add_option("--static", o.static_dataset,
                  "The static render of the same scenario and seed (`depot sim render SCENARIO "
                  "--load 0 --ideal`): also the distance to the true surface");
  cmd->add_option("--every", o.every, "Look for movers in every n-th frame")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--static-every", o.static_every, "Lift every n-th frame of the static render")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--near", o.near_m, "Report the share of points closer than this (m)")
      ->check(CLI::Range(0.0001, 10.0))
      ->capture_default_str();
  cmd->add_option("--static-tolerance", o.static_tolerance_m,
                  "With --static: a point this close (m) to the true static surface is the "
                  "static world's, not a mover's")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--json", args->json, "Write the figures as JSON");
  cmd->add_flag("-q,--quiet", o.quiet, "No progress line");
  cmd->callback([args] { run_cloud_eval(*args); });
}

}  // namespace depot::cli
