// depot_sim_bench: frames per second of the simulator's stages and end to
// end (render + labels + writing) at the scenario's resolution. Figures are
// also given as ratios to the raw MuJoCo RGB+depth render measured in the
// same run, so they compare across machines. Then both actor styles end to
// end (mesh as a ratio to primitive, measured in the same run), the colour
// pipeline's stages (as ratios to the additive noise it replaces), the
// scenario's sensor effect by effect end to end (as ratios to the exact
// camera), and the
// resident memory of a long sequence, early and at its end.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/error.h"
#include "common/png_codec.h"
#include "common/rng.h"
#include "common/yaml_overrides.h"
#include "sim/pipeline/render_dataset.h"
#include "sim/scenario/scenario_loader.h"
#include "sim/sensor/colour_pipeline.h"
#include "sim/sensor/kinect_model.h"
#include "sim/world/simulated_sequence.h"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

double ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Resident set size of this process (MB).
double rss_mb() {
  long pages = 0, resident = 0;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1e6;
}

// End-to-end frames per second, as `depot sim render` runs it.
double end_to_end_fps(const depot::sim::Scenario& scenario, int writers, double* mb_written) {
  const std::string out =
      (fs::temp_directory_path() / ("depot_sim_bench_" + std::to_string(getpid()))).string();
  depot::sim::RenderRequest request;
  request.dataset.output = out;
  request.dataset.writer_threads = writers;
  request.progress = false;
  const depot::sim::RenderSummary s = depot::sim::render_dataset(scenario, request);
  fs::remove_all(out);
  if (mb_written) *mb_written = s.bytes / 1e6;
  return s.frames / s.seconds;
}

// Resident memory after a tenth of the frames and after all of them, while
// rendering (no writing) `frames` frames.
std::pair<double, double> sequence_memory(depot::sim::Scenario scenario, int frames) {
  scenario.frames = frames;
  depot::sim::SimulatedSequence sequence(scenario, depot::sim::GlBackend::kOsMesa);
  depot::sim::RenderedFrame frame;
  depot::sim::FrameTruth truth;
  double early = 0;
  for (int i = 0; sequence.next(frame, truth, nullptr); ++i)
    if (i == frames / 10) early = rss_mb();
  return {early, rss_mb()};
}

// Time of apply_colour_sensor on `frames` rendered frames, per frame (ms):
// each stage of the colour pipeline added in turn, then a shipped profile.
void colour_pipeline_costs(const depot::sim::Scenario& scenario, int frames) {
  depot::sim::SimulatedSequence sequence(scenario, depot::sim::GlBackend::kOsMesa);
  std::vector<cv::Mat> images;
  depot::sim::RenderedFrame frame;
  depot::sim::FrameTruth truth;
  while (static_cast<int>(images.size()) < frames && sequence.next(frame, truth))
    images.push_back(frame.bgr.clone());
  // From the plain Kinect model (whatever profile the scenario names).
  depot::sim::SensorSpec sensor = scenario.sensor;
  sensor.ideal = false;
  sensor.light = {};
  sensor.exposure_control = {};
  sensor.colour = {};
  std::vector<std::pair<std::string, depot::sim::SensorSpec>> steps;
  steps.emplace_back("additive rgb_noise (baseline)", sensor);
  sensor.light.level = 0.8;  // the pipeline runs from here on
  steps.emplace_back("+ light and tone curve", sensor);
  sensor.colour.vignetting = 0.7;
  sensor.colour.lens_blur = 0.8;
  steps.emplace_back("+ vignetting, lens blur", sensor);
  sensor.colour.demosaic = "bilinear";
  steps.emplace_back("+ Bayer, bilinear", sensor);
  sensor.colour.demosaic = "edge_aware";
  steps.emplace_back("  (edge_aware instead)", sensor);
  sensor.colour.full_well = 10000;
  sensor.colour.read_noise = 5;
  steps.emplace_back("+ shot and read noise", sensor);
  sensor.colour.jpeg_quality = 90;
  steps.emplace_back("+ JPEG 90", sensor);
  std::printf("colour pipeline (apply_colour_sensor, %zu frames at %dx%d)\n", images.size(),
              scenario.camera.width, scenario.camera.height);
  double baseline = 0;
  for (const auto& [name, spec] : steps) {
    const auto t0 = Clock::now();
    for (size_t i = 0; i < images.size(); ++i) {
      cv::Mat image = images[i].clone();
      depot::sim::apply_colour_sensor(image, spec, {}, i);
    }
    const double per_frame = ms(t0, Clock::now()) / images.size();
    if (baseline == 0) baseline = per_frame;
    std::printf("  %-34s %8.2f ms/frame %8.2fx baseline\n", name.c_str(), per_frame,
                per_frame / baseline);
  }
}

