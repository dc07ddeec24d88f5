// `depot eval rejection DATASET KEYPOINTS`: any system's rejected keypoints
// (a per-keypoint file, eval/keypoint_file.h) scored against a simulated
// dataset's labels by the rule the built-in modes are scored with
// (eval/keypoint_score.h).
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/staged_file.h"
#include "eval/keypoint_score.h"
#include "eval/report_json.h"
#include "tools/depot/commands.h"
#include "tools/depot/output_paths.h"

namespace depot::cli {
namespace {

struct RejectionArgs {
  std::string dataset;
  std::string keypoints;
  std::string json;
  double scale_factor = 1.2;
};

// "undefined" when nothing was rejected (precision) or nothing moved (recall).
std::string ratio_text(double v) {
  if (!std::isfinite(v)) return "undefined";
  return fmt::format("{:.4f}", v);
}

nlohmann::json ratio_json(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nullptr;
}

void run_rejection_eval(const RejectionArgs& a) {
  OutputPaths outputs;
  outputs.add_input("KEYPOINTS", a.keypoints);
  outputs.add_input_folder("DATASET", a.dataset);
  outputs.add_file("--json", a.json);
  outputs.check();
  if (!a.json.empty()) check_output_file(a.json);
  const eval::KeypointFileScore result =
      eval::score_dataset_keypoints(a.dataset, a.keypoints, static_cast<float>(a.scale_factor));
  const eval::RejectionScore& s = result.score;

  std::printf("rejection of %s against the labels of %s\n", a.keypoints.c_str(), a.dataset.c_str());
  std::printf("  keypoints      %zu in %zu of %zu frames (octave %s, scale factor %g)\n",
              result.keypoints, result.frames, result.dataset_frames,
              result.has_octave ? "from the file" : "0: no octave column", a.scale_factor);
  std::printf("  true positive  %ld (rejected, on a moving object)\n", s.true_positive);
  std::printf("  false positive %ld (rejected, static; %ld of them boundary points)\n",
              s.false_positive, s.boundary_false_positive);
  std::printf("  false negative %ld (kept, on a moving object)\n", s.false_negative);
  std::printf("  true negative  %ld (kept, static; %ld of them boundary points)\n", s.true_negative,
              s.boundary_true_negative);
  std::printf("  precision      %s (boundary points counted as static)\n",
              ratio_text(s.precision()).c_str());
  std::printf("  precision      %s without boundary points\n",
              ratio_text(s.precision_without_boundary()).c_str());
  std::printf("  recall         %s\n", ratio_text(s.recall()).c_str());
  // By the mover's class: a carried crate (an a-priori static class) beside
  // the people, an animal no detector names.
  for (const auto& [name, c] : result.moving_by_class)
    std::printf("  recall %-7s %s (%ld of %ld keypoints on moving %s rejected)\n", name.c_str(),
                ratio_text(c.recall()).c_str(), c.rejected, c.moving, name.c_str());
  if (a.json.empty()) return;
  nlohmann::json by_class = nlohmann::json::object();
  for (const auto& [name, c] : result.moving_by_class)
    by_class[name] = {
        {"moving", c.moving}, {"rejected", c.rejected}, {"recall", ratio_json(c.recall())}};
  const nlohmann::json doc = {
      {"dataset", a.dataset},
      {"keypoints", a.keypoints},
      {"scale_factor", a.scale_factor},
      {"octave_column", result.has_octave},
      {"keypoints_scored", result.keypoints},
      {"frames_scored", result.frames},
      {"dataset_frames", result.dataset_frames},
      {"true_positive", s.true_positive},
      {"false_positive", s.false_positive},
      {"false_negative", s.false_negative},
      {"true_negative", s.true_negative},
      {"boundary_false_positive", s.boundary_false_positive},
      {"boundary_true_negative", s.boundary_true_negative},
      {"precision", ratio_json(s.precision())},
      {"precision_without_boundary", ratio_json(s.precision_without_boundary())},
      {"recall", ratio_json(s.recall())},
      {"recall_by_class", by_class}};
  eval::write_json_file(a.json, doc);
  std::printf("  json           %s\n", a.json.c_str());
}

}  // namespace

void register_rejection_eval_command(CLI::App* eval_group) {
  auto args = std::make_shared<RejectionArgs>();
  CLI::App* cmd = eval_group->add_subcommand(
      "rejection",
      "Any system's kept and rejected keypoints (a per-keypoint CSV) scored against a simulated "
      "dataset's labels, as `depot slam run` scores its own rejection");
  cmd->add_option("DATASET", args->dataset, "The simulated dataset the keypoints were found in")
      ->required();
  cmd->add_option("KEYPOINTS", args->keypoints,
                  "Per-keypoint CSV with a header: timestamp,x,y,kept (0 = rejected); optional "
                  "octave, response, set; other columns ignored (`depot slam run --keypoints` "
                  "writes one)")
      ->required();
  cmd->add_option("--json", args->json, "Also write the figures as JSON");
  cmd->add_option("--scale-factor", args->scale_factor,
                  "The ORB pyramid's scale between levels: the boundary rule's circle at a "
                  "keypoint's octave")
      ->check(CLI::Range(1.01, 2.0))
      ->capture_default_str();
  cmd->callback([args] { run_rejection_eval(*args); });
}

}  // namespace depot::cli
