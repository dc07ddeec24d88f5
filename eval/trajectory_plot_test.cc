#include "eval/trajectory_plot.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "eval/result_plots.h"
#include "eval/test_trajectories.h"

namespace depot::eval {
namespace {

using testing::helix_trajectory;

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

MatchedTrajectories noisy_pair(const std::string& estimate_name) {
  const auto gt = helix_trajectory(90, 30.0);
  std::vector<StampedPose> est = gt;
  for (size_t k = 0; k < est.size(); ++k) {
    est[k].pose.translation() += Eigen::Vector3d(0.01 * std::sin(0.3 * k), 0.0, 0.005 * k / 90.0);
  }
  return match_trajectories(gt, est, {}, "gt.txt", estimate_name);
}

TEST(TrajectoryPlot, AteFigureHasThePanelsAxesAndLegend) {
  const MatchedTrajectories m = noisy_pair("run <1> & more.txt");
  const std::string svg = render_trajectory_plot_svg(ate_plot(m, compute_ate(m)));
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  for (const char* text :
       {">top view (x-y)<", ">side view (x-z)<", ">x (m)<", ">y (m)<", ">z (m)<", ">time (s)<",
        ">ATE (m)<", ">ground truth<", ">start<", ">ATE over time (m)<", "linearGradient"}) {
    EXPECT_THAT(svg, ::testing::HasSubstr(text)) << text;
  }
  EXPECT_THAT(svg, ::testing::HasSubstr("run &lt;1&gt; &amp; more.txt"));  // escaped title
  EXPECT_THAT(svg, ::testing::Not(::testing::HasSubstr("run <1>")));
  EXPECT_EQ(count(svg, "<text"), count(svg, "</text>"));
  // Two views, each drawing one coloured segment per consecutive pose pair.
  EXPECT_GE(count(svg, "<line"), 2u * 89u);
  EXPECT_THAT(svg, ::testing::HasSubstr(">rmse "));
}

TEST(TrajectoryPlot, RpeFigureHasTranslationAndRotationPanels) {
  const MatchedTrajectories m = noisy_pair("est.txt");
  const RpeResult rpe = compute_rpe(m, {10.0, DeltaUnit::kFrames});
  const TrajectoryPlot plot = rpe_plot(m, rpe);
  EXPECT_EQ(plot.series.size(), 2u);
  EXPECT_TRUE(std::isnan(plot.estimate_colour_values.back()));  // no pair starts there
  const std::string path = testing::scratch_path("rpe.svg");
  write_trajectory_plot_svg(path, plot);
  const std::string svg = testing::read_whole_file(path);
  EXPECT_THAT(svg, ::testing::HasSubstr(">RPE translation over time (m)<"));
  EXPECT_THAT(svg, ::testing::HasSubstr(">RPE rotation over time (deg)<"));
}

TEST(TrajectoryPlot, RejectsInconsistentInput) {
  TrajectoryPlot plot;
  EXPECT_THROW(render_trajectory_plot_svg(plot), Error);
  plot.reference = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()};
  plot.estimate = plot.reference;
  plot.estimate_colour_values = {1.0};
  EXPECT_THROW(render_trajectory_plot_svg(plot), Error);
}

}  // namespace
}  // namespace depot::eval
