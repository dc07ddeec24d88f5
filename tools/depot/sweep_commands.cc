// `depot sweep ...`: grids of simulated runs (scenarios x parameter levels x
// modes x seeds), each job its own process, resumable, with a report.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>
#include <utility>

#include "common/child_process.h"
#include "common/error.h"
#include "common/image_size.h"
#include "common/interrupt.h"
#include "sim/scenario/shipped_scenarios.h"
#include "tools/depot/commands.h"
#include "tools/depot/sweep_file.h"
#include "tools/harness/job/sweep_jobs.h"
#include "tools/harness/plan/sweep_plan.h"
#include "tools/harness/plan/sweep_spec.h"
#include "tools/harness/report/sweep_report.h"
#include "tools/harness/schedule/slurm_scheduler.h"
#include "tools/harness/schedule/sweep_runner.h"
#include "tools/harness/schedule/sweep_status.h"
#include "tools/system/system_spec.h"

#include "sim/scenario/scenario_loader.h"

namespace fs = std::filesystem;

namespace depot::cli {
namespace {

struct SweepArgs {
  std::vector<std::string> scenarios;
  std::vector<std::string> vary, fixed;
  std::vector<std::string> modes = {"orb", "orb+yolo", "orb+lk", "full"};
  int seeds = 3, frames = 300, width = 640, workers = 1;
  std::string mapping = "sync";
  bool keep_data = false, plan_only = false, quiet = false, assume_queue_empty = false;
  std::vector<std::string> figures;
  std::string output;
  std::string file;  // --file: the sweep written down (sweep_file.h)
  std::string scheduler = "local";
  harness::SlurmOptions slurm;
};

harness::SweepSpec make_spec(const SweepArgs& a) {
  harness::SweepSpec spec;
  for (const auto& name : a.scenarios) {
    const std::string path = fs::absolute(sim::resolve_scenario(name)).lexically_normal().string();
    spec.scenarios.push_back({sim::load_scenario(path).name, path});
  }
  for (const auto& v : a.vary) spec.vary.push_back(harness::parse_sweep_parameter(v, "--vary"));
  for (const auto& v : a.fixed) spec.fixed.push_back(harness::parse_sweep_parameter(v, "--set"));
  spec.modes = a.modes;
  spec.seeds = a.seeds;
  spec.frames = a.frames;
  spec.width = a.width;
  spec.sync_mapping = a.mapping == "sync";
  spec.keep_data = a.keep_data;
  harness::resolve_system_files(spec);  // absolute, as the scenarios' paths
  harness::validate(spec, "depot sweep run");
  return spec;
}

// A word as a shell reads it back: quoted when it holds anything but
// letters, digits and /._-+=:,@%
std::string shell_word(const std::string& word) {
  const bool plain = !word.empty() && word.find_first_not_of(
                                          "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                          "0123456789/._-+=:,@%") == std::string::npos;
  if (plain) return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string shell_line(const std::vector<std::string>& words) {
  std::string line;
  for (const auto& w : words) line += (line.empty() ? "" : " ") + shell_word(w);
  return line;
}

// The command that resumes this sweep where it ran: on Slurm with the
// options that place its jobs on the cluster.
std::string resume_command(const SweepArgs& a, const std::string& root) {
  std::vector<std::string> words = {"depot", "sweep", "resume", root};
  if (a.scheduler == "slurm") {
    words.insert(words.end(), {"--scheduler", "slurm"});
    const harness::SlurmOptions& s = a.slurm;
    for (const auto& [option, value] :
         {std::pair<const char*, std::string>{"--partition", s.partition},
          {"--account", s.account},
          {"--time", s.time_limit},
          {"--mem", s.memory},
          {"--cpus-per-task", s.cpus_per_task > 0 ? std::to_string(s.cpus_per_task) : ""}})
      if (!value.empty()) words.insert(words.end(), {option, value});
    for (const auto& arg : s.sbatch_args) words.push_back("--sbatch-arg=" + arg);
  }
  return shell_line(words);
}

void report(const harness::SweepPlan& plan, const harness::SweepLayout& layout,
            const std::vector<std::string>& figures, bool print_table) {
  const harness::ReportFiles files = harness::write_sweep_report(plan, layout, figures);
  for (const auto& problem : files.corrupt)
    std::fprintf(stderr,
                 "depot: warning: %s; left out of the report (`depot sweep resume %s` runs it "
                 "again)\n",
                 problem.c_str(), shell_word(layout.root).c_str());
  if (print_table) std::printf("%s", files.ablation_markdown.c_str());
  std::printf("report: %s (%zu of %zu runs)\ntables: %s\n", files.html.c_str(), files.runs_found,
              files.runs_expected, files.markdown.c_str());
}

void execute(const harness::SweepPlan& plan, const harness::SweepLayout& layout,
             const SweepArgs& a) {
  harness::SweepRunOptions options;
  options.program = own_program_path();
  options.workers = a.workers;
  options.progress = !a.quiet;
  options.assume_queue_empty = a.assume_queue_empty;
  harness::SweepRunResult r;
  if (a.scheduler == "slurm") {
    const harness::SlurmRunResult s =
        harness::run_sweep_on_slurm(plan, layout, options, a.slurm, interrupt_flag());
    if (s.detached) {
      std::printf(
          "submitted; follow it with `depot sweep status %s`, then `depot sweep report %s`\n",
          layout.root.c_str(), layout.root.c_str());
      return;
    }
    r = s.run;
  } else {
    r = harness::run_sweep(plan, layout, options, interrupt_flag());
  }
  if (r.interrupted)
    fail(layout.root, "sweep interrupted; finished runs are kept, resume with `" +
                          resume_command(a, layout.root) + "`");
  report(plan, layout, a.figures, true);
  if (r.failed || r.blocked)
    fail(layout.root, std::to_string(r.failed) + " job(s) failed and " + std::to_string(r.blocked) +
                          " could not run (logs in " + layout.root + "/logs); `" +
                          resume_command(a, layout.root) + "` retries them");
}

// The file's fields where the command line gave none.
SweepArgs with_sweep_file(SweepArgs a, const CLI::App& cmd) {
  if (a.file.empty()) {
    if (a.scenarios.empty()) fail("depot sweep run", "name the scenarios, or --file F.yaml");
    return a;
  }
  const SweepFile f = read_sweep_file(a.file);
  if (a.scenarios.empty()) a.scenarios = f.scenarios;
  if (!cmd.count("--vary")) a.vary = f.vary;
  if (!cmd.count("--set")) a.fixed = f.fixed;
  if (!cmd.count("--modes") && f.modes) a.modes = *f.modes;
  if (!cmd.count("--seeds") && f.seeds) a.seeds = *f.seeds;
  if (!cmd.count("--frames") && f.frames) a.frames = *f.frames;
  if (!cmd.count("--width") && f.width) a.width = *f.width;
  if (!cmd.count("--mapping") && f.mapping) a.mapping = *f.mapping;
  return a;
}

void run_command(const SweepArgs& a) {
  const harness::SweepSpec spec = make_spec(a);
  const harness::SweepLayout layout{a.output};
  const harness::SweepPlan plan = harness::make_sweep_plan(spec);
  // Every cell's settings must load before anything is written or run.
  harness::check_sweep_inputs(plan);
  harness::write_or_check_spec(layout, spec);
  if (a.plan_only) {
    // For a cluster scheduler: every render job before the runs that read
    // it, with absolute paths (the jobs run elsewhere), one line each.
    const harness::SweepLayout absolute{fs::absolute(layout.root).lexically_normal().string()};
    for (const auto& job : plan.jobs)
      std::printf("%s\n",
                  shell_line(harness::job_command(own_program_path(), absolute, job)).c_str());
    return;
  }
  execute(plan, layout, a);
}

void add_run_options(CLI::App* cmd, SweepArgs& a) {
  cmd->add_option("scenarios", a.scenarios, "Scenario names or YAML files (or --file)")
      ->default_str("");
  cmd->add_option("--file", a.file,
                  "A sweep file (scenarios, vary, set, modes, seeds, frames, width, mapping; "
                  "e.g. scenarios/stress/breaking_point.yaml); options given here override it")
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", a.output, "Sweep folder (resumes when it holds this sweep)")
      ->required();
  cmd->add_option(
         "--vary", a.vary,
         "PARAM=L1,L2,...: load, depth_noise, rgb_noise, exposure, readout, distortion (k1), "
         "miss_rate, latency, detector (sim, darknet, xl, fastestdet, yolov5), scenario.KEY, "
         "detector.KEY, rejection.KEY (repeatable: the grid is the product)")
      ->default_str("");
  cmd->add_option("--set", a.fixed, "PARAM=VALUE for every run (same names as --vary)")
      ->default_str("");
  // A system's file is loaded with the sweep (one error line naming it).
  cmd->add_option("--modes", a.modes,
                  "Modes, comma separated: orb, orb+yolo, orb+lk, full, masked, or "
                  "system:NAME for another program (scenes/systems/NAME.yaml, or a path to "
                  "your own system file)")
      ->delimiter(',')
      ->check(CLI::Validator(
          [](const std::string& mode) -> std::string {
            static const std::set<std::string> builtin = {"orb", "orb+yolo", "orb+lk", "full",
                                                          "masked"};
            if (builtin.count(mode) || system::is_system_mode(mode)) return "";
            return mode + " is no mode (orb, orb+yolo, orb+lk, full, masked, or system:NAME)";
          },
          "MODE"));
  cmd->add_option("--seeds", a.seeds, "Seeds per cell (scenario and detector)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--frames", a.frames, "Frames per run")->check(CLI::Range(10, 100000));
  cmd->add_option("--width", a.width,
                  "Image width (height and intrinsics scale); each side 32..4096 px")
      ->check(CLI::Range(kMinImageSide, kMaxImageSide));
  cmd->add_option("--mapping", a.mapping,
                  "Local mapping: sync (in the tracking thread, reproducible) or threaded (its "
                  "own thread, as ORB-SLAM2; faster, not reproducible)")
      ->check(CLI::IsMember({"sync", "threaded"}));
  cmd->add_flag("--keep-data", a.keep_data, "Keep rendered datasets after their runs");
  cmd->add_flag("--plan-only", a.plan_only,
                "Write sweep.json and print one command per job (for a cluster), run nothing");
}

void add_execution_options(CLI::App* cmd, SweepArgs& a) {
  cmd->add_option("-j,--workers", a.workers, "Jobs run at the same time")
      ->check(CLI::Range(1, 256));
  cmd->add_option("--figures", a.figures, "Run ids whose trajectory figures the report shows")
      ->delimiter(',')
      ->default_str("orb and full at the last level, seed 1");
  cmd->add_flag("-q,--quiet", a.quiet, "No progress lines (the table and report still print)");
  cmd->add_flag("--assume-queue-empty", a.assume_queue_empty,
                "Run although the folder was submitted to Slurm and its queue is not looked at "
                "(for when squeue cannot answer here): only when its tasks are known to have "
                "ended, else they run jobs twice");
  cmd->add_option("--scheduler", a.scheduler,
                  "local (a process pool of -j workers) or slurm (job arrays through sbatch; the "
                  "folder and depot must be on a filesystem every node sees)")
      ->check(CLI::IsMember({"local", "slurm"}));
  const std::string group = "Slurm (--scheduler slurm)";
  cmd->add_option("--partition", a.slurm.partition, "Slurm partition (default: the cluster's)")
      ->group(group);
  cmd->add_option("--account", a.slurm.account, "Slurm account to charge")->group(group);
  cmd->add_option("--time", a.slurm.time_limit, "Time limit per job, e.g. 30 or 1:00:00")
      ->group(group);
  cmd->add_option("--mem", a.slurm.memory, "Memory per job, e.g. 4G")->group(group);
  cmd->add_option("--cpus-per-task", a.slurm.cpus_per_task, "CPUs per job (0: the cluster's)")
      ->check(CLI::Range(0, 1024))
      ->group(group);
  cmd->add_option("--sbatch-arg", a.slurm.sbatch_args,
                  "An extra sbatch option, as one word (repeatable), e.g. --sbatch-arg=--qos=low")
      ->allow_extra_args(false)
      ->group(group);
  cmd->add_option("--retries", a.slurm.retries, "Further attempts of a failed job")
      ->check(CLI::Range(0, 10))
      ->group(group);
  cmd->add_flag("--detach", a.slurm.detach,
                "Submit and return; `depot sweep status` follows it, Ctrl-C cancels nothing")
      ->group(group);
  cmd->add_option("--poll", a.slurm.poll_seconds, "Seconds between looks at the queue")
      ->check(CLI::Range(0.1, 600.0))
      ->group(group);
}

}  // namespace

void register_sweep_commands(CLI::App& app) {
  CLI::App* group = app.add_subcommand(
      "sweep", "Grids of simulated runs (scenarios x levels x modes x seeds) with a report");
  group->require_subcommand(1);

  auto run_args = std::make_shared<SweepArgs>();
  CLI::App* run = group->add_subcommand(
      "run", "Run a sweep (or resume it in the same folder) and write its report");
  add_run_options(run, *run_args);
  add_execution_options(run, *run_args);
  run->callback([run_args, run] { run_command(with_sweep_file(*run_args, *run)); });

  auto resume_args = std::make_shared<SweepArgs>();
  CLI::App* resume =
      group->add_subcommand("resume", "Finish an interrupted sweep, skipping finished jobs");
  resume->add_option("folder", resume_args->output, "Sweep folder")->required();
  add_execution_options(resume, *resume_args);
  resume->callback([resume_args] {
    const harness::SweepLayout layout{resume_args->output};
    const harness::SweepPlan plan = harness::make_sweep_plan(harness::read_spec(layout));
    harness::check_sweep_inputs(plan);  // the scenario files may have changed since
    execute(plan, layout, *resume_args);
  });

  auto job_folder = std::make_shared<std::string>();
  auto job_id = std::make_shared<std::string>();
  CLI::App* job = group->add_subcommand(
      "job", "Run one job of a sweep in this process (what `run` starts per job; for clusters)");
  job->add_option("folder", *job_folder, "Sweep folder")->required();
  job->add_option("id", *job_id, "Job id (see `depot sweep run --plan-only`)")->required();
  job->callback([job_folder, job_id] {
    const harness::SweepLayout layout{*job_folder};
    const harness::SweepPlan plan = harness::make_sweep_plan(harness::read_spec(layout));
    const harness::SweepJob& j = harness::find_job(plan, *job_id, layout.root);
    if (j.kind == harness::JobKind::kRender) {
      const harness::DatasetRecord d = harness::run_render_job(plan, layout, j);
      std::printf("%s: %d frames, %.1f %% moving pixels, %.1f s\n", j.id.c_str(), d.frames,
                  100 * d.moving_share_mean, d.render_seconds);
    } else {
      const harness::RunRecord r = harness::run_slam_job(plan, layout, j);
      std::printf("%s: %s ATE %.4f m precision %.3f recall %.3f, %.1f s\n", j.id.c_str(),
                  r.ok ? "ok" : r.error.c_str(), r.ate_rmse, r.precision, r.recall, r.seconds);
    }
  });

  auto status_folder = std::make_shared<std::string>();
  CLI::App* status = group->add_subcommand(
      "status", "How many jobs are done, queued, running or failed (also while on Slurm)");
  status->add_option("folder", *status_folder, "Sweep folder")->required();
  status->callback([status_folder] {
    const harness::SweepLayout layout{*status_folder};
    const harness::SweepPlan plan = harness::make_sweep_plan(harness::read_spec(layout));
    const harness::SweepStatus s = harness::read_sweep_status(plan, layout);
    // The words of the report (harness/plan/sweep_job_state.h).
    std::printf("%s: %zu jobs: %zu done", layout.root.c_str(), s.jobs, s.done);
    if (s.without_trajectory) std::printf(" (%zu without a trajectory)", s.without_trajectory);
    if (s.on_slurm)
      std::printf(", %zu running, %zu pending in Slurm", s.running, s.pending);
    else if (s.local_runner)
      std::printf(", %zu running, %zu waiting in a local `depot sweep` (pid %ld)", s.running,
                  s.pending, s.local_runner);
    std::printf(", %zu failed", s.failed);
    if (s.corrupt) std::printf(", %zu corrupt", s.corrupt);
    std::printf(", %zu not started\n", s.not_started);
    if (!s.queue_error.empty())
      std::printf("(the Slurm queue could not be read: %s)\n", s.queue_error.c_str());
    for (const auto& run : s.runs_without_trajectory)
      std::printf("without a trajectory: %s\n", run.c_str());
    for (const auto& id : s.failed_jobs)
      std::printf("failed: %s (log: %s)\n", id.c_str(), layout.log_file(id).c_str());
    for (const auto& problem : s.corrupt_records)
      std::printf("corrupt: %s (`depot sweep resume %s` runs it again)\n", problem.c_str(),
                  shell_word(layout.root).c_str());
  });

  auto report_args = std::make_shared<SweepArgs>();
  CLI::App* rep = group->add_subcommand(
      "report", "Write the tables, plots and HTML report of a (possibly partial) sweep");
  rep->add_option("folder", report_args->output, "Sweep folder")->required();
  rep->add_option("--figures", report_args->figures, "Run ids whose trajectory figures to show")
      ->delimiter(',')
      ->default_str("orb and full at the last level, seed 1");
  rep->callback([report_args] {
    const harness::SweepLayout layout{report_args->output};
    report(harness::make_sweep_plan(harness::read_spec(layout)), layout, report_args->figures,
           true);
  });
}

}  // namespace depot::cli
