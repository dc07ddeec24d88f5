#pragma once
// What the simulated RGB-D sensor makes of an exact frame: depth artefacts
// (from the exact colour, so before its noise), the depth model and the
// colour-depth misregistration, then the colour sensor. One chain for every
// consumer: the dataset writer (PNG files) and the Python module (arrays).
#include <cstdint>

#include <opencv2/core.hpp>

#include "sim/render/renderer.h"
#include "sim/scenario/scenario.h"
#include "sim/sensor/colour_pipeline.h"

namespace depot::sim {

// The seed of frame `index`'s sensor noise.
uint64_t sensor_seed(const Scenario& scenario, int index);

// Applies the sensor to frame.bgr in place and returns the sensed depth
// (metres, CV_32F). An ideal sensor or a covered camera (which sees nothing,
// not noise) leaves the frame exact.
cv::Mat sense_frame(RenderedFrame& frame, const Scenario& scenario, const ColourCapture& capture,
                    bool covered, uint64_t seed);

}  // namespace depot::sim
