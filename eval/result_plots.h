#pragma once
// Turns ATE / RPE results into the SVG figure of trajectory_plot.h.
#include "eval/ate.h"
#include "eval/matched_trajectories.h"
#include "eval/rpe.h"
#include "eval/trajectory_plot.h"

namespace depot::eval {

// Estimate as aligned for the ATE, coloured by its per-pose ATE.
TrajectoryPlot ate_plot(const MatchedTrajectories& matched, const AteResult& ate);

// Estimate SE(3)-aligned for display only (RPE itself needs no alignment),
// each pose coloured by the translational RPE of the pair it starts; panels
// of translational and rotational RPE over time.
TrajectoryPlot rpe_plot(const MatchedTrajectories& matched, const RpeResult& rpe);

}  // namespace depot::eval
