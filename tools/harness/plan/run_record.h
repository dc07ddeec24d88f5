#pragma once
// The result record of one sweep job, written as JSON beside its outputs.
// A dataset record describes a rendered dataset (its measured dynamic load);
// a run record describes one SLAM run on it (accuracy, rejection, timing).
// Undefined figures (no rejection, too few poses) are NaN, stored as null.
#include <cmath>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

namespace depot::harness {

struct DatasetRecord {
  std::string id;
  int frames = 0;
  double moving_share_mean = 0;  // share of pixels on moving objects, mean over frames
  double moving_share_max = 0;
  double render_seconds = 0;
};

struct RunRecord {
  std::string id;
  std::string scenario;
  std::map<std::string, std::string> parameters;  // varied parameter -> level
  int seed = 1;
  std::string mode;
  bool ok = true;
  std::string error;     // why the run produced no trajectory (ok = false)
  std::string log_tail;  // a failed system's last log lines

  int frames = 0;
  int tracked = 0;  // frames with a pose in the final trajectory (states.txt: NEW_MAP, OK,
                    // RELOCALIZED); the JSON also holds tracked_share = tracked / frames
  int lost = 0;     // frames tracking reported lost (no pose)
  // The atlas (eval/maps_ate.h): frames with a pose in any map, the maps
  // holding them, and ATE over all of them with each map aligned on its own.
  int posed = 0;
  int maps = 0;
  double ate_all_maps_rmse = NAN;  // m
  int keyframes = 0;
  double ate_rmse = NAN, ate_mean = NAN, ate_median = NAN, ate_std = NAN, ate_max = NAN;  // m
  double rpe_delta_s = 1.0;
  double rpe_trans_rmse = NAN, rpe_trans_std = NAN;  // m
  double rpe_rot_rmse = NAN, rpe_rot_std = NAN;      // deg
  // Rejection vs ground truth; `precision` counts boundary points (see
  // eval/motion_truth.h) as static, `precision_without_boundary` leaves them out.
  double precision = NAN, precision_without_boundary = NAN, recall = NAN;
  // The same over the keypoints with depth only (boundary points left out):
  // only they start map points. NaN for another system's run.
  double precision_with_depth = NAN, recall_with_depth = NAN;
  long true_positive = 0, false_positive = 0, false_negative = 0, true_negative = 0;
  long false_positive_boundary = 0, true_negative_boundary = 0;  // boundary points among them
  double median_frame_ms = NAN, rejection_ms = NAN;
  double moving_share = NAN;  // from the dataset record
  double seconds = 0;         // wall time of the run
};

nlohmann::json to_json(const DatasetRecord& record);
nlohmann::json to_json(const RunRecord& record);

// Throw Error("<path>: ...") when the file is missing, corrupt or incomplete.
DatasetRecord read_dataset_record(const std::string& path);
RunRecord read_run_record(const std::string& path);

// Atomic write of a record (indented JSON).
void write_record(const std::string& path, const nlohmann::json& record);

}  // namespace depot::harness
