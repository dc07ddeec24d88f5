#include "sim/pipeline/render_dataset.h"

#include <chrono>

#include "common/error.h"
#include "common/interrupt.h"
#include "common/progress.h"
#include "sim/scenario/scenario_loader.h"
#include "sim/world/simulated_sequence.h"

namespace depot::sim {

void apply_overrides(Scenario& scenario, const RenderRequest& r) {
  if (r.frames) {
    if (*r.frames < 1) fail("--frames", "must be at least 1");
    scenario.frames = *r.frames;
  }
  if (r.seed) set_scenario_seed(scenario, *r.seed);
  if (r.dynamic_load) apply_dynamic_load(scenario, *r.dynamic_load);
  if (r.ideal) scenario.sensor.ideal = true;
  if (r.width) scale_camera(scenario.camera, *r.width);
}

RenderSummary render_dataset(Scenario scenario, const RenderRequest& request) {
  apply_overrides(scenario, request);
  auto start = std::chrono::steady_clock::now();
  SimulatedSequence sequence(scenario, request.gl);
  DatasetWriter writer(request.dataset, sequence.scenario(), sequence.classes(),
                       sequence.world().instances());

  RenderSummary summary;
  Progress progress("render " + scenario.name, static_cast<size_t>(sequence.frame_count()),
                    request.progress);
  RenderedFrame frame;
  FrameTruth truth;
  SequenceTimings t;
  double subframes = 0, renders = 0;
  while (sequence.next(frame, truth, &t)) {
    throw_if_interrupted(request.dataset.output);
    summary.physics_ms += t.physics_ms;
    summary.color_depth_ms += t.render.color_depth_ms;
    summary.segmentation_ms += t.render.segmentation_ms;
    summary.convert_ms += t.render.convert_ms;
    subframes += t.subframes;
    renders += t.renders;
    summary.field_ms += t.field_ms;
    writer.add(std::move(frame), truth);
    frame = RenderedFrame();
    progress.update(static_cast<size_t>(truth.index + 1));
  }
  WriterTimings w = writer.finish();
  progress.finish();
  summary.frames = sequence.frame_count();
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double n = summary.frames;
  summary.physics_ms /= n;
  summary.color_depth_ms /= n;
  summary.segmentation_ms /= n;
  summary.convert_ms /= n;
  summary.subframes = subframes / n;
  summary.renders = renders / n;
  summary.field_ms /= n;
  summary.sensor_ms = w.sensor_ms / n;
  summary.encode_write_ms = w.encode_write_ms / n;
  summary.bytes = w.bytes;
  summary.output = request.dataset.output;
  return summary;
}

}  // namespace depot::sim
