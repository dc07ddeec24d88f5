// `depot sim ...`: render scenarios to datasets, list them, preview datasets.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <optional>

#include "common/error.h"
#include "common/image_size.h"
#include "sim/dataset/contact_sheet.h"
#include "sim/pipeline/export_truth.h"
#include "sim/pipeline/render_dataset.h"
#include "sim/scenario/scenario_loader.h"
#include "tools/depot/commands.h"
#include "sim/scenario/shipped_scenarios.h"

namespace fs = std::filesystem;

namespace depot::cli {
namespace {

struct RenderArgs {
  std::string scenario;
  std::string output;
  int frames = 0;
  uint64_t seed = 0;
  double load = -1;
  std::string gl = "osmesa";
  bool ideal = false;
  bool overwrite = false;
  bool yolo = false;
  bool quiet = false;
  int writers = 2;
  int width = 0;
  int png_level = -1;
  std::vector<std::string> settings;  // --set KEY=VALUE
};

std::vector<YamlOverride> parse_overrides(const std::vector<std::string>& texts) {
  std::vector<YamlOverride> overrides;
  for (const auto& t : texts) overrides.push_back(parse_yaml_override(t, "--set"));
  return overrides;
}

void add_set_option(CLI::App* cmd, std::vector<std::string>& settings) {
  cmd->add_option("--set", settings,
                  "Change a scenario key, e.g. --set sensor.rgb_noise=4 (repeatable)")
      ->default_str("");
}

void run_render(const RenderArgs& a, const CLI::App& cmd) {
  sim::Scenario scenario =
      sim::load_scenario(sim::resolve_scenario(a.scenario), parse_overrides(a.settings));
  sim::RenderRequest r;
  r.dataset.output = a.output;
  r.dataset.overwrite = a.overwrite;
  r.dataset.yolo_export = a.yolo;
  r.dataset.writer_threads = a.writers;
  r.dataset.png_compression = a.png_level;
  r.gl = sim::parse_gl_backend(a.gl);
  if (cmd.count("--frames")) r.frames = a.frames;
  if (cmd.count("--seed")) r.seed = a.seed;
  if (cmd.count("--load")) r.dynamic_load = a.load;
  if (cmd.count("--width")) r.width = a.width;
  r.ideal = a.ideal;
  r.progress = !a.quiet;
  sim::RenderSummary s = sim::render_dataset(scenario, r);
  std::printf(
      "rendered %d frames of %s to %s in %.1f s (%.1f fps end to end; per frame: physics %.1f ms, "
      "rgb+depth %.1f ms, "
      "labels %.1f ms, convert %.1f ms; sensor model %.1f ms and PNG writing %.1f ms on writer "
      "threads; %.1f MB)\n",
      s.frames, scenario.name.c_str(), s.output.c_str(), s.seconds, s.frames / s.seconds,
      s.physics_ms, s.color_depth_ms, s.segmentation_ms, s.convert_ms, s.sensor_ms,
      s.encode_write_ms, s.bytes / 1e6);
  if (s.subframes > 1.0) {
    // Under auto-exposure the exposure is each frame's own (exposures.txt).
    const bool automatic = scenario.sensor.exposure_control.automatic;
    const std::string times =
        fmt::format("exposure {}{:.1f} ms, readout {:.1f} ms", automatic ? "auto, up to " : "",
                    scenario.sensor.longest_exposure() * 1e3, scenario.sensor.readout * 1e3);
    if (scenario.sensor.motion_blur == "field")
      std::printf(
          "shutter: %.1f sub-frames per frame on average, moved from one render by the motion "
          "field in %.1f ms (%s; sim/sensor/motion_field.h)\n",
          s.subframes, s.field_ms, times.c_str());
    else
      std::printf("shutter: %.1f colour renders per frame on average (%s; sim/sensor/shutter.h)\n",
                  s.renders, times.c_str());
  }
}

void run_list() {
  const std::string folder = sim::scenarios_folder();
  for (const auto& name : sim::list_scenarios(folder)) {
    sim::Scenario s = sim::load_scenario((fs::path(folder) / (name + ".yaml")).string());
    int living = 0, pushables = 0;
    for (const auto& a : s.actors) {
      if (sim::is_living_actor(a.type)) ++living;
      if (sim::is_pushable_actor(a.type)) ++pushables;
    }
    std::printf("%-28s %4d frames  motion %-10s  %d actors, %d pushables  %s\n", name.c_str(),
                s.frames, s.motion.type.c_str(), living, pushables, s.description.c_str());
  }
}

}  // namespace

void register_sim_commands(CLI::App& app) {
  CLI::App* sim = app.add_subcommand("sim", "Simulate the depot and write TUM RGB-D datasets");
  sim->require_subcommand(1);

  auto args = std::make_shared<RenderArgs>();
  CLI::App* render =
      sim->add_subcommand("render", "Render a scenario to a TUM RGB-D dataset with labels");
  render
      ->add_option("scenario", args->scenario,
                   "Scenario YAML file, or the name of a shipped scenario")
      ->required();
  render
      ->add_option("-o,--output", args->output,
                   "Output dataset folder (appears only when complete)")
      ->required();
  render->add_option("--frames", args->frames, "Number of frames")
      ->check(CLI::Range(1, 1000000))
      ->default_str("the scenario's");
  render->add_option("--seed", args->seed, "Random seed")->default_str("the scenario's");
  render
      ->add_option("--load", args->load,
                   "Dynamic load factor: number, size and speed of actors (0..4)")
      ->check(CLI::Range(0.0, 4.0))
      ->default_str("the scenario's");
  render->add_option("--gl", args->gl, "Off-screen GL backend")
      ->check(CLI::IsMember({"osmesa", "egl"}));
  render
      ->add_option("--width", args->width,
                   "Image width (default: the scenario's); height and intrinsics scale with it; "
                   "each side 32..4096 px")
      ->check(CLI::Range(kMinImageSide, kMaxImageSide))
      ->default_str("the scenario's");
  render->add_flag("--ideal", args->ideal, "No sensor model: exact depth and colour");
  render->add_flag("--overwrite", args->overwrite, "Replace an existing output folder");
  render->add_flag("--yolo", args->yolo,
                   "Also export a YOLO training set (yolo/images, yolo/labels, data.yaml)");
  render->add_option("--writers", args->writers, "PNG writer threads")->check(CLI::Range(1, 32));
  render->add_option("--png-level", args->png_level, "zlib level 0-9 for all images")
      ->check(CLI::Range(0, 9))
      ->default_str("colour stored, depth and labels 1");
  render->add_flag("-q,--quiet", args->quiet, "No progress bar");
  add_set_option(render, args->settings);
  render->callback([args, render] { run_render(*args, *render); });

  auto truth_args = std::make_shared<RenderArgs>();
  CLI::App* truth = sim->add_subcommand(
      "truth",
      "Export a scenario's ground truth only (trajectory, object poses, objects): no images, fast");
  truth
      ->add_option("scenario", truth_args->scenario,
                   "Scenario YAML file, or the name of a shipped scenario")
      ->required();
  truth->add_option("-o,--output", truth_args->output, "Output folder (appears only when complete)")
      ->required();
  truth->add_option("--frames", truth_args->frames, "Number of frames")
      ->check(CLI::Range(1, 1000000))
      ->default_str("the scenario's");
  truth->add_option("--seed", truth_args->seed, "Random seed")->default_str("the scenario's");
  truth->add_option("--load", truth_args->load, "Dynamic load factor (0..4)")
      ->check(CLI::Range(0.0, 4.0))
      ->default_str("the scenario's");
  truth->add_flag("--overwrite", truth_args->overwrite, "Replace an existing output folder");
  truth->add_flag("-q,--quiet", truth_args->quiet, "No progress bar");
  add_set_option(truth, truth_args->settings);
  truth->callback([truth_args, truth] {
    sim::Scenario scenario = sim::load_scenario(sim::resolve_scenario(truth_args->scenario),
                                                parse_overrides(truth_args->settings));
    sim::RenderRequest r;
    r.dataset.output = truth_args->output;
    r.dataset.overwrite = truth_args->overwrite;
    if (truth->count("--frames")) r.frames = truth_args->frames;
    if (truth->count("--seed")) r.seed = truth_args->seed;
    if (truth->count("--load")) r.dynamic_load = truth_args->load;
    r.progress = !truth_args->quiet;
    sim::TruthSummary s = sim::export_truth(scenario, r);
    std::printf("exported the ground truth of %d frames of %s to %s in %.2f s (%.0f frames/s)\n",
                s.frames, scenario.name.c_str(), s.output.c_str(), s.seconds, s.frames / s.seconds);
  });

  CLI::App* list = sim->add_subcommand("list", "List the shipped scenarios");
  list->callback([] { run_list(); });

  auto preview_dataset = std::make_shared<std::string>();
  auto preview_out = std::make_shared<std::string>();
  auto preview_opts = std::make_shared<sim::ContactSheetOptions>();
  CLI::App* preview =
      sim->add_subcommand("preview", "Write a contact sheet (RGB | depth | labels) of a dataset");
  preview->add_option("dataset", *preview_dataset, "Dataset folder")->required();
  preview->add_option("-o,--output", *preview_out, "Output image (.png, .jpg or .jpeg)")
      ->required();
  preview->add_option("--rows", preview_opts->rows, "Frames shown")->check(CLI::Range(1, 50));
  preview->callback([=] {
    sim::write_contact_sheet(*preview_dataset, *preview_out, *preview_opts);
    std::printf("wrote %s\n", preview_out->c_str());
  });
}

}  // namespace depot::cli
