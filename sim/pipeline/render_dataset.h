#pragma once
// `depot sim render`: a scenario to a dataset folder, with progress and timings.
#include <optional>
#include <string>

#include "sim/dataset/dataset_writer.h"
#include "sim/render/gl_context.h"
#include "sim/scenario/scenario.h"

namespace depot::sim {

struct RenderRequest {
  DatasetOptions dataset;
  GlBackend gl = GlBackend::kOsMesa;
  std::optional<int> frames;
  std::optional<uint64_t> seed;
  std::optional<double> dynamic_load;
  std::optional<int> width;  // rescales the camera
  bool ideal = false;
  bool progress = true;
};

struct RenderSummary {
  int frames = 0;
  double seconds = 0;
  double physics_ms = 0, color_depth_ms = 0, segmentation_ms = 0, convert_ms = 0;  // per frame
  double sensor_ms = 0, encode_write_ms = 0;  // per frame, on writer threads
  double subframes = 1;                       // sub-frames per frame (exposure, readout)
  double renders = 1;                         // colour renders per frame among them
  double field_ms = 0;                        // per frame, sub-frames by the motion field
  size_t bytes = 0;
  std::string output;
};

// Applies the request's overrides to the scenario (frames, seed, load, ideal).
void apply_overrides(Scenario& scenario, const RenderRequest& request);

RenderSummary render_dataset(Scenario scenario, const RenderRequest& request);

}  // namespace depot::sim
