#include "tools/harness/plan/sweep_plan.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "common/error.h"
#include "common/tum_io.h"
#include "slam/reject/rejection_filter.h"
#include "slam/reject/rejection_settings.h"
#include "tools/system/system_spec.h"

namespace fs = std::filesystem;

namespace depot::harness {
std::string file_safe(const std::string& text) {
  std::string out = text;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '+' &&
        c != '_')
      c = '_';
  return out;
}

bool parameter_affects_mode(const ParameterKey& parameter, const std::string& mode) {
  // Another program has its own settings: only the scenario reaches it.
  if (system::is_system_mode(mode)) return parameter.target == ParameterTarget::kScenario;
  const slam::RejectionMode m = slam::parse_rejection_mode(mode);
  switch (parameter.target) {
    case ParameterTarget::kScenario:
      return true;
    case ParameterTarget::kDetector:
    case ParameterTarget::kDetectorChoice:
      return slam::mode_uses_detector(m);
    case ParameterTarget::kRejection: {
      // The modes the setting acts in (slam/reject/rejection_settings.h);
      // sweeps check every key before they plan.
      const slam::RejectionSetting* setting = slam::find_rejection_setting(parameter.key);
      return setting ? setting->acts_in(m)
                     : m == slam::RejectionMode::kFull || m == slam::RejectionMode::kMasked;
    }
  }
  return true;
}

std::vector<std::pair<std::string, std::string>> run_levels(const SweepSpec& spec,
                                                            const SweepCell& cell,
                                                            const std::string& mode) {
  std::vector<std::pair<std::string, std::string>> out;
  for (size_t k = 0; k < spec.vary.size(); ++k)
    if (parameter_affects_mode(resolve_parameter(spec.vary[k].name), mode))
      out.emplace_back(spec.vary[k].name, cell.levels[k]);
  return out;
}

SweepPlan make_sweep_plan(const SweepSpec& spec) {
  validate(spec, "sweep");
  SweepPlan plan;
  plan.spec = spec;
  size_t combinations = 1;
  for (const auto& p : spec.vary) combinations *= p.values.size();
  // A dataset depends only on the scenario's settings: cells that differ in
  // detector or rejection levels alone share their renders.
  std::vector<std::string> dataset_keys;
  std::set<std::string> ids;
  for (size_t s = 0; s < spec.scenarios.size(); ++s) {
    for (size_t c = 0; c < combinations; ++c) {
      SweepCell cell;
      cell.scenario = s;
      cell.id = file_safe(spec.scenarios[s].name);
      cell.label = spec.scenarios[s].name;
      std::string dataset_key = cell.id;
      size_t rest = c;
      // The last parameter varies fastest.
      std::vector<std::string> levels(spec.vary.size());
      for (size_t k = spec.vary.size(); k-- > 0;) {
        levels[k] = spec.vary[k].values[rest % spec.vary[k].values.size()];
        rest /= spec.vary[k].values.size();
      }
      for (size_t k = 0; k < spec.vary.size(); ++k) {
        const std::string part = "__" + file_safe(spec.vary[k].name) + "-" + file_safe(levels[k]);
        cell.id += part;
        if (resolve_parameter(spec.vary[k].name).target == ParameterTarget::kScenario)
          dataset_key += part;
        cell.label += " " + spec.vary[k].name + "=" + levels[k];
      }
      if (!ids.insert(cell.id).second)
        fail("--vary", "two cells would share the folder '" + cell.id +
                           "' (levels that differ only in punctuation)");
      cell.levels = levels;
      plan.cells.push_back(cell);
      dataset_keys.push_back(dataset_key);
    }
  }
  std::map<std::string, size_t> render_of;  // dataset id -> index in plan.jobs
  for (size_t c = 0; c < plan.cells.size(); ++c)
    for (int seed = 1; seed <= spec.seeds; ++seed) {
      const std::string dataset_id = dataset_keys[c] + "__s" + std::to_string(seed);
      if (render_of.count(dataset_id)) continue;
      SweepJob job;
      job.kind = JobKind::kRender;
      job.cell = c;
      job.seed = seed;
      job.id = job.dataset_id = dataset_id;
      job.cells = {c};
      render_of[dataset_id] = plan.jobs.size();
      plan.jobs.push_back(job);
    }
  std::map<std::string, size_t> run_of;  // run id -> index in plan.jobs
  for (size_t c = 0; c < plan.cells.size(); ++c)
    for (int seed = 1; seed <= spec.seeds; ++seed)
      for (const auto& mode : spec.modes) {
        // The run's id names only the levels that matter to its mode.
        std::string run_key = file_safe(spec.scenarios[plan.cells[c].scenario].name);
        for (const auto& [name, level] : run_levels(spec, plan.cells[c], mode))
          run_key += "__" + file_safe(name) + "-" + file_safe(level);
        const std::string id = run_key + "__s" + std::to_string(seed) + "__" + file_safe(mode);
        if (auto it = run_of.find(id); it != run_of.end()) {
          plan.jobs[it->second].cells.push_back(c);
          continue;
        }
        SweepJob job;
        job.kind = JobKind::kSlam;
        job.cell = c;
        job.cells = {c};
        job.seed = seed;
        job.mode = mode;
        if (system::is_system_mode(mode)) job.system_file = system_file(spec, mode);
        job.dataset_id = dataset_keys[c] + "__s" + std::to_string(seed);
        job.id = id;
        run_of[id] = plan.jobs.size();
        plan.jobs.push_back(job);
      }
  return plan;
}

