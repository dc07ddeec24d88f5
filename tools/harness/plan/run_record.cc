#include "tools/harness/plan/run_record.h"

#include <cmath>
#include <fstream>

#include "common/error.h"
#include "common/tum_io.h"

namespace depot::harness {
namespace {

// NaN <-> null, since JSON has no NaN.
nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}
double number(const nlohmann::json& j, const char* key) {
  const auto& v = j.at(key);
  return v.is_null() ? NAN : v.get<double>();
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot open record");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    fail(path, std::string("corrupt record: ") + e.what());
  }
}

}  // namespace

nlohmann::json to_json(const DatasetRecord& r) {
  return {{"id", r.id},
          {"frames", r.frames},
          {"moving_share_mean", number(r.moving_share_mean)},
          {"moving_share_max", number(r.moving_share_max)},
          {"render_seconds", r.render_seconds}};
}

nlohmann::json to_json(const RunRecord& r) {
  return {{"id", r.id},
          {"scenario", r.scenario},
          {"parameters", r.parameters},
          {"seed", r.seed},
          {"mode", r.mode},
          {"ok", r.ok},
          {"error", r.error},
          {"log_tail", r.log_tail},
          {"frames", r.frames},
          {"tracked", r.tracked},
          {"tracked_share", number(r.frames ? static_cast<double>(r.tracked) / r.frames : NAN)},
          {"lost", r.lost},
          {"posed", r.posed},
          {"posed_share", number(r.frames ? static_cast<double>(r.posed) / r.frames : NAN)},
          {"maps", r.maps},
          {"keyframes", r.keyframes},
          {"ate",
           {{"rmse", number(r.ate_rmse)},
            {"mean", number(r.ate_mean)},
            {"median", number(r.ate_median)},
            {"std", number(r.ate_std)},
            {"max", number(r.ate_max)},
            {"all_maps_rmse", number(r.ate_all_maps_rmse)}}},
          {"rpe",
           {{"delta_s", r.rpe_delta_s},
            {"translation_rmse", number(r.rpe_trans_rmse)},
            {"translation_std", number(r.rpe_trans_std)},
            {"rotation_rmse_deg", number(r.rpe_rot_rmse)},
            {"rotation_std_deg", number(r.rpe_rot_std)}}},
          {"rejection",
           {{"precision", number(r.precision)},
            {"precision_without_boundary", number(r.precision_without_boundary)},
            {"recall", number(r.recall)},
            {"true_positive", r.true_positive},
            {"false_positive", r.false_positive},
            {"false_negative", r.false_negative},
            {"true_negative", r.true_negative},
            {"false_positive_boundary", r.false_positive_boundary},
            {"true_negative_boundary", r.true_negative_boundary},
            {"with_depth",
             {{"precision_without_boundary", number(r.precision_with_depth)},
              {"recall", number(r.recall_with_depth)}}}}},
          {"timing",
           {{"median_frame_ms", number(r.median_frame_ms)},
            {"rejection_ms", number(r.rejection_ms)},
            {"seconds", r.seconds}}},
          {"moving_share", number(r.moving_share)}};
}

DatasetRecord read_dataset_record(const std::string& path) {
  const nlohmann::json j = read_json(path);
  DatasetRecord r;
  try {
    r.id = j.at("id").get<std::string>();
    r.frames = j.at("frames").get<int>();
    r.moving_share_mean = number(j, "moving_share_mean");
    r.moving_share_max = number(j, "moving_share_max");
    r.render_seconds = j.at("render_seconds").get<double>();
  } catch (const nlohmann::json::exception& e) {
    fail(path, std::string("incomplete dataset record: ") + e.what());
  }
  return r;
}

RunRecord read_run_record(const std::string& path) {
  const nlohmann::json j = read_json(path);
  RunRecord r;
  try {
    r.id = j.at("id").get<std::string>();
    r.scenario = j.at("scenario").get<std::string>();
    r.parameters = j.at("parameters").get<std::map<std::string, std::string>>();
    r.seed = j.at("seed").get<int>();
    r.mode = j.at("mode").get<std::string>();
    r.ok = j.at("ok").get<bool>();
    r.error = j.at("error").get<std::string>();
    r.log_tail = j.value("log_tail", std::string());  // records from before systems lack it
    r.frames = j.at("frames").get<int>();
    r.tracked = j.at("tracked").get<int>();
    r.lost = j.at("lost").get<int>();
    r.keyframes = j.at("keyframes").get<int>();
    const auto& ate = j.at("ate");
    r.ate_rmse = number(ate, "rmse");
    r.ate_mean = number(ate, "mean");
    r.ate_median = number(ate, "median");
    r.ate_std = number(ate, "std");
    r.ate_max = number(ate, "max");
    // Records from before the atlas lack these: the trajectory was all.
    r.posed = j.value("posed", r.tracked);
    r.maps = j.value("maps", r.tracked > 0 ? 1 : 0);
    r.ate_all_maps_rmse = ate.contains("all_maps_rmse") ? number(ate, "all_maps_rmse") : r.ate_rmse;
    const auto& rpe = j.at("rpe");
    r.rpe_delta_s = rpe.at("delta_s").get<double>();
    r.rpe_trans_rmse = number(rpe, "translation_rmse");
    r.rpe_trans_std = number(rpe, "translation_std");
    r.rpe_rot_rmse = number(rpe, "rotation_rmse_deg");
    r.rpe_rot_std = number(rpe, "rotation_std_deg");
    const auto& rej = j.at("rejection");
    r.precision = number(rej, "precision");
    r.recall = number(rej, "recall");
    r.true_positive = rej.at("true_positive").get<long>();
    r.false_positive = rej.at("false_positive").get<long>();
    r.false_negative = rej.at("false_negative").get<long>();
    r.true_negative = rej.at("true_negative").get<long>();
    r.precision_without_boundary = number(rej, "precision_without_boundary");
    r.false_positive_boundary = rej.at("false_positive_boundary").get<long>();
    r.true_negative_boundary = rej.at("true_negative_boundary").get<long>();
    // Records written before the with-depth score have none.
    if (rej.contains("with_depth")) {
      r.precision_with_depth = number(rej.at("with_depth"), "precision_without_boundary");
      r.recall_with_depth = number(rej.at("with_depth"), "recall");
    }
    const auto& timing = j.at("timing");
    r.median_frame_ms = number(timing, "median_frame_ms");
    r.rejection_ms = number(timing, "rejection_ms");
    r.seconds = timing.at("seconds").get<double>();
    r.moving_share = number(j, "moving_share");
  } catch (const nlohmann::json::exception& e) {
    fail(path, std::string("incomplete run record: ") + e.what());
  }
  return r;
}

void write_record(const std::string& path, const nlohmann::json& record) {
  write_text_file_atomic(path, record.dump(2) + "\n");
}

}  // namespace depot::harness
