// `depot slam vocabulary train|info`: learning a place-recognition
// vocabulary from image folders and TUM datasets, and describing one.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "common/progress.h"
#include "common/staged_file.h"
#include "slam/feature/orb_extractor.h"
#include "slam/io/tum_sequence.h"
#include "slam/place/vocabulary_file.h"
#include "slam/place/vocabulary_training.h"
#include "tools/depot/cli_errors.h"
#include "tools/depot/commands.h"

namespace depot::cli {
namespace {

namespace fs = std::filesystem;

struct TrainArgs {
  std::string output;
  std::vector<std::string> image_folders;
  std::vector<std::string> datasets;
  size_t dataset_every = 10;
  int features = 1000;
  slam::VocabularyTrainingParams params;
  bool quiet = false;
};

bool is_image(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp";
}

// The training images: every image of each folder (sorted by name, so the
// order and hence the vocabulary are reproducible) and every n-th colour
// frame of each dataset.
struct TrainingImage {
  std::string path;  // image file, or dataset folder
  size_t frame = 0;  // frame of a dataset
  bool from_dataset = false;
};

std::vector<TrainingImage> list_images(const TrainArgs& a) {
  std::vector<TrainingImage> out;
  for (const std::string& folder : a.image_folders) {
    if (!fs::is_directory(folder)) fail(folder, "no such image folder");
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(folder))
      if (e.is_regular_file() && is_image(e.path())) files.push_back(e.path().string());
    if (files.empty()) fail(folder, "holds no .png/.jpg/.bmp images");
    std::sort(files.begin(), files.end());
    for (const std::string& f : files) out.push_back({f, 0, false});
  }
  for (const std::string& d : a.datasets) {
    slam::TumSequence seq(d);
    for (size_t i = 0; i < seq.size(); i += a.dataset_every) out.push_back({d, i, true});
  }
  return out;
}

void train(const TrainArgs& a) {
  if (a.image_folders.empty() && a.datasets.empty()) fail_usage("", "give --images or --dataset");
  check_output_file(a.output);
  const std::vector<TrainingImage> images = list_images(a);
  if (images.empty()) fail("depot slam vocabulary train", "give --images or --dataset");
  slam::OrbParams orb;
  orb.n_features = a.features;
  slam::OrbExtractor extractor(orb);
  std::vector<cv::Mat> descriptors;
  size_t total = 0;
  const auto t0 = std::chrono::steady_clock::now();
  Progress extract_progress("extracting ORB", images.size(), !a.quiet);
  std::unique_ptr<slam::TumSequence> open_dataset;
  for (size_t i = 0; i < images.size(); ++i) {
    const TrainingImage& img = images[i];
    cv::Mat bgr, gray;
    if (img.from_dataset) {
      if (!open_dataset || open_dataset->folder() != img.path)
        open_dataset = std::make_unique<slam::TumSequence>(img.path);
      cv::Mat depth;
      open_dataset->load(img.frame, bgr, depth);
    } else {
      bgr = cv::imread(img.path, cv::IMREAD_COLOR);
      if (bgr.empty()) fail(img.path, "not a readable image");
    }
    cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
    std::vector<cv::KeyPoint> kps;
    cv::Mat d;
    extractor.extract(gray, cv::Mat(), kps, d);
    total += static_cast<size_t>(d.rows);
    descriptors.push_back(d);
    extract_progress.update(i + 1, std::to_string(total) + " descriptors");
  }
  extract_progress.finish();
  const auto t1 = std::chrono::steady_clock::now();
  Progress tree_progress("building the tree", 100, !a.quiet);
  const slam::Vocabulary vocabulary = slam::train_vocabulary(
      descriptors, a.params,
      [&](double share) { tree_progress.update(static_cast<size_t>(share * 100)); });
  tree_progress.finish();
  const auto t2 = std::chrono::steady_clock::now();
  slam::save_vocabulary(vocabulary, a.output);
  const auto secs = [](auto from, auto to) {
    return std::chrono::duration<double>(to - from).count();
  };
  std::printf(
      "vocabulary %s: %zu words (k %d, %d levels) from %zu descriptors of %zu images; "
      "%.1f s extracting, %.1f s clustering; %.1f MB; identity %08x\n",
      a.output.c_str(), vocabulary.n_words(), vocabulary.branching(), vocabulary.levels(), total,
      images.size(), secs(t0, t1), secs(t1, t2), static_cast<double>(fs::file_size(a.output)) / 1e6,
      slam::vocabulary_identity(vocabulary));
}

void info(const std::string& path) {
  const slam::Vocabulary v = slam::load_vocabulary(path);
  size_t leaves_by_depth[9] = {};
  for (const slam::VocabularyNode& n : v.nodes())
    if (n.word >= 0 && n.depth < 9) leaves_by_depth[n.depth]++;
  std::printf("%s: %zu words, %zu nodes, branching %d, %d levels, identity %08x\n", path.c_str(),
              v.n_words(), v.n_nodes(), v.branching(), v.levels(), slam::vocabulary_identity(v));
  std::printf("words by depth:");
  for (int d = 1; d <= v.levels() && d < 9; ++d) std::printf(" %d:%zu", d, leaves_by_depth[d]);
  std::printf("\n");
}

}  // namespace

void register_vocabulary_commands(CLI::App* slam_group) {
  CLI::App* group = slam_group->add_subcommand(
      "vocabulary", "Place-recognition vocabularies (bags of binary ORB words)");
  group->require_subcommand(1);
  auto a = std::make_shared<TrainArgs>();
  CLI::App* train_cmd =
      group->add_subcommand("train", "Learn a vocabulary tree from image folders and TUM datasets");
  train_cmd->add_option("-o,--output", a->output, "Vocabulary file to write")->required();
  train_cmd->add_option("--images", a->image_folders,
                        "Folder of .png/.jpg images (all of them, sorted by name); repeatable");
  train_cmd->add_option("--dataset", a->datasets, "TUM RGB-D folder; repeatable");
  train_cmd->add_option("--dataset-every", a->dataset_every, "Every n-th frame of each dataset")
      ->check(CLI::Range(1, 100000));
  train_cmd->add_option("--features", a->features, "ORB features per image")
      ->check(CLI::Range(50, 20000));
  train_cmd->add_option("--branching", a->params.branching, "Children per node (k)")
      ->check(CLI::Range(2, 64));
  train_cmd->add_option("--levels", a->params.levels, "Depth of the tree (up to k^levels words)")
      ->check(CLI::Range(1, 8));
  train_cmd->add_option("--seed", a->params.seed, "Seed of the k-means++ initialisation");
  train_cmd->add_flag("-q,--quiet", a->quiet, "No progress lines");
  train_cmd->callback([a] { train(*a); });

  auto path = std::make_shared<std::string>();
  CLI::App* info_cmd = group->add_subcommand("info", "Describe a vocabulary file");
  info_cmd->add_option("file", *path, "Vocabulary file")->required();
  info_cmd->callback([path] { info(*path); });
}

}  // namespace depot::cli
