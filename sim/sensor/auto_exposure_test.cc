#include "sim/sensor/auto_exposure.h"

#include <cmath>

#include <gtest/gtest.h>

namespace depot::sim {
namespace {

TEST(AutoExposure, SrgbCurveRoundTrips) {
  for (double v = 0.0; v <= 1.0; v += 0.01) EXPECT_NEAR(srgb_decode(srgb_encode(v)), v, 1e-12);
  EXPECT_NEAR(srgb_encode(0.18), 0.4614, 1e-4);  // mid grey
}

TEST(AutoExposure, FixedExposureNeverMoves) {
  ExposureControl control(ExposureControlSpec{}, 0.01);
  control.observe(0.01, 1.0 / 30);
  control.observe(0.99, 1.0 / 30);
  EXPECT_DOUBLE_EQ(control.current().exposure, 0.01);
  EXPECT_DOUBLE_EQ(control.current().gain, 1.0);
  EXPECT_DOUBLE_EQ(control.current().scale, 1.0);
}

// A scene whose linear mean at the reference exposure is `scene`: the
// meter's reading at the control's current setting.
double metered(double scene, const ExposureControl& control) {
  return srgb_encode(std::min(1.0, scene * control.current().scale));
}

// After the light drops to a quarter, the loop recovers the target as a
// first-order lag of its time constant: exposure first, then gain.
TEST(AutoExposure, RecoversFromALightDropWithItsTimeConstant) {
  ExposureControlSpec spec;
  spec.automatic = true;
  spec.time_constant = 0.2;
  spec.max_exposure = 0.02;
  spec.max_gain = 4;
  const double reference = 0.01, scene = 0.18, dt = 1.0 / 30;
  spec.target = srgb_encode(scene);  // on target before the drop
  ExposureControl control(spec, reference);
  for (int i = 0; i < 10; ++i) control.observe(metered(scene, control), dt);
  EXPECT_NEAR(control.current().scale, 1.0, 1e-9);
  const double dark = scene / 4;
  const int frames_per_tau = static_cast<int>(std::lround(spec.time_constant / dt));
  for (int i = 0; i < 4 * frames_per_tau; ++i) {
    const double error_before = std::log(4.0 / control.current().scale);
    control.observe(metered(dark, control), dt);
    if (i + 1 == frames_per_tau) {
      EXPECT_NEAR(std::log(4.0 / control.current().scale), std::log(4.0) * std::exp(-1.0),
                  0.1 * std::log(4.0) * std::exp(-1.0));
    }
    EXPECT_LT(std::log(4.0 / control.current().scale), error_before);  // monotone, no overshoot
    // Gain only once the exposure is at its longest.
    if (control.current().gain > 1.0) {
      EXPECT_DOUBLE_EQ(control.current().exposure, spec.max_exposure);
    }
  }
  // Four time constants in, e^-4 of the (log) error is left.
  const double after_four = 4.0 * std::exp(-std::log(4.0) * std::exp(-4.0));
  EXPECT_NEAR(control.current().scale, after_four, 0.01);
  EXPECT_DOUBLE_EQ(control.current().exposure, 0.02);
  EXPECT_NEAR(control.current().gain, after_four * reference / spec.max_exposure, 0.005);
}

TEST(AutoExposure, ASaturatedFrameShortensTheExposureAndLimitsHold) {
  ExposureControlSpec spec;
  spec.automatic = true;
  spec.max_exposure = 0.03;
  spec.max_gain = 2;
  ExposureControl control(spec, 0.01);
  control.observe(1.0, 1.0 / 30);
  EXPECT_LT(control.current().exposure, 0.01);
  for (int i = 0; i < 300; ++i) control.observe(1.0, 1.0 / 30);
  EXPECT_DOUBLE_EQ(control.current().exposure, spec.min_exposure);
  for (int i = 0; i < 300; ++i) control.observe(0.0, 1.0 / 30);  // covered: opens fully
  EXPECT_DOUBLE_EQ(control.current().exposure, 0.03);
  EXPECT_DOUBLE_EQ(control.current().gain, 2.0);
}

}  // namespace
}  // namespace depot::sim
