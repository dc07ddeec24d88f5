#include "sim/pipeline/export_truth.h"

#include <chrono>
#include <filesystem>
#include <fstream>

#include "common/interrupt.h"
#include "common/progress.h"
#include "common/staged_directory.h"
#include "common/tum_io.h"
#include "dataset/dataset_files.h"
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
  const std::string header = dataset::file_header_line(scenario.name);
  std::string gt = "# ground truth trajectory (camera-to-world)\n" + header +
                   "# timestamp tx ty tz qx qy qz qw\n";
  std::vector<dataset::ObjectPoseRecord> poses;
  std::string stamps = "# frame timestamps (no images were rendered)\n" + header +
                       "# rgb_timestamp depth_timestamp\n";
  Progress progress("truth " + scenario.name, static_cast<size_t>(sequence.frame_count()),
                    request.progress);
  FrameTruth truth;
  while (sequence.next_truth(truth)) {
    throw_if_interrupted(request.dataset.output);
    gt += format_tum_pose({truth.rgb_timestamp, truth.camera}) + "\n";
    for (dataset::ObjectPoseRecord& r : object_pose_records(truth)) poses.push_back(std::move(r));
    stamps += dataset::format_timestamp(truth.rgb_timestamp) + " " +
              dataset::format_timestamp(truth.depth_timestamp) + "\n";
    progress.update(static_cast<size_t>(truth.index + 1));
  }
  progress.finish();
  const fs::path root = dir.path();
  write_text_file_atomic((root / "groundtruth.txt").string(), gt);
  dataset::write_object_poses(root.string(), scenario.name, poses);
  write_text_file_atomic((root / "timestamps.txt").string(), stamps);
  dataset::write_objects(
      root.string(), objects_file(scenario.name, sequence.world().instances(), sequence.classes()));
  dataset::DatasetInfo info = scenario_info(scenario, "depot-slam simulator (ground truth only)");
  info.frames = sequence.frame_count();
  dataset::write_info(root.string(), info);
  std::ifstream src(scenario.source_path, std::ios::binary);
  write_text_file_atomic(
      (root / "scenario.yaml").string(),
      std::string((std::istreambuf_iterator<char>(src)), std::istreambuf_iterator<char>()));
  if (scenario.procedural)
    write_text_file_atomic((root / "scene.yaml").string(), scene_layout_yaml(scenario.layout));
  dir.commit();
  TruthSummary summary;
  summary.frames = sequence.frame_count();
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary.output = request.dataset.output;
  return summary;
}

}  // namespace depot::sim
