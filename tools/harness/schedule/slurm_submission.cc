#include "tools/harness/schedule/slurm_submission.h"

#include <sys/stat.h>

#include <deque>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/staged_file.h"

namespace fs = std::filesystem;

namespace depot::harness {
namespace {

// Arguments: ATTEMPTS TASK_LIST LOG_DIR COMMAND...; runs `COMMAND <id>` for
// the id on line SLURM_ARRAY_TASK_ID + 1 of TASK_LIST. Paths come as
// arguments, never pasted into the text, so no folder name can inject shell.
// A failed attempt is retried; a cancelled task (SIGTERM to every process of
// the job) is not: the trap runs once the current attempt has ended.
constexpr const char* kTaskScript = R"(#!/bin/sh
# One Slurm array task of a depot sweep (written by `depot sweep run --scheduler slurm`).
attempts="$1"; list="$2"; logs="$3"; shift 3
id=$(sed -n "$((SLURM_ARRAY_TASK_ID + 1))p" "$list")
if [ -z "$id" ]; then
  echo "depot-slurm: no sweep job at index $SLURM_ARRAY_TASK_ID of $list" >&2
  exit 2
fi
log="$logs/$id.log"
mkdir -p "$logs" && : >"$log" || exit 2
trap 'echo "depot-slurm: cancelled" >>"$log"; exit 143' TERM INT
attempt=1
while :; do
  "$@" "$id" >>"$log" 2>&1
  code=$?
  [ "$code" -eq 0 ] && exit 0
  echo "depot-slurm: attempt $attempt of $attempts exited $code" >>"$log"
  [ "$attempt" -ge "$attempts" ] && exit "$code"
  attempt=$((attempt + 1))
done
)";

const char* kind_name(JobKind kind) {
  return kind == JobKind::kRender ? "render" : "slam";
}

void write_text(const std::string& path, const std::string& text) {
  StagedFile file(path);
  file.stream() << text;
  file.commit();
}

}  // namespace

std::string slurm_dir(const SweepLayout& layout) {
  return layout.root + "/slurm";
}
std::string task_script_path(const SweepLayout& layout) {
  return slurm_dir(layout) + "/task.sh";
}
std::string task_list_path(const SweepLayout& layout, size_t array) {
  return slurm_dir(layout) + "/array-" + std::to_string(array) + ".tasks";
}

void write_task_files(const SweepLayout& layout, const SlurmSubmission& submission) {
  fs::create_directories(slurm_dir(layout) + "/out");
  write_text(task_script_path(layout), kTaskScript);
  chmod(task_script_path(layout).c_str(), 0755);
  for (size_t k = 0; k < submission.arrays.size(); ++k) {
    std::string lines;
    int next = 0;
    for (const auto& [index, id] : submission.arrays[k].tasks) {
      for (; next < index; ++next) lines += "\n";  // indices of other arrays' datasets
      lines += id + "\n";
      next = index + 1;
    }
    write_text(task_list_path(layout, k), lines);
  }
}

std::string array_indices(const SlurmArray& array) {
  std::string text;
  auto it = array.tasks.begin();
  while (it != array.tasks.end()) {
    const int first = it->first;
    int last = first;
    for (++it; it != array.tasks.end() && it->first == last + 1; ++it) last = it->first;
    if (!text.empty()) text += ",";
    text += std::to_string(first) + (last > first ? "-" + std::to_string(last) : "");
  }
  return text;
}

void write_submission(const SweepLayout& layout, const SlurmSubmission& submission) {
  nlohmann::json arrays = nlohmann::json::array();
  for (const SlurmArray& a : submission.arrays) {
    nlohmann::json tasks = nlohmann::json::object();
    for (const auto& [index, id] : a.tasks) tasks[std::to_string(index)] = id;
    arrays.push_back({{"job_id", a.job_id},
                      {"kind", kind_name(a.kind)},
                      {"after_render", a.after_render},
                      {"tasks", tasks}});
  }
  write_text(slurm_dir(layout) + "/submission.json",
             nlohmann::json{{"arrays", arrays}}.dump(2) + "\n");
}

std::optional<SlurmSubmission> read_submission(const SweepLayout& layout) {
  const std::string path = slurm_dir(layout) + "/submission.json";
  std::ifstream in(path);
  if (!in) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    SlurmSubmission s;
    for (const auto& a : j.at("arrays")) {
      SlurmArray array;
      array.job_id = a.at("job_id").get<std::string>();
      array.kind = a.at("kind").get<std::string>() == "render" ? JobKind::kRender : JobKind::kSlam;
      array.after_render = a.at("after_render").get<bool>();
      for (const auto& [index, id] : a.at("tasks").items())
        array.tasks[std::stoi(index)] = id.get<std::string>();
      s.arrays.push_back(array);
    }
    return s;
  } catch (const std::exception& e) {
    fail(path, std::string("corrupt: ") + e.what());
  }
}

std::string file_tail(const std::string& path, int lines) {
  std::ifstream in(path);
  std::deque<std::string> last;
  for (std::string line; std::getline(in, line);) {
    last.push_back(line);
    if (static_cast<int>(last.size()) > lines) last.pop_front();
  }
  std::string text;
  for (const auto& line : last) text += line + "\n";
  return text;
}

}  // namespace depot::harness
