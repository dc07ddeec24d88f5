// `depot export mcap DATASET -o run.mcap`: a dataset folder as a ROS 2 bag
// (tools/bag/bag_export.h says what goes where).
#include <cstdio>
#include <memory>
#include <string>

#include "common/error.h"
#include "common/staged_file.h"
#include "dataset/mcap/mcap_records.h"
#include "tools/bag/bag_export.h"
#include "tools/depot/commands.h"

namespace depot::cli {
namespace {

struct ExportArgs {
  std::string dataset, output, compression = "zstd";
  bool quiet = false;
};

void export_mcap(const ExportArgs& a) {
  bag::BagExportOptions options;
  options.compression = mcap::parse_compression(a.compression, "--compression");
  if (a.output.size() < 6 || a.output.compare(a.output.size() - 5, 5, ".mcap") != 0)
    fail(a.output, "a bag's name must end in .mcap (that is how `depot slam run` knows it)");
  check_output_file(a.output);
  options.progress = !a.quiet;
  const bag::BagExportReport r = bag::export_bag(a.dataset, a.output, options);
  const double mb = r.totals.file_bytes / 1e6, folder_mb = r.folder_bytes / 1e6;
  std::printf(
      "wrote %s: %zu frames, %llu messages on %zu topics in %u %s chunks, %.1f MB (the folder: "
      "%.1f MB, %.2fx), %.1f frames/s\n",
      a.output.c_str(), r.frames, static_cast<unsigned long long>(r.totals.messages),
      r.topics.size(), r.totals.chunks,
      options.compression == mcap::Compression::kNone ? "uncompressed" : a.compression.c_str(), mb,
      folder_mb, folder_mb > 0 ? mb / folder_mb : 0.0, r.seconds > 0 ? r.frames / r.seconds : 0.0);
}

}  // namespace

void register_export_commands(CLI::App& app) {
  CLI::App* group = app.add_subcommand("export", "Write datasets in other formats: mcap");
  group->require_subcommand(1);
  auto args = std::make_shared<ExportArgs>();
  CLI::App* mcap = group->add_subcommand(
      "mcap", "Write a dataset as a ROS 2 bag (MCAP, CDR): images, camera_info, tf, truth");
  mcap->add_option("dataset", args->dataset, "Dataset folder (TUM RGB-D, simulated or real)")
      ->required();
  mcap->add_option("-o,--output", args->output, "Bag to write (.mcap)")->required();
  mcap->add_option("--compression", args->compression, "Chunk compression: zstd, lz4 or none")
      ->capture_default_str();
  mcap->add_flag("-q,--quiet", args->quiet, "No progress line");
  mcap->callback([args] { export_mcap(*args); });
}

}  // namespace depot::cli
