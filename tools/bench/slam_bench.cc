// depot_slam_bench: per-frame tracking time (median, p95) and its stages on a
// simulated sequence, and memory growth over a long run. Stage times are also
// given as ratios to ORB extraction measured in the same run.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/error.h"
#include "slam/io/settings.h"
#include "slam/io/tum_sequence.h"
#include "slam/system/system.h"
#include "sim/pipeline/render_dataset.h"
#include "sim/scenario/scenario_loader.h"

namespace fs = std::filesystem;

namespace {

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

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
  bool sync = false;
  app.add_option("--dataset", dataset, "TUM folder to run (default: render --scenario first)");
  app.add_option("--scenario", scenario, "Shipped scenario to render when no dataset is given");
  app.add_option("--frames", frames, "Frames")->check(CLI::Range(10, 1000000));
  app.add_flag("--sync", sync, "Local mapping in the tracking thread");
  CLI11_PARSE(app, argc, argv);
  std::string rendered;
  try {
    if (dataset.empty()) {
      depot::sim::Scenario s =
          depot::sim::load_scenario(std::string(DEPOT_SOURCE_DIR) + "/scenarios/" + scenario + ".yaml");
      depot::sim::RenderRequest r;
      rendered = (fs::temp_directory_path() / ("depot_slam_bench_" + std::to_string(getpid()))).string();
      r.dataset.output = rendered;
      r.frames = frames;
      r.progress = false;
      std::fprintf(stderr, "rendering %d frames of %s...\n", frames, scenario.c_str());
      depot::sim::render_dataset(s, r);
      dataset = rendered;
    }
    depot::slam::TumSequence sequence(dataset);
    depot::slam::SlamSettings settings;
    if (!sequence.calibration_path().empty()) settings = depot::slam::load_settings(sequence.calibration_path());
    settings.threaded_mapping = !sync;
    sequence.set_depth_factor(settings.camera.depth_factor);
    const size_t n = std::min<size_t>(frames, sequence.size());

    depot::slam::System system(settings);
    std::vector<double> total, extract, match, optimize, other;
    double rss_start = rss_mb(), rss_early = 0;
    size_t kf_early = 0;
    int lost = 0;
    cv::Mat bgr, depth;
    for (size_t i = 0; i < n; ++i) {
      sequence.load(i, bgr, depth);
      auto r = system.track(bgr, depth, sequence.entry(i).rgb_timestamp);
      lost += r.state == depot::slam::TrackingState::kLost;
      total.push_back(r.timing.total_ms);
      extract.push_back(r.timing.extract_ms);
      match.push_back(r.stats.match_ms);
      optimize.push_back(r.stats.optimize_ms);
      other.push_back(r.timing.track_ms - r.stats.match_ms - r.stats.optimize_ms);
      if (i == n / 10) rss_early = rss_mb(), kf_early = system.n_keyframes();
    }
    system.finish();
    const double rss_end = rss_mb();
    const size_t kfs = system.n_keyframes();
    const double base = percentile(extract, 0.5);
    std::printf("depot_slam_bench: %zu frames of %s, %s mapping, %d lost\n", n, dataset.c_str(),
                sync ? "synchronous" : "threaded", lost);
    std::printf("  %-32s %10s %10s %12s\n", "stage", "median ms", "p95 ms", "vs extract");
    auto row = [&](const char* name, const std::vector<double>& v) {
      std::printf("  %-32s %10.2f %10.2f %11.2fx\n", name, percentile(v, 0.5), percentile(v, 0.95),
                  percentile(v, 0.5) / base);
    };
    row("ORB extraction (baseline)", extract);
    row("matching", match);
    row("pose optimisation", optimize);
    row("other tracking (local map, KF)", other);
    row("total per frame", total);
    std::printf("  median tracking %.1f ms per frame (target < 25 ms at 640x480)\n", percentile(total, 0.5));
    std::printf("  memory: RSS %.1f MB at start, %.1f MB after %zu frames (%zu keyframes), %.1f MB at the end (%zu "
                "keyframes, %zu map points): %.3f MB per keyframe after the first tenth\n",
                rss_start, rss_early, n / 10 + 1, kf_early, rss_end, kfs, system.n_map_points(),
                kfs > kf_early ? (rss_end - rss_early) / static_cast<double>(kfs - kf_early) : 0.0);
  } catch (const depot::Error& e) {
    std::fprintf(stderr, "depot_slam_bench: error: %s\n", e.what());
    if (!rendered.empty()) fs::remove_all(rendered);
    return 1;
  }
  if (!rendered.empty()) fs::remove_all(rendered);
  return 0;
}
