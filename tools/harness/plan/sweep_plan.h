#pragma once
// A sweep's grid expanded into cells and jobs, and where each job's output
// lives. A cell is one scenario at one combination of parameter levels; per
// cell and seed one render job writes a dataset, and one SLAM job per mode
// reads it. Ids are stable (derived from names and levels), so a resumed
// sweep or a cluster array task finds the same job under the same id.
#include <string>
#include <utility>
#include <vector>

#include "common/yaml_overrides.h"
#include "tools/harness/plan/sweep_spec.h"

namespace depot::harness {

struct SweepCell {
  size_t scenario = 0;              // index into spec.scenarios
  std::vector<std::string> levels;  // one per spec.vary parameter
  std::string id;                   // "depot_walking_xyz__load-0.5", safe as a file name
  std::string label;                // "depot_walking_xyz load=0.5"
};

enum class JobKind { kRender, kSlam };

struct SweepJob {
  JobKind kind = JobKind::kRender;
  // render: the dataset id (scenario, scenario levels, seed); slam: the
  // scenario, the levels its mode depends on (run_levels), seed and mode
  std::string id;
  size_t cell = 0;  // render: a cell with this dataset's scenario settings; slam: its first cell
  int seed = 1;
  std::string mode;         // slam jobs only
  std::string system_file;  // a "system:NAME" mode's file, absolute (SweepSpec::systems)
  std::string dataset_id;   // the dataset a slam job reads (its own id for render)
  // slam: every cell this run stands for. A mode that ignores a varied
  // parameter (orb ignores the detector's and the rejection's) runs once for
  // all of that parameter's levels, and its result counts in each cell.
  std::vector<size_t> cells;
};

struct SweepPlan {
  SweepSpec spec;
  std::vector<SweepCell> cells;
  // All render jobs first, then slam jobs. Cells that differ only in
  // detector or rejection levels share a dataset (one render per seed).
  std::vector<SweepJob> jobs;
};

// Letters, digits, '.', '-', '+' and '_' stay; anything else becomes '_'.
std::string file_safe(const std::string& text);

SweepPlan make_sweep_plan(const SweepSpec& spec);

// Whether a parameter of this target can change a run in this mode: the
// scenario's always; the detector's only where a detector runs (orb+yolo,
// full, masked); the flow test's extensions in full and masked, the object
// masks' (mask.*, tracking.*, person_mask) only in masked, the box depth
// split (background_margin) only in full.
bool parameter_affects_mode(const ParameterKey& parameter, const std::string& mode);

// The varied parameters a run in this mode depends on, each with the cell's
// level, in the spec's order: what names the run and what its record keeps.
std::vector<std::pair<std::string, std::string>> run_levels(const SweepSpec& spec,
                                                            const SweepCell& cell,
                                                            const std::string& mode);

// Throws Error("<sweep>: no job '<id>'").
const SweepJob& find_job(const SweepPlan& plan, const std::string& id, const std::string& sweep);

// The overrides of a cell (its levels plus the fixed settings) for one target.
std::vector<YamlOverride> cell_overrides(const SweepPlan& plan, const SweepCell& cell,
                                         ParameterTarget target);

// Where a sweep keeps its files, under one root folder.
struct SweepLayout {
  std::string root;
  std::string spec_file() const;                            // sweep.json
  std::string dataset_dir(const std::string& id) const;     // data/<id>/
  std::string dataset_record(const std::string& id) const;  // data/<id>.json
  // A contact sheet of the dataset (RGB | depth | labels of one frame), kept
  // when the dataset is removed: the report shows the worlds rendered.
  std::string dataset_preview(const std::string& id) const;  // data/<id>.jpg
  std::string run_dir(const std::string& id) const;          // runs/<id>/
  std::string run_record(const std::string& id) const;       // runs/<id>/result.json
  std::string log_file(const std::string& job_id) const;     // logs/<id>.log
  std::string report_dir() const;                            // report/
};

// Writes sweep.json, or checks that an existing one describes the same sweep
// (so a resume cannot mix two grids in one folder). Throws Error naming the
// folder and the first difference.
void write_or_check_spec(const SweepLayout& layout, const SweepSpec& spec);
SweepSpec read_spec(const SweepLayout& layout);

}  // namespace depot::harness
