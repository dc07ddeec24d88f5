#include "sim/world/sensed_frame.h"

#include "common/rng.h"
#include "sim/sensor/depth_artefacts.h"
#include "sim/sensor/kinect_model.h"

namespace depot::sim {

uint64_t sensor_seed(const Scenario& scenario, int index) {
  return derive_seed(scenario.seed, 0x5e9, static_cast<uint64_t>(index));
}

cv::Mat sense_frame(RenderedFrame& frame, const Scenario& scenario, const ColourCapture& capture,
                    bool covered, uint64_t seed) {
  const SensorSpec& sensor = scenario.sensor;
  if (sensor.ideal || covered) return frame.depth;
  apply_depth_artefacts(frame.depth, frame.bgr, sensor, seed);
  cv::Mat depth =
      misregister_depth(apply_depth_model(frame.depth, sensor, scenario.camera.f, seed), sensor);
  apply_colour_sensor(frame.bgr, sensor, capture, derive_seed(seed, 1));
  return depth;
}

}  // namespace depot::sim
