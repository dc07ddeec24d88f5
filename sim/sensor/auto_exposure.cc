#include "sim/sensor/auto_exposure.h"

#include <algorithm>
#include <cmath>

namespace depot::sim {

double srgb_encode(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double encoded) {
  encoded = std::clamp(encoded, 0.0, 1.0);
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

ExposureControl::ExposureControl(const ExposureControlSpec& spec, double reference_exposure)
    : spec_(spec), reference_(reference_exposure > 0 ? reference_exposure : 1.0) {
  setting_.exposure = reference_exposure;
  setting_.gain = 1.0;
  setting_.scale = 1.0;
}

void ExposureControl::observe(double mean_output, double dt) {
  if (!spec_.automatic) return;
  // The loop works on linear light: the exposure that would have put the
  // metered mean on the target, reached by a first-order lag. A black or
  // saturated frame says little about how far off it is, so one frame moves
  // by at most 4x.
  const double measured = std::max(srgb_decode(mean_output), 1e-4);
  const double wanted = srgb_decode(spec_.target);
  const double step = std::clamp(std::log(wanted / measured), -std::log(4.0), std::log(4.0));
  const double alpha = 1.0 - std::exp(-std::max(dt, 0.0) / spec_.time_constant);
  set_total(setting_.exposure * setting_.gain * std::exp(alpha * step));
}

void ExposureControl::set_total(double exposure_times_gain) {
  const double total =
      std::clamp(exposure_times_gain, spec_.min_exposure, spec_.max_exposure * spec_.max_gain);
  setting_.exposure = std::clamp(total, spec_.min_exposure, spec_.max_exposure);
  setting_.gain = std::clamp(total / setting_.exposure, 1.0, spec_.max_gain);
  setting_.scale = setting_.exposure * setting_.gain / reference_;
}

}  // namespace depot::sim
