#include "tools/harness/plan/sweep_job_state.h"

#include <filesystem>

#include "common/error.h"

namespace fs = std::filesystem;

namespace depot::harness {

JobRecordState job_record_state(const SweepLayout& layout, const SweepJob& job) {
  JobRecordState s;
  const std::string path =
      job.kind == JobKind::kRender ? layout.dataset_record(job.id) : layout.run_record(job.id);
  std::error_code ec;
  if (fs::exists(path, ec)) {
    try {
      std::string id;
      if (job.kind == JobKind::kRender) {
        id = read_dataset_record(path).id;
      } else {
        s.run = read_run_record(path);
        id = s.run->id;
      }
      if (id != job.id) fail(path, "the record of job '" + id + "', not of '" + job.id + "'");
      s.state = RecordState::kDone;
      return s;
    } catch (const Error& e) {
      // read_*_record name the path themselves: "<path>: <problem>".
      s.state = RecordState::kCorrupt;
      s.problem = e.what();
      s.run.reset();
      return s;
    }
  }
  if (fs::exists(failure_record_path(layout, job.id), ec)) s.state = RecordState::kFailed;
  return s;
}

bool job_finished(const SweepLayout& layout, const SweepJob& job) {
  return job_record_state(layout, job).state == RecordState::kDone;
}

std::string failure_record_path(const SweepLayout& layout, const std::string& job_id) {
  return (fs::path(layout.root) / "failed" / (job_id + ".json")).string();
}

void write_failure_record(const SweepLayout& layout, const std::string& job_id,
                          const nlohmann::json& record) {
  const std::string path = failure_record_path(layout, job_id);
  fs::create_directories(fs::path(path).parent_path());
  write_record(path, record);
}

void remove_failure_record(const SweepLayout& layout, const std::string& job_id) {
  std::error_code ec;
  fs::remove(failure_record_path(layout, job_id), ec);
}

}  // namespace depot::harness
