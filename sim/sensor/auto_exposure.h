#pragma once
// The colour camera's exposure time and analogue gain, fixed or under an
// auto-exposure loop that meters each frame and moves toward a target
// brightness with a control lag, as a camera driver does: the frame after a
// light change is still exposed for the old light. Plain state advanced
// frame by frame (sim/world/simulated_sequence.cc owns one).
//
// Brightness model: the render is the camera's output at the reference
// exposure (the sensor's `exposure`, or 1 when that is 0) and gain 1 under
// light level 1; exposure x gain scale the linear image from there.
#include "sim/scenario/scenario.h"

namespace depot::sim {

struct ExposureSetting {
  double exposure = 0.0;  // s (the shutter's integration time)
  double gain = 1.0;
  // Linear image scale against the render: exposure x gain / reference.
  double scale = 1.0;
};

class ExposureControl {
 public:
  // `reference_exposure`: the exposure the render stands for (s, > 0 when
  // automatic). Starts at the reference, gain 1.
  ExposureControl(const ExposureControlSpec& spec, double reference_exposure);

  const ExposureSetting& current() const { return setting_; }

  // Meters a frame exposed at current(): `mean_output` is its mean output
  // brightness (0..1, after saturation and the tone curve), `dt` the time
  // to the next frame. Moves exposure x gain toward the target by the
  // loop's lag: exposure first, gain only beyond max_exposure.
  void observe(double mean_output, double dt);

 private:
  void set_total(double exposure_times_gain);

  ExposureControlSpec spec_;
  double reference_ = 1.0;
  ExposureSetting setting_;
};

// sRGB's tone curve (IEC 61966-2-1): the camera's output encoding of
// linear light, both on 0..1.
double srgb_encode(double linear);
double srgb_decode(double encoded);

}  // namespace depot::sim
