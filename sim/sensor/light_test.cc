#include "sim/sensor/light.h"

#include <cmath>

#include <gtest/gtest.h>

namespace depot::sim {
namespace {

// The mean by brute force: the midpoint rule on a fine grid.
double numeric_mean(const LightSpec& light, double t0, double t1) {
  const int n = 200000;
  double sum = 0;
  for (int i = 0; i < n; ++i) sum += light_level_at(light, t0 + (t1 - t0) * (i + 0.5) / n);
  return sum / n;
}

TEST(Light, EventsRampHoldAndSwitch) {
  LightSpec light;
  light.level = 2.0;
  light.events = {{1.0, 1.0}, {2.0, 0.5}, {3.0, 0.5}, {3.0, 1.0}};
  EXPECT_DOUBLE_EQ(light_level_at(light, 0.0), 2.0);   // held before the first point
  EXPECT_DOUBLE_EQ(light_level_at(light, 1.5), 1.5);   // halfway down the ramp
  EXPECT_DOUBLE_EQ(light_level_at(light, 2.99), 1.0);  // held
  EXPECT_DOUBLE_EQ(light_level_at(light, 3.0), 2.0);   // switched back on
  EXPECT_DOUBLE_EQ(light_level_at(light, 9.0), 2.0);
}

TEST(Light, MeansAreExactIntegrals) {
  LightSpec light;
  light.level = 0.8;
  light.events = {{0.01, 1.0}, {0.03, 0.2}, {0.05, 0.2}, {0.05, 0.9}};
  light.flicker = 0.3;
  light.mains_hz = 60;
  for (const auto& [t0, t1] : std::vector<std::pair<double, double>>{
           {0.0, 0.004}, {0.005, 0.045}, {0.02, 0.07}, {0.049, 0.051}, {0.06, 0.061}})
    EXPECT_NEAR(mean_light_level(light, t0, t1), numeric_mean(light, t0, t1), 1e-8)
        << t0 << " " << t1;
  EXPECT_DOUBLE_EQ(mean_light_level(light, 0.02, 0.02), light_level_at(light, 0.02));
}

TEST(Light, FlickerAveragesOutOverWholePeriodsOnly) {
  LightSpec light;
  light.flicker = 0.5;
  light.mains_hz = 50;  // 100 Hz flicker: 10 ms period
  EXPECT_NEAR(mean_light_level(light, 0.0123, 0.0223), 1.0, 1e-12);
  EXPECT_NEAR(mean_light_level(light, 0.0123, 0.0423), 1.0, 1e-12);
  EXPECT_GT(std::abs(mean_light_level(light, 0.0, 0.004) - 1.0), 0.1);
}

// A rolling shutter under flicker: bands, one per flicker period of the
// readout; an exposure of a whole flicker period has none.
TEST(Light, RollingShutterUnderFlickerGivesOneBandPerFlickerPeriod) {
  LightSpec light;
  light.flicker = 0.4;
  light.mains_hz = 50;
  const int rows = 480;
  const double readout = 0.03;  // three 10 ms flicker periods
  std::vector<double> offsets(rows);
  for (int y = 0; y < rows; ++y) offsets[y] = (static_cast<double>(y) / (rows - 1) - 0.5) * readout;
  const std::vector<float> short_exposure = row_light_levels(light, 1.0, 0.001, offsets);
  int peaks = 0;
  for (int y = 1; y + 1 < rows; ++y)
    if (short_exposure[y] > short_exposure[y - 1] && short_exposure[y] >= short_exposure[y + 1])
      ++peaks;
  EXPECT_EQ(peaks, 3);
  const auto [lo, hi] = std::minmax_element(short_exposure.begin(), short_exposure.end());
  EXPECT_GT(*hi - *lo, 0.7);  // +-0.4 nearly in full after a 1 ms exposure
  const std::vector<float> whole_period = row_light_levels(light, 1.0, 0.01, offsets);
  for (float v : whole_period) EXPECT_NEAR(v, 1.0, 1e-6);
}

}  // namespace
}  // namespace depot::sim
