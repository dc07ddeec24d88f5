// Our ORB-SLAM2-style extractor against cv::ORB (1000 features, same pyramid
// settings) on the real TUM fr3/walking_xyz frame, 640x480 grayscale.
//   build-*/slam/feature/orb_extractor_bench
// Reports ms per frame for each, and BM_OursOverCvOrb times both alternately in
// the same iterations and reports ours / cv::ORB as "ratio".
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "slam/feature/descriptor_distance.h"
#include "slam/feature/orb_extractor.h"

namespace {

namespace fs = std::filesystem;
using depot::slam::OrbExtractor;
using depot::slam::OrbParams;

const cv::Mat& frame() {
  static const cv::Mat img = [] {
    const fs::path dir = fs::path(DEPOT_SHARED_DATA) / "tum/fr3_walking_xyz_frame/rgb";
    std::vector<fs::path> pngs;
    if (fs::is_directory(dir)) {
      for (const auto& e : fs::directory_iterator(dir)) {
        if (e.path().extension() == ".png") pngs.push_back(e.path());
      }
    }
    std::sort(pngs.begin(), pngs.end());
    return pngs.empty() ? cv::Mat() : cv::imread(pngs.front().string(), cv::IMREAD_GRAYSCALE);
  }();
  return img;
}

bool have_frame(benchmark::State& state) {
  if (frame().empty()) {
    state.SkipWithError(
        "real frame absent: tum/fr3_walking_xyz_frame/rgb/*.png not found "
        "under " DEPOT_SHARED_DATA);
    return false;
  }
  return true;
}

void report_ms(benchmark::State& state, double seconds, size_t n_kps) {
  state.counters["ms_per_frame"] =
      benchmark::Counter(1e3 * seconds / state.iterations(), benchmark::Counter::kDefaults);
  state.counters["keypoints"] = static_cast<double>(n_kps);
}

void BM_OurOrb(benchmark::State& state) {
  if (!have_frame(state)) return;
  OrbExtractor orb(OrbParams{});
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  double seconds = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    orb.extract(frame(), cv::Mat(), kps, desc);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    benchmark::DoNotOptimize(desc.data);
  }
  report_ms(state, seconds, kps.size());
}
BENCHMARK(BM_OurOrb)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_CvOrb(benchmark::State& state) {
  if (!have_frame(state)) return;
  const cv::Ptr<cv::ORB> orb = cv::ORB::create(1000, 1.2f, 8);
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  double seconds = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    orb->detectAndCompute(frame(), cv::noArray(), kps, desc);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    benchmark::DoNotOptimize(desc.data);
  }
  report_ms(state, seconds, kps.size());
}
BENCHMARK(BM_CvOrb)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// Both in every iteration, so load changes on the machine hit both alike.
void BM_OursOverCvOrb(benchmark::State& state) {
  if (!have_frame(state)) return;
  OrbExtractor ours(OrbParams{});
  const cv::Ptr<cv::ORB> theirs = cv::ORB::create(1000, 1.2f, 8);
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  double t_ours = 0;
  double t_cv = 0;
  for (auto _ : state) {
    auto t0 = std::chrono::steady_clock::now();
    ours.extract(frame(), cv::Mat(), kps, desc);
    auto t1 = std::chrono::steady_clock::now();
    theirs->detectAndCompute(frame(), cv::noArray(), kps, desc);
    auto t2 = std::chrono::steady_clock::now();
    t_ours += std::chrono::duration<double>(t1 - t0).count();
    t_cv += std::chrono::duration<double>(t2 - t1).count();
    benchmark::DoNotOptimize(desc.data);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["ours_ms"] = 1e3 * t_ours / n;
  state.counters["cv_orb_ms"] = 1e3 * t_cv / n;
  state.counters["ratio"] = t_ours / t_cv;
}
BENCHMARK(BM_OursOverCvOrb)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// One descriptor distance (the inner loop of brute-force matching).
void BM_DescriptorDistance(benchmark::State& state) {
  cv::Mat d(1024, depot::slam::kDescriptorBytes, CV_8UC1);
  cv::randu(d, 0, 256);
  int sum = 0;
  for (auto _ : state) {
    for (int i = 0; i + 1 < d.rows; ++i) {
      sum += depot::slam::descriptor_distance(d.ptr<std::uint8_t>(i), d.ptr<std::uint8_t>(i + 1));
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * (d.rows - 1));
}
BENCHMARK(BM_DescriptorDistance);

}  // namespace

BENCHMARK_MAIN();
