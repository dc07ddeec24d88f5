// libFuzzer target: PLY point clouds as `depot eval cloud` reads them
// (tools/perception/cloud_eval.cc): our header/length check first
// (slam/io/ply_file.h, check_ply_file), then assimp on what passed it (a
// count that differs from the header's is read_cloud's error). Seeds come from the writer:
// DEPOT_FUZZ_WRITE_SEED=FILE fuzz_ply_file writes a small binary PLY and
// exits.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "slam/io/ply_file.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

void write_seed(const std::string& path) {
  std::vector<depot::slam::PlyPoint> points;
  for (int i = 0; i < 4; ++i)
    points.push_back({Eigen::Vector3f(0.1f * i, 0.2f, 1.5f),
                      cv::Vec3b(10, static_cast<uint8_t>(20 * i), 30), i + 1});
  depot::slam::write_ply(path, points, "observations");
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  depot::fuzz::write_seed_if_asked(write_seed);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = depot::fuzz::write_input("cloud.ply", data, size);
  depot::slam::PlyCheck check;
  bool valid = false;
  depot::fuzz::expect_clean(path, [&] {
    check = depot::slam::check_ply_file(path);
    valid = true;
  });
  if (!valid || !check.only_vertices) return 0;
  // What read_cloud does next.
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, 0);
  size_t points = 0;
  for (unsigned m = 0; scene && m < scene->mNumMeshes; ++m)
    points += scene->mMeshes[m]->mNumVertices;
  static_cast<void>(points);
  return 0;
}
