#pragma once
// Machine-readable ATE / RPE reports: inputs, options, summary figures and
// the per-pose (per-pair) errors, so other tools can re-plot or re-average.
#include <string>

#include <nlohmann/json.hpp>

#include "eval/ate.h"
#include "eval/matched_trajectories.h"
#include "eval/rpe.h"
#include "eval/statistics.h"

namespace depot::eval {

nlohmann::json statistics_json(const ErrorStatistics& statistics);

nlohmann::json ate_report_json(const MatchedTrajectories& matched, const AteResult& ate);

nlohmann::json rpe_report_json(const MatchedTrajectories& matched, const RpeResult& rpe);

// Writes the report (indented, newline-terminated) atomically.
void write_json_file(const std::string& path, const nlohmann::json& report);

}  // namespace depot::eval
