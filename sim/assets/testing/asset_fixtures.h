#pragma once
// Test helpers (header-only) for sim/assets: paths into the shared real
// models, models loaded once per test process, and a scratch folder.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <string>

#include "sim/assets/asset_loader.h"

namespace depot::sim::testing {

inline std::string shared_asset(const std::string& relative) {
  return std::string(DEPOT_SHARED_DATA) + "/assets/" + relative;
}

// The people's files: metres, +y up, facing +z.
inline AssetLoadOptions person_options() {
  AssetLoadOptions o;
  o.up = Axis::kPosY;
  o.forward = Axis::kPosZ;
  return o;
}

// mh_worker_male.glb loaded once (it takes ~0.2 s).
inline const AssetModel& worker() {
  static const AssetModel model =
      load_asset(shared_asset("people/mh_worker_male.glb"), person_options());
  return model;
}

// A folder of this test process, made by mkdtemp and removed at exit.
inline const std::filesystem::path& scratch_dir() {
  static std::filesystem::path dir;
  static std::once_flag once;
  std::call_once(once, [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "depot_assets_XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot create " + pattern);
    dir = pattern;
    if (!std::getenv("DEPOT_KEEP_TEST_FILES"))
      std::atexit([] {
        std::error_code ec;
        std::filesystem::remove_all(dir, ec);
      });
  });
  return dir;
}

// Writes `bytes` to scratch_dir()/name and returns the path.
inline std::string scratch_file(const std::string& name, const std::string& bytes) {
  const std::filesystem::path p = scratch_dir() / name;
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << bytes;
  return p.string();
}

}  // namespace depot::sim::testing
