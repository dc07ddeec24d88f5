#include "eval/report_json.h"

#include "common/tum_io.h"

namespace depot::eval {
namespace {

using nlohmann::json;

json inputs_json(const MatchedTrajectories& matched) {
  return {{"reference", matched.reference_name},
          {"estimate", matched.estimate_name},
          {"reference_poses", matched.reference_size},
          {"estimate_poses", matched.estimate_size},
          {"matched_poses", matched.size()},
          {"association",
           {{"max_difference_s", matched.association.max_difference},
            {"offset_s", matched.association.offset}}}};
}

json alignment_json(AlignmentKind kind, const SimilarityTransform& t) {
  json rotation = json::array();
  for (int r = 0; r < 3; ++r) {
    rotation.push_back({t.rotation(r, 0), t.rotation(r, 1), t.rotation(r, 2)});
  }
  return {{"kind", to_string(kind)},
          {"scale", t.scale},
          {"rotation", rotation},
          {"translation", {t.translation.x(), t.translation.y(), t.translation.z()}}};
}

}  // namespace

json statistics_json(const ErrorStatistics& s) {
  return {{"count", s.count}, {"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median},
          {"std", s.std},     {"min", s.min},   {"max", s.max},   {"sse", s.sse}};
}

json ate_report_json(const MatchedTrajectories& matched, const AteResult& ate) {
  json report = inputs_json(matched);
  report["metric"] = "ate";
  report["unit"] = "m";
  report["alignment"] = alignment_json(ate.alignment_kind, ate.alignment);
  report["statistics"] = statistics_json(ate.statistics);
  report["per_pose"] = {{"timestamps", ate.stamps}, {"errors", ate.errors}};
  return report;
}

json rpe_report_json(const MatchedTrajectories& matched, const RpeResult& rpe) {
  json report = inputs_json(matched);
  report["metric"] = "rpe";
  report["delta"] = rpe.selection.delta;
  report["delta_unit"] = to_string(rpe.selection.unit);
  report["pairs"] = rpe.pairs.size();
  report["translation"] = {{"unit", "m"},
                           {"statistics", statistics_json(rpe.translation_statistics)}};
  report["rotation"] = {{"unit", "deg"}, {"statistics", statistics_json(rpe.rotation_statistics)}};
  json first, second;
  for (const PosePair& p : rpe.pairs) {
    first.push_back(p.i);
    second.push_back(p.j);
  }
  report["per_pair"] = {{"timestamps", rpe.stamps},
                        {"i", first},
                        {"j", second},
                        {"translation", rpe.translation},
                        {"rotation", rpe.rotation}};
  return report;
}

void write_json_file(const std::string& path, const json& report) {
  write_text_file_atomic(path, report.dump(2) + "\n");
}

}  // namespace depot::eval