const SweepJob& find_job(const SweepPlan& plan, const std::string& id, const std::string& sweep) {
  for (const auto& job : plan.jobs)
    if (job.id == id) return job;
  fail(sweep, "no job '" + id + "' in this sweep");
}

std::vector<YamlOverride> cell_overrides(const SweepPlan& plan, const SweepCell& cell,
                                         ParameterTarget target) {
  std::vector<YamlOverride> out;
  for (const auto& p : plan.spec.fixed) {
    const ParameterKey key = resolve_parameter(p.name);
    if (key.target == target) out.push_back({key.key, p.values.front()});
  }
  for (size_t k = 0; k < plan.spec.vary.size(); ++k) {
    const ParameterKey key = resolve_parameter(plan.spec.vary[k].name);
    if (key.target == target) out.push_back({key.key, cell.levels[k]});
  }
  return out;
}

std::string SweepLayout::spec_file() const {
  return (fs::path(root) / "sweep.json").string();
}
std::string SweepLayout::dataset_dir(const std::string& id) const {
  return (fs::path(root) / "data" / id).string();
}
std::string SweepLayout::dataset_record(const std::string& id) const {
  return (fs::path(root) / "data" / (id + ".json")).string();
}
std::string SweepLayout::dataset_preview(const std::string& id) const {
  return (fs::path(root) / "data" / (id + ".jpg")).string();
}
std::string SweepLayout::run_dir(const std::string& id) const {
  return (fs::path(root) / "runs" / id).string();
}
std::string SweepLayout::run_record(const std::string& id) const {
  return (fs::path(run_dir(id)) / "result.json").string();
}
std::string SweepLayout::log_file(const std::string& job_id) const {
  return (fs::path(root) / "logs" / (job_id + ".log")).string();
}
std::string SweepLayout::report_dir() const {
  return (fs::path(root) / "report").string();
}

SweepSpec read_spec(const SweepLayout& layout) {
  const std::string path = layout.spec_file();
  std::ifstream in(path);
  if (!in) fail(path, "cannot open (not a sweep folder?)");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    fail(path, std::string("corrupt sweep description: ") + e.what());
  }
  return sweep_spec_from_json(j, path);
}

void write_or_check_spec(const SweepLayout& layout, const SweepSpec& spec) {
  const nlohmann::json wanted = to_json(spec);
  if (fs::exists(layout.spec_file())) {
    const nlohmann::json existing = to_json(read_spec(layout));
    if (existing == wanted) return;
    for (const auto& [key, value] : wanted.items())
      if (existing.value(key, nlohmann::json()) != value)
        fail(layout.root, "holds a different sweep (its '" + key +
                              "' differs); resume it with `depot sweep resume " + layout.root +
                              "` or choose another folder");
    fail(layout.root, "holds a different sweep");
  }
  std::error_code ec;
  if (fs::exists(layout.root, ec) &&
      (!fs::is_directory(layout.root, ec) || !fs::is_empty(layout.root, ec)))
    fail(layout.root,
         "is not a sweep folder (no sweep.json) and is not empty; choose a new or empty folder");
  fs::create_directories(layout.root);
  write_text_file_atomic(layout.spec_file(), wanted.dump(2) + "\n");
}

}  // namespace depot::harness
