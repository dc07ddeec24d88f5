#include "sim/pipeline/export_truth.h"

#include <chrono>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/interrupt.h"
#include "common/progress.h"
#include "common/staged_directory.h"
#include "common/tum_io.h"
#include "sim/dataset/dataset_writer.h"
#include "sim/dataset/truth_files.h"
#include "sim/world/simulated_sequence.h"

namespace fs = std::filesystem;

namespace depot::sim {

TruthSummary export_truth(Scenario scenario, const RenderRequest& request) {
  apply_overrides(scenario, request);
  const auto start = std::chrono::steady_clock::now();
  SimulatedSequence sequence(scenario, request.gl, /*render=*/false);
  StagedDirectory dir(request.dataset.output, simulator_output_kind(), request.dataset.overwrite);
  const std::string header = "# file: '" + scenario.name + "' (depot-slam simulator)\n";
  std::string gt = "# ground truth trajectory (camera-to-world)\n" + header +
                   "# timestamp tx ty tz qx qy qz qw\n";
  std::string poses =
      object_poses_header() + header + "# timestamp id tx ty tz qx qy qz qw moving\n";
  std::string stamps = "# frame timestamps (no images were rendered)\n" + header +
                       "# rgb_timestamp depth_timestamp\n";
  Progress progress("truth " + scenario.name, static_cast<size_t>(sequence.frame_count()),
                    request.progress);
  FrameTruth truth;
  while (sequence.next_truth(truth)) {
    throw_if_interrupted(request.dataset.output);
    gt += format_tum_pose({truth.rgb_timestamp, truth.camera}) + "\n";
    poses += object_pose_lines(truth);
    stamps += format_timestamp(truth.rgb_timestamp) + " " +
              format_timestamp(truth.depth_timestamp) + "\n";
    progress.update(static_cast<size_t>(truth.index + 1));
  }
  progress.finish();
  const fs::path root = dir.path();
  write_text_file_atomic((root / "groundtruth.txt").string(), gt);
  write_text_file_atomic((root / "object_poses.txt").string(), poses);
  write_text_file_atomic((root / "timestamps.txt").string(), stamps);
  write_text_file_atomic(
      (root / "objects.json").string(),
      objects_json(scenario.name, sequence.world().instances(), sequence.classes()));
  nlohmann::json info = {{"generator", "depot-slam simulator (ground truth only)"},
                         {"scenario", scenario.name},
                         {"seed", scenario.seed},
                         {"frames", sequence.frame_count()},
                         {"dynamic_load", scenario.dynamic_load},
                         {"actors_style", scenario.actors_style},
                         {"props_style", scenario.props_style},
                         {"motion", scenario.motion.type}};
  info["world_seed"] = scenario.world_seed();
  write_text_file_atomic((root / "info.json").string(), info.dump(1) + "\n");
  std::ifstream src(scenario.source_path, std::ios::binary);
  write_text_file_atomic(
      (root / "scenario.yaml").string(),
      std::string((std::istreambuf_iterator<char>(src)), std::istreambuf_iterator<char>()));
  dir.commit();
  TruthSummary summary;
  summary.frames = sequence.frame_count();
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary.output = request.dataset.output;
  return summary;
}

}  // namespace depot::sim
