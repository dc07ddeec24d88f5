// `depot eval realism DATASET [--reference REAL]`: image statistics of a
// (simulated) recording side by side with a real one (eval/image_realism.h).
#include <algorithm>
#include <cstdio>
#include <memory>

#include <CLI/CLI.hpp>
#include <opencv2/imgproc.hpp>

#include "common/config_path.h"
#include "common/progress.h"
#include "common/staged_file.h"
#include "eval/image_realism.h"
#include "slam/io/tum_sequence.h"
#include "tools/depot/commands.h"
#include "tools/depot/output_paths.h"

namespace depot::cli {
namespace {

struct RealismArgs {
  std::string dataset;
  std::string reference;
  int frames = 300;
  int every = 1;
  std::string page;
  bool quiet = false;
};

std::string folder_name(const std::string& folder) {
  std::string f = folder;
  while (f.size() > 1 && f.back() == '/') f.pop_back();
  const size_t slash = f.find_last_of('/');
  return slash == std::string::npos ? f : f.substr(slash + 1);
}

// Every `every`-th frame, `frames` at most; the frame before each gives
// its image motion.
eval::Realism measure_recording(const std::string& folder, const RealismArgs& a) {
  const slam::TumSequence sequence(folder);
  std::vector<size_t> picked;
  for (size_t i = 0; i < sequence.size() && static_cast<int>(picked.size()) < a.frames;
       i += static_cast<size_t>(a.every))
    picked.push_back(i);
  Progress progress("realism " + folder_name(folder), picked.size(), !a.quiet);
  std::vector<eval::FrameRealism> frames;
  cv::Mat bgr, depth, previous_bgr, previous_depth, previous_grey;
  for (size_t k = 0; k < picked.size(); ++k) {
    const size_t i = picked[k];
    previous_grey.release();
    if (i > 0) {
      sequence.load(i - 1, previous_bgr, previous_depth);
      cv::cvtColor(previous_bgr, previous_grey, cv::COLOR_BGR2GRAY);
    }
    sequence.load(i, bgr, depth);
    frames.push_back(eval::measure_frame(bgr, depth, previous_grey));
    progress.update(k + 1);
  }
  progress.finish();
  return eval::summarise_realism(folder_name(folder), frames);
}

void run_realism(const RealismArgs& a) {
  OutputPaths outputs;
  outputs.add_input_folder("DATASET", a.dataset);
  outputs.add_input_folder("--reference", a.reference);
  outputs.add_file("--page", a.page);
  outputs.check();
  if (!a.page.empty()) check_output_file(a.page);
  const eval::Realism simulated = measure_recording(a.dataset, a);
  const eval::Realism reference = measure_recording(a.reference, a);
  std::printf("%s", eval::format_realism_table(simulated, reference).c_str());
  if (a.page.empty()) return;
  StagedFile page(a.page);
  page.stream() << eval::realism_page(simulated, reference);
  page.commit();
  std::printf("wrote %s\n", a.page.c_str());
}

}  // namespace

void register_realism_eval_command(CLI::App* eval_group) {
  auto args = std::make_shared<RealismArgs>();
  args->reference = shared_data_dir() + "/tum/fr3_walking_xyz_frame";
  CLI::App* cmd = eval_group->add_subcommand(
      "realism",
      "Image statistics of a dataset beside a real recording's: sharpness, noise by brightness, "
      "ORB keypoints, depth holes by depth and at edges, image motion");
  cmd->add_option("DATASET", args->dataset, "A TUM RGB-D folder (a simulated dataset)")->required();
  cmd->add_option("--reference", args->reference,
                  "A real recording: a TUM RGB-D folder, or rgb/ and depth/ of images named by "
                  "their timestamps")
      ->capture_default_str();
  cmd->add_option("--frames", args->frames, "Measure this many frames of each at most")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--every", args->every, "Measure every n-th frame")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--page", args->page, "Write the side-by-side page (HTML, with plots)");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress line");
  cmd->callback([args] { run_realism(*args); });
}

}  // namespace depot::cli
