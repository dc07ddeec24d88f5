#include "eval/series_plot.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"

namespace depot::eval {
namespace {

SeriesPlot two_modes(bool log_y) {
  SeriesPlot p;
  p.title = "ATE vs load";
  p.x_label = "load";
  p.y_label = "ATE RMSE (m)";
  p.x_levels = {"0", "0.5", "1", "2"};
  p.log_y = log_y;
  p.series = {{"orb", series_colour(0), "", {0.01, 0.2, 0.7, 1.1}, {0.001, 0.05, 0.1, 0.2}},
              {"full", series_colour(3), "6 3", {0.008, 0.009, NAN, 0.012}, {0, 0, NAN, 0.002}}};
  return p;
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(SeriesPlot, SquareMarkersTellASeriesOfTheSameColourApart) {
  SeriesPlot p = two_modes(false);
  p.series[1].colour = p.series[0].colour;
  p.series[1].marker = PlotMarker::kSquare;
  const std::string svg = render_series_plot_svg(p);
  EXPECT_EQ(count(svg, "<circle"), 4 + 1);  // orb's points and legend marker
  // full's 3 points and its legend marker are squares (7 px wide rects).
  EXPECT_EQ(count(svg, "width=\"7.00\" height=\"7.00\""), 3 + 1);
}

TEST(SeriesPlot, DrawsEveryDefinedPointWithLegendAndGaps) {
  const std::string svg = render_series_plot_svg(two_modes(true));
  // 4 + 3 defined points plus one legend marker per series.
  EXPECT_EQ(count(svg, "<circle"), 4 + 3 + 2);
  // full has a gap at level 1: two polylines for it, one for orb.
  EXPECT_EQ(count(svg, "<polyline"), 2);  // orb run, full's first run (second is one point)
  EXPECT_THAT(svg, ::testing::HasSubstr(">orb<"));
  EXPECT_THAT(svg, ::testing::HasSubstr(">full<"));
  EXPECT_THAT(svg, ::testing::HasSubstr("(log scale)"));
  // Decades from 0.001 to 10 cover the data.
  EXPECT_THAT(svg, ::testing::HasSubstr(">0.001<"));
  EXPECT_THAT(svg, ::testing::HasSubstr(">1<"));
}

TEST(SeriesPlot, LinearAxisHonoursAFixedRange) {
  SeriesPlot p = two_modes(false);
  p.y_lo = 0;
  p.y_hi = 1.5;
  const std::string svg = render_series_plot_svg(p);
  EXPECT_THAT(svg, ::testing::HasSubstr(">1.5<"));
  EXPECT_THAT(svg, ::testing::Not(::testing::HasSubstr("(log scale)")));
}

TEST(SeriesPlot, CategoricalLevelsAreSpacedEvenly) {
  SeriesPlot p = two_modes(true);
  p.x_levels = {"walking_xyz", "walking_rpy", "sitting_xyz", "static"};
  const std::string svg = render_series_plot_svg(p);
  EXPECT_THAT(svg, ::testing::HasSubstr(">walking_rpy<"));
}

TEST(SeriesPlot, RejectsBadInput) {
  SeriesPlot p = two_modes(true);
  p.series[0].mean.pop_back();
  EXPECT_THROW(render_series_plot_svg(p), Error);
  SeriesPlot none = two_modes(true);
  for (auto& s : none.series) s.mean.assign(4, NAN);
  EXPECT_THROW(render_series_plot_svg(none), Error);
  SeriesPlot empty;
  EXPECT_THROW(render_series_plot_svg(empty), Error);
}

}  // namespace
}  // namespace depot::eval
