// depot_slam_bench: per-frame tracking time (median, p95) and its stages on a
// simulated sequence, and memory growth over a long run. Stage times are also
// given as ratios to ORB extraction measured in the same run. With a
// detector mode, the tracker's wait for the detector with the detection
// thread running ahead, against the same run without, at --rate Hz input.
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/error.h"
#include "common/percentile.h"
#include "sim/pipeline/render_dataset.h"
#include "sim/scenario/scenario_loader.h"
#include "slam/io/tum_sequence.h"
#include "slam/reject/rejection_filter.h"
#include "slam/system/system.h"
#include "tools/runner/slam_runner.h"

namespace fs = std::filesystem;

namespace {

using depot::percentile;

double rss_mb() {
  std::ifstream statm("/proc/self/statm");
  long pages_total = 0, pages_resident = 0;
  statm >> pages_total >> pages_resident;
  return pages_resident * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1e6;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"SLAM benchmark: tracking time per frame and stage, memory growth"};
  std::string dataset;
  std::string scenario = "depot_static";
  int frames = 900;
  std::string mapping = "threaded";
  std::string mode = "orb";
  std::string detector_type = "sim";
  double rate_hz = 30;
  std::string person_mask = "depth";
  app.add_option("--person-mask", person_mask,
                 "masked: person masks from depth, segmentation, both")
      ->check(CLI::IsMember({"depth", "segmentation", "both"}))
      ->capture_default_str();
  app.add_option("--mode", mode, "Rejection mode measured against plain orb in the same run")
      ->check(CLI::IsMember({"orb", "orb+yolo", "orb+lk", "full", "masked"}));
  app.add_option("--detector", detector_type, "sim | darknet | fastestdet | yolov5")
      ->check(CLI::IsMember({"sim", "darknet", "fastestdet", "yolov5"}));
  app.add_option("--dataset", dataset, "TUM folder to run (default: render --scenario first)");
  app.add_option("--scenario", scenario, "Shipped scenario to render when no dataset is given");
  app.add_option("--frames", frames, "Frames")->check(CLI::Range(10, 1000000));
  app.add_option("--mapping", mapping, "Local mapping: threaded or sync (in the tracking thread)")
      ->check(CLI::IsMember({"sync", "threaded"}))
      ->capture_default_str();
  app.add_option("--rate", rate_hz,
                 "Input rate (Hz) of the run-ahead comparison (0 = as fast as possible)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  const depot::slam::RejectionParams::PersonMask person_mask_source =
      depot::slam::parse_person_mask(person_mask);
  const bool sync = mapping == "sync";
  std::string rendered;
  try {
    if (dataset.empty()) {
      depot::sim::Scenario s = depot::sim::load_scenario(std::string(DEPOT_SOURCE_DIR) +
                                                         "/scenarios/" + scenario + ".yaml");
      depot::sim::RenderRequest r;
      rendered =
          (fs::temp_directory_path() / ("depot_slam_bench_" + std::to_string(getpid()))).string();
      r.dataset.output = rendered;
      r.frames = frames;
      r.progress = false;
      std::fprintf(stderr, "rendering %d frames of %s...\n", frames, scenario.c_str());
      depot::sim::render_dataset(s, r);
      dataset = rendered;
    }
    const size_t n = std::min<size_t>(frames, depot::slam::TumSequence(dataset).size());

    struct Measured {
      std::vector<double> total, extract, match, optimize, other, filter, wait, detect, mask,
          segment;
      int lost = 0;
      std::vector<double> relocalise;  // track time of frames shown after a cover
      int relocalised = 0, relocalise_tries = 0;
      double rss_start = 0, rss_early = 0, rss_end = 0;
      size_t kf_early = 0, kfs = 0, points = 0;
    };
    // `probe_relocalisation`: after the run, the camera is covered for a
    // frame and then shows an earlier frame of the sequence again (30 of
    // them, spread over it): what a lost frame's relocalisation costs.
    auto measure = [&](const std::string& run_mode, bool loop_closing, bool probe_relocalisation) {
      Measured m;
      // The product's run of one sequence (runner::run_sequence), recorded
      // frame by frame; each frame tracked as it arrives (no run-ahead), so
      // the detector's wait is measured as the tracker sees it.
      depot::runner::RunOptions options;
      options.input.dataset = dataset;
      options.rejection.mode = run_mode;
      options.perception.detector = detector_type;
      options.rejection.params.person_mask = person_mask_source;
      options.input.sync = sync;
      options.input.loop_closing = loop_closing;
      options.input.frames = n;
      options.quiet = true;
      options.pacing.run_ahead = false;
      m.rss_start = rss_mb();
      options.hooks.on_frame = [&](size_t i, const depot::slam::TrackResult& r,
                                   const depot::slam::RejectionFilter* filter,
                                   const depot::slam::System& system) {
        m.lost += r.state == depot::slam::TrackingState::kLost;
        m.total.push_back(r.timing.total_ms);
        m.extract.push_back(r.timing.extract_ms);
        m.match.push_back(r.stats.match_ms);
        m.optimize.push_back(r.stats.optimize_ms);
        m.other.push_back(r.timing.track_ms - r.stats.match_ms - r.stats.optimize_ms);
        if (filter) {
          m.filter.push_back(filter->last_stats().filter_ms);
          m.wait.push_back(filter->last_stats().wait_ms);
          m.detect.push_back(filter->last_stats().detect_ms);
          m.mask.push_back(filter->last_stats().mask_ms);
          m.segment.push_back(filter->last_stats().segment_ms);
        }
        if (i == n / 10) m.rss_early = rss_mb(), m.kf_early = system.n_keyframes();
      };
      options.hooks.after_run = [&](depot::slam::System& system,
                                    const depot::slam::RgbdSequence& sequence) {
        if (probe_relocalisation) {
          cv::Mat bgr, depth;
          sequence.load(0, bgr, depth);
          double t = sequence.timestamp(n - 1);
          const cv::Mat black = cv::Mat::zeros(bgr.size(), CV_8UC3);
          const cv::Mat no_depth = cv::Mat::zeros(depth.size(), CV_32F);
          for (size_t k = 0; k < n; k += std::max<size_t>(1, n / 30)) {
            system.track(black, no_depth, t += 0.033);
            sequence.load(k, bgr, depth);
            const auto r = system.track(bgr, depth, t += 0.033);
            m.relocalise.push_back(r.timing.track_ms);
            ++m.relocalise_tries;
            m.relocalised += r.state == depot::slam::TrackingState::kRelocalized;
          }
        }
        m.rss_end = rss_mb();
        m.kfs = system.n_keyframes();
        m.points = system.n_map_points();
      };
      depot::runner::run_sequence(options);
      return m;
    };
    const Measured no_loops = measure("orb", false, false);
    const Measured base_run = measure("orb", true, true);
    const Measured run = mode == "orb" ? base_run : measure(mode, true, false);
    const double base = percentile(base_run.extract, 0.5);
    auto row = [&](const char* name, const std::vector<double>& v) {
      std::printf("  %-34s %10.2f %10.2f %11.2fx\n", name, percentile(v, 0.5), percentile(v, 0.95),
                  percentile(v, 0.5) / base);
    };
    std::printf("depot_slam_bench: %zu frames of %s, %s mapping, %d lost\n", n, dataset.c_str(),
                sync ? "synchronous" : "threaded", base_run.lost);
    std::printf("  %-34s %10s %10s %12s\n", "stage (mode orb)", "median ms", "p95 ms",
                "vs extract");
    row("ORB extraction (baseline)", base_run.extract);
    row("matching", base_run.match);
    row("pose optimisation", base_run.optimize);
    row("other tracking (local map, KF)", base_run.other);
    row("total per frame", base_run.total);
    std::printf(
        "  median tracking %.1f ms per frame (target < 25 ms at 640x480); p95 / median %.2f\n",
        percentile(base_run.total, 0.5),
        percentile(base_run.total, 0.95) / percentile(base_run.total, 0.5));
    std::printf(
        "  loop closing on vs off (same run): tracking (matching + optimisation + other) median "
        "%.2f vs %.2f ms: %.2fx; total per frame %.2f vs %.2f ms: %.2fx\n",
        percentile(base_run.match, 0.5) + percentile(base_run.optimize, 0.5) +
            percentile(base_run.other, 0.5),
        percentile(no_loops.match, 0.5) + percentile(no_loops.optimize, 0.5) +
            percentile(no_loops.other, 0.5),
        (percentile(base_run.match, 0.5) + percentile(base_run.optimize, 0.5) +
         percentile(base_run.other, 0.5)) /
            (percentile(no_loops.match, 0.5) + percentile(no_loops.optimize, 0.5) +
             percentile(no_loops.other, 0.5)),
        percentile(base_run.total, 0.5), percentile(no_loops.total, 0.5),
        percentile(base_run.total, 0.5) / percentile(no_loops.total, 0.5));
    std::printf(
        "  relocalisation after a covered frame (%d views of the sequence shown again): %d "
        "relocalised; tracking time of such a frame median %.1f ms, p95 %.1f ms (%.2fx a tracked "
        "frame's median)\n",
        base_run.relocalise_tries, base_run.relocalised, percentile(base_run.relocalise, 0.5),
        percentile(base_run.relocalise, 0.95),
        percentile(base_run.relocalise, 0.5) / percentile(base_run.total, 0.5));
    std::printf(
        "  memory: RSS %.1f MB at start, %.1f MB after %zu frames (%zu keyframes), %.1f MB at the "
        "end (%zu "
        "keyframes, %zu map points): %.3f MB per keyframe after the first tenth\n",
        base_run.rss_start, base_run.rss_early, n / 10 + 1, base_run.kf_early, base_run.rss_end,
        base_run.kfs, base_run.points,
        base_run.kfs > base_run.kf_early ? (base_run.rss_end - base_run.rss_early) /
                                               static_cast<double>(base_run.kfs - base_run.kf_early)
                                         : 0.0);
    if (mode != "orb") {
      std::printf("  mode %s with the %s detector (%d lost):\n", mode.c_str(),
                  detector_type.c_str(), run.lost);
      row("rejection stage (after detection)", run.filter);
      if (mode == "masked") row("  of it: box tracking + depth masks", run.mask);
      row("detector (own thread)", run.detect);
      if (mode == "masked" && person_mask != "depth")
        row("person segmenter (own thread)", run.segment);
      row("tracking waited for the detector", run.wait);
      row("total per frame", run.total);
      const double det = percentile(run.detect, 0.5), wait = percentile(run.wait, 0.5);
      std::printf(
          "  the detection thread hides %.0f %% of the detector's time; the rejection stage adds "
          "%.1f %% to "
          "plain tracking time (%.2f of %.2f ms)\n",
          det > 0 ? 100.0 * (1.0 - wait / det) : 100.0,
          100.0 * percentile(run.filter, 0.5) / percentile(base_run.total, 0.5),
          percentile(run.filter, 0.5), percentile(base_run.total, 0.5));
      const double frame_ms = percentile(run.total, 0.5);
      std::printf(
          "  share of this run's tracking time per frame (median %.2f ms): rejection stage %.1f %% "
          "(goal < 15 %%)\n",
          frame_ms, 100.0 * percentile(run.filter, 0.5) / frame_ms);
      if (mode == "masked" && person_mask != "depth")
        std::printf("  person segmenter: %.1f %% of it, hidden in the detection thread\n",
                    100.0 * percentile(run.segment, 0.5) / frame_ms);
    }
    if (depot::slam::mode_uses_detector(depot::slam::parse_rejection_mode(mode))) {
      // The runner's loop with its emulated camera, run-ahead off then on.
      auto run_at_rate = [&](bool run_ahead) {
        depot::runner::RunOptions options;
        options.input.dataset = dataset;
        options.rejection.mode = mode;
        options.perception.detector = detector_type;
        options.input.frames = n;
        options.input.sync = sync;
        options.quiet = true;
        options.pacing.rate_hz = rate_hz;
        options.rejection.params.person_mask = person_mask_source;
        options.pacing.run_ahead = run_ahead;
        return depot::runner::run_sequence(options);
      };
      const depot::runner::RunSummary off = run_at_rate(false), on = run_at_rate(true);
      const std::string input =
          rate_hz > 0 ? fmt::format("{:g} Hz input", rate_hz) : "input as fast as possible";
      std::printf("  mode %s, %s, detection thread running ahead vs not (same run):\n",
                  mode.c_str(), input.c_str());
      std::printf("  %-34s %10s %10s %12s\n", "median ms", "without", "with", "with/without");
      auto compare = [](const char* name, double without, double with) {
        std::printf("  %-34s %10.2f %10.2f %11.2fx\n", name, without, with,
                    without > 0 ? with / without : 0.0);
      };
      compare("tracking waited for the detector", off.wait_ms, on.wait_ms);
      compare("  (p95)", off.wait_p95_ms, on.wait_p95_ms);
      compare("detector (own thread)", off.detect_ms, on.detect_ms);
      compare("total per frame", off.median_ms, on.median_ms);
      std::printf("  frames handled after their turn: %zu without, %zu with (of %zu)\n",
                  off.late_frames, on.late_frames, n);
      std::printf("  median wait with run-ahead %.3f ms (goal < 1 ms at 30 Hz)\n", on.wait_ms);
    }
  } catch (const depot::Error& e) {
    std::fprintf(stderr, "depot_slam_bench: error: %s\n", e.what());
    if (!rendered.empty()) fs::remove_all(rendered);
    return 1;
  }
  if (!rendered.empty()) fs::remove_all(rendered);
  return 0;
}
