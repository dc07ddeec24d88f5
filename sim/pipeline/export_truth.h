#pragma once
// `depot sim truth`: a scenario's ground truth alone (camera trajectory,
// object poses and moving flags, objects), no images: fast, for users who
// feed other SLAM systems.
#include "sim/pipeline/render_dataset.h"

namespace depot::sim {

struct TruthSummary {
  int frames = 0;
  double seconds = 0;
  std::string output;
};

// Uses the request's output, overwrite, frames, seed and load; writes
// groundtruth.txt, timestamps.txt, object_poses.txt, objects.json,
// info.json and scenario.yaml (the same bytes a rendered dataset has for
// the first and third).
TruthSummary export_truth(Scenario scenario, const RenderRequest& request);

}  // namespace depot::sim
