#pragma once
// The scene's light level over time: one factor on every light of the scene
// (MuJoCo's renders are linear in their lights, so the factor scales the
// linear image), from a base level, scripted events (dimming, switching)
// and mains flicker. Plain functions of time; the colour pipeline
// (sim/sensor/colour_pipeline.h) applies the level each row saw.
#include <vector>

#include "sim/scenario/scenario.h"

namespace depot::sim {

// The light level at `t` (s since the first frame).
double light_level_at(const LightSpec& light, double t);

// The mean light level over [t0, t1] (the level at t0 when t1 <= t0),
// integrated exactly: piecewise linear events times the flicker's cosine.
double mean_light_level(const LightSpec& light, double t0, double t1);

// The mean level each image row saw: row y's exposure window is centred
// `row_offsets[y]` after `t` (s since the first frame; sim/sensor/shutter.h)
// and lasts `exposure` seconds. A rolling shutter under flicker gives bands.
std::vector<float> row_light_levels(const LightSpec& light, double t, double exposure,
                                    const std::vector<double>& row_offsets);

}  // namespace depot::sim