// End to end with the scenario's sensor built up effect by effect, from the
// exact camera: what each effect of a profile (kinect_v1 on the shipped
// scenarios) costs, as ratios to the exact camera in the same run.
void sensor_effect_costs(const depot::sim::Scenario& scenario, int writers) {
  const depot::sim::SensorSpec full = scenario.sensor;
  std::vector<std::pair<std::string, depot::sim::SensorSpec>> steps;
  depot::sim::SensorSpec s = full;
  s.ideal = true;
  steps.emplace_back("exact camera (--ideal, baseline)", s);
  s = full;
  s.exposure = s.readout = 0;
  s.exposure_control = {};
  s.light = {};
  s.colour = {};
  s.lens = {};
  steps.emplace_back("depth model + additive noise", s);
  s.light = full.light;
  s.colour = full.colour;
  steps.emplace_back("+ light, colour pipeline", s);
  s.lens = full.lens;
  steps.emplace_back("+ lens distortion", s);
  // Auto-exposure sets the shutter's exposure: it comes with the blur.
  s.exposure_control = full.exposure_control;
  s.exposure = full.exposure;
  s.readout = full.readout;
  s.motion_blur = "field";
  steps.emplace_back("+ exposure, rolling shutter (field)", s);
  s.motion_blur = "subframes";
  steps.emplace_back("  (by sub-frame renders instead)", s);
  std::printf("sensor effects end to end (%s's sensor: exposure %.3f s%s, readout %.3f s)\n",
              scenario.name.c_str(), full.exposure, full.exposure_control.automatic ? " auto" : "",
              full.readout);
  double baseline = 0;
  auto measure = [&](const std::string& name, const depot::sim::Scenario& variant) {
    const double fps = end_to_end_fps(variant, writers, nullptr);
    if (baseline == 0) baseline = fps;
    std::printf("  %-36s %6.1f fps %6.2fx exact camera\n", name.c_str(), fps, fps / baseline);
  };
  for (const auto& [name, spec] : steps) {
    depot::sim::Scenario variant = scenario;
    variant.sensor = spec;
    measure(name, variant);
  }
  // Not the sensor's, but light all the same: MuJoCo's shadow maps, one
  // 2048 px pass per light a frame.
  depot::sim::Scenario shadowed = scenario;
  shadowed.sensor = full;
  shadowed.shadows = true;
  measure("+ the actors' shadows (shadows: true)", shadowed);
}

