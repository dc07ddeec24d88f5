#pragma once
// Where one sweep job stands, from what its folder holds: the one definition
// shared by `sweep status`, `resume` (either scheduler) and `report`.
//   done         its record reads back whole and names this job. A SLAM
//                run's record may say it kept no trajectory (ok = false):
//                an outcome of the sweep, which resume keeps.
//   corrupt      a record is there but does not read back (cut short, not
//                JSON, a field missing, another job's): not done; resume
//                runs the job again and its new record replaces the bad one.
//   failed       no record, and its process failed (every attempt):
//                failed/<id>.json says how; resume runs it again.
//   not started  none of these.
// Whether a job without a record is running now is for the Slurm queue or
// the local runner to say (sweep_status.h).
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "tools/harness/plan/run_record.h"
#include "tools/harness/plan/sweep_plan.h"

namespace depot::harness {

enum class RecordState { kNotStarted, kDone, kCorrupt, kFailed };

struct JobRecordState {
  RecordState state = RecordState::kNotStarted;
  std::string problem;           // kCorrupt: "<record path>: <what is wrong>"
  std::optional<RunRecord> run;  // a done SLAM job's record
  // A done SLAM run that kept no trajectory (ok = false).
  bool without_trajectory() const { return run && !run->ok; }
};

JobRecordState job_record_state(const SweepLayout& layout, const SweepJob& job);

// The job's record reads back (done in the sense above).
bool job_finished(const SweepLayout& layout, const SweepJob& job);

// failed/<id>.json: a job whose process failed (every attempt).
std::string failure_record_path(const SweepLayout& layout, const std::string& job_id);
void write_failure_record(const SweepLayout& layout, const std::string& job_id,
                          const nlohmann::json& record);
// A job that runs again gets a new chance: its old failure no longer stands.
void remove_failure_record(const SweepLayout& layout, const std::string& job_id);

}  // namespace depot::harness
