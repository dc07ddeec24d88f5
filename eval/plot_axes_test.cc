#include "eval/plot_axes.h"

#include <gtest/gtest.h>

#include "eval/colormap.h"

namespace depot::eval {
namespace {

TEST(PlotAxes, NiceStepsAreOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_DOUBLE_EQ(nice_step(1.0, 5), 0.2);
  EXPECT_DOUBLE_EQ(nice_step(0.73, 6), 0.2);
  EXPECT_DOUBLE_EQ(nice_step(0.03, 6), 0.005);
  EXPECT_DOUBLE_EQ(nice_step(45.0, 5), 10.0);
  EXPECT_DOUBLE_EQ(nice_step(0.0, 5), 1.0);
}

TEST(PlotAxes, TicksStayInsideTheRangeAndLabelCleanly) {
  const std::vector<double> ticks = ticks_within({-0.05, 0.43}, 0.1);
  ASSERT_EQ(ticks.size(), 5u);
  EXPECT_EQ(tick_label(ticks[0], 0.1), "0.0");
  EXPECT_EQ(tick_label(ticks[3], 0.1), "0.3");
  EXPECT_EQ(tick_label(-1e-12, 0.1), "0.0");
  EXPECT_EQ(tick_label(-0.25, 0.05), "-0.25");
  EXPECT_EQ(tick_label(20.0, 5.0), "20");
}

TEST(PlotAxes, RangeFromZeroEndsOnAStep) {
  const AxisRange r = nice_range_from_zero(0.0, 0.0374, 5);
  EXPECT_DOUBLE_EQ(r.lo, 0.0);
  EXPECT_NEAR(r.hi, 0.04, 1e-15);
}

TEST(PlotAxes, EqualAspectRangesUseOneScale) {
  const PlotArea area{0, 0, 400, 200};
  AxisRange x, y;
  equal_aspect_ranges(area, {0.0, 1.0}, {-3.0, 3.0}, 0.05, &x, &y);
  EXPECT_NEAR(x.span() / area.width, y.span() / area.height, 1e-12);
  EXPECT_LE(y.lo, -3.0);
  EXPECT_GE(y.hi, 3.0);
  EXPECT_NEAR(0.5 * (x.lo + x.hi), 0.5, 1e-12);
  const PlotFrame frame(area, x, y);
  EXPECT_NEAR(frame.to_pixel(x.lo, y.lo).y, 200.0, 1e-9);  // y grows upwards
  EXPECT_NEAR(frame.to_pixel(x.hi, y.hi).x, 400.0, 1e-9);
}

TEST(Colormap, ViridisEndsAndClamps) {
  EXPECT_EQ(viridis(0.0), "#440154");
  EXPECT_EQ(viridis(1.0), "#fde725");
  EXPECT_EQ(viridis(-3.0), "#440154");
  EXPECT_EQ(viridis(7.0), "#fde725");
  EXPECT_EQ(viridis_samples().size(), 11u);
}

}  // namespace
}  // namespace depot::eval