void row(const char* stage, double ms_per_frame, double baseline_ms) {
  std::printf("  %-34s %8.2f ms/frame %8.1f fps %8.2fx\n", stage, ms_per_frame,
              1000.0 / ms_per_frame, baseline_ms / ms_per_frame);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Simulator benchmark: per-stage and end-to-end frames per second"};
  std::string scenario_path = std::string(DEPOT_SOURCE_DIR) + "/scenarios/depot_walking_xyz.yaml";
  int frames = 150;
  int writers = 2;
  int memory_frames = 1800;
  std::vector<std::string> sets;
  app.add_option("--scenario", scenario_path, "Scenario YAML");
  app.add_option("--set", sets, "Scenario override KEY=VALUE, as `depot sim render --set`");
  app.add_option("--memory-frames", memory_frames,
                 "Frames of the memory run per actor style (0: skip it)")
      ->check(CLI::Range(0, 100000));
  app.add_option("--frames", frames, "Frames per measurement")->check(CLI::Range(10, 100000));
  app.add_option("--writers", writers, "Writer threads for the end-to-end run")
      ->check(CLI::Range(1, 32));
  CLI11_PARSE(app, argc, argv);
  try {
    std::vector<depot::YamlOverride> overrides;
    for (const std::string& text : sets)
      overrides.push_back(depot::parse_yaml_override(text, "--set"));
    depot::sim::Scenario scenario = depot::sim::load_scenario(scenario_path, overrides);
    scenario.frames = frames;

    // Stages, single-threaded, on the same frames.
    double physics = 0, render = 0, labels = 0, convert = 0, sensor = 0, png_rgb = 0, png_depth = 0,
           png_labels = 0;
    {
      depot::sim::SimulatedSequence sequence(scenario, depot::sim::GlBackend::kOsMesa);
      depot::sim::RenderedFrame frame;
      depot::sim::FrameTruth truth;
      depot::sim::SequenceTimings t;
      std::vector<uchar> buf;
      while (sequence.next(frame, truth, &t)) {
        physics += t.physics_ms;
        render += t.render.color_depth_ms;
        labels += t.render.segmentation_ms;
        convert += t.render.convert_ms;
        auto t0 = Clock::now();
        cv::Mat depth = depot::sim::apply_depth_model(frame.depth, scenario.sensor,
                                                      scenario.camera.f, truth.index);
        depot::sim::apply_colour_sensor(frame.bgr, scenario.sensor, truth.capture, truth.index);
        cv::Mat depth16 = depot::sim::depth_to_u16(depth, scenario.camera.depth_factor);
        auto t1 = Clock::now();
        cv::imencode(".png", frame.bgr, buf,
                     {cv::IMWRITE_PNG_COMPRESSION, 1, cv::IMWRITE_PNG_STRATEGY,
                      cv::IMWRITE_PNG_STRATEGY_HUFFMAN_ONLY});
        auto t2 = Clock::now();
        buf = depot::encode_png(depth16, depot::PngKind::kDepth);
        auto t3 = Clock::now();
        buf = depot::encode_png(frame.instance, depot::PngKind::kLabels);
        auto t4 = Clock::now();
        sensor += ms(t0, t1), png_rgb += ms(t1, t2), png_depth += ms(t2, t3),
            png_labels += ms(t3, t4);
      }
    }
    const double n = frames;
    const double base = render / n;

    double mb_written = 0;
    const double fps = end_to_end_fps(scenario, writers, &mb_written);

    std::printf(
        "depot_sim_bench: %s, %d frames at %dx%d, the scenario's sensor, %d writer threads\n",
        scenario.name.c_str(), frames, scenario.camera.width, scenario.camera.height, writers);
    std::printf("  %-34s %17s %12s %9s\n", "stage (single-threaded)", "", "", "vs render");
    row("physics + actor posing", physics / n, base);
    row("render RGB + depth (baseline)", base, base);
    row("render instance labels", labels / n, base);
    row("convert (flip, depth, ids)", convert / n, base);
    row("sensor model", sensor / n, base);
    row("PNG encode RGB (stored)", png_rgb / n, base);
    row("PNG encode depth", png_depth / n, base);
    row("PNG encode labels", png_labels / n, base);
    const double serial =
        (physics + render + labels + convert + sensor + png_rgb + png_depth + png_labels) / n;
    row("sum of stages (one core)", serial, base);
    row("end to end (render + labels + write)", 1000.0 / fps, base);
    std::printf("  end to end: %.1f fps (target >= 25 fps at 640x480), %.1f MB written\n", fps,
                mb_written);

    colour_pipeline_costs(scenario, std::min(frames, 60));
    sensor_effect_costs(scenario, writers);

    // Actor styles side by side, same scenario and frames.
    std::printf("actor styles (scenario's style: %s)\n", scenario.actors_style.c_str());
    double primitive_fps = 0;
    for (const char* style : {"primitive", "mesh"}) {
      depot::sim::Scenario styled = scenario;
      styled.actors_style = style;
      const double f = end_to_end_fps(styled, writers, nullptr);
      if (primitive_fps == 0) primitive_fps = f;
      std::printf("  %-9s end to end %6.1f fps  %5.2fx primitive\n", style, f, f / primitive_fps);
      if (memory_frames > 0) {
        const auto [early, late] = sequence_memory(styled, memory_frames);
        std::printf(
            "  %-9s resident memory %6.0f MB at frame %d, %6.0f MB at frame %d (%+.1f %%)\n", style,
            early, memory_frames / 10, late, memory_frames, 100.0 * (late - early) / early);
      }
    }
  } catch (const depot::Error& e) {
    std::fprintf(stderr, "depot_sim_bench: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
