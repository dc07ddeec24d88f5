// `depot slam map info M` and `depot slam map export M -o F.ply`: what a
// saved map holds, and its points as a coloured point cloud.
#include <cstdio>
#include <memory>
#include <string>

#include "slam/data/map.h"
#include "slam/data/map_point.h"
#include "slam/io/map_export.h"
#include "slam/io/map_file.h"
#include "slam/io/ply_file.h"
#include "tools/depot/commands.h"

namespace depot::cli {
namespace {

struct LoadedMap {
  slam::MapFileInfo info;
  slam::ScaleLevels levels;
  slam::Map map;
};

// The map as its file describes it (its own camera, pyramid and vocabulary).
std::unique_ptr<LoadedMap> load(const std::string& path) {
  auto loaded = std::make_unique<LoadedMap>();
  MutexLock lock(loaded->map.mutex());
  loaded->info = slam::load_map_file_as_saved(path, loaded->levels, loaded->map);
  return loaded;
}

void info(const std::string& path) {
  const auto m = load(path);
  const slam::MapFileInfo& i = m->info;
  size_t observations = 0;
  {
    MutexLock lock(m->map.mutex());
    for (const slam::MapPoint* mp : m->map.map_points()) observations += mp->observations.size();
  }
  const slam::PinholeCamera& c = i.camera;
  const std::string lens = c.distorted() ? " lens " + describe_lens(c.lens) : "";
  std::printf(
      "%s: map format %u, %zu keyframes, %zu map points (%.1f observations each) in %zu map%s of "
      "the atlas, camera %dx%d fx %.1f fy %.1f cx %.1f cy %.1f%s, ORB pyramid %d levels x %.2f, "
      "vocabulary identity %08x\n",
      path.c_str(), i.version, i.keyframes, i.points,
      i.points ? static_cast<double>(observations) / i.points : 0.0, i.maps, i.maps == 1 ? "" : "s",
      c.width, c.height, c.fx, c.fy, c.cx, c.cy, lens.c_str(), i.levels, i.scale_factor,
      i.vocabulary);
}

void export_points(const std::string& path, const std::string& output) {
  const auto m = load(path);
  std::vector<slam::PlyPoint> cloud;
  {
    MutexLock lock(m->map.mutex());
    cloud = slam::map_point_cloud(m->map);
  }
  slam::write_ply(output, cloud, "observations");
  std::printf("wrote %s: %zu map points of %s\n", output.c_str(), cloud.size(), path.c_str());
}

}  // namespace

void register_map_commands(CLI::App* slam_group) {
  CLI::App* group =
      slam_group->add_subcommand("map", "Saved maps (depot slam run --save-map): info, export");
  group->require_subcommand(1);
  auto path = std::make_shared<std::string>();
  CLI::App* info_cmd = group->add_subcommand("info", "Describe a saved map");
  info_cmd->add_option("file", *path, "Map file")->required();
  info_cmd->callback([path] { info(*path); });

  auto export_path = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  CLI::App* export_cmd = group->add_subcommand(
      "export", "Write a map's points as a coloured PLY point cloud (with observation counts)");
  export_cmd->add_option("file", *export_path, "Map file")->required();
  export_cmd->add_option("-o,--output", *output, "PLY file to write")->required();
  export_cmd->callback([export_path, output] { export_points(*export_path, *output); });
}

}  // namespace depot::cli
