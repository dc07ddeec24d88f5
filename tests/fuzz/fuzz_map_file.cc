// libFuzzer target: saved maps (slam/io/map_file.h), as `slam map info` and
// `map export` read them (camera and pyramid from the file) and as
// `--load-map` does (the run's camera, pyramid and vocabulary, here the
// file's own so that the body is read).
//
// A map ends in a CRC-32 of the bytes before it, which mutated input would
// almost never match: the target writes the right one over the input's last
// four bytes, so the fuzzer reaches the body. Seeds come from the writer:
// DEPOT_FUZZ_WRITE_SEED=FILE fuzz_map_file writes a small map and exits.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include "common/binary_io.h"
#include "slam/data/map.h"
#include "slam/data/map_point.h"
#include "slam/io/map_file.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

using namespace depot::slam;

// Two keyframes seeing three points.
void write_seed(const std::string& path) {
  static const ScaleLevels levels = ScaleLevels::make(8, 1.2f);
  const PinholeCamera camera;
  Map map;
  depot::MutexLock lock(map.mutex());
  std::vector<KeyFrame*> kfs;
  for (int k = 0; k < 2; ++k) {
    std::vector<cv::KeyPoint> kps;
    for (int i = 0; i < 3; ++i)
      kps.emplace_back(100.0f + 50 * i + 5 * k, 200.0f + 10 * i, 31.0f, 10.0f * i, 1.0f, i % 2);
    cv::Mat descriptors(3, 32, CV_8U);
    for (int i = 0; i < 3; ++i)
      for (int b = 0; b < 32; ++b) descriptors.at<uint8_t>(i, b) = static_cast<uint8_t>(i * 37 + b);
    Frame frame(k, 1.0 + 0.1 * k,
                Features(kps, descriptors, std::vector<float>{2.0f, 2.5f, -1.0f}, camera, &levels));
    frame.T_cw.translation() = Eigen::Vector3d(0.1 * k, 0, 0);
    frame.has_pose = true;
    kfs.push_back(map.create_keyframe(frame));
  }
  for (int i = 0; i < 3; ++i) {
    MapPoint* mp = map.create_map_point(Eigen::Vector3d(0.1 * i, 0.2, 2.0), kfs[0]);
    for (KeyFrame* kf : kfs) {
      mp->add_observation(kf, i);
      kf->add_map_point(mp, i);
    }
    mp->update_descriptor();
    mp->update_normal_and_depth();
  }
  for (KeyFrame* kf : kfs) kf->update_connections();
  kfs[1]->loop_edges.insert(kfs[0]);
  save_map_file(map, camera, levels, 0x1234abcd, path);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  depot::fuzz::write_seed_if_asked(write_seed);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes = depot::fuzz::with_valid_checksum(data, size);
  const std::string path = depot::fuzz::write_input(
      "map.bin", reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  MapFileInfo info;
  depot::fuzz::expect_clean(path, [&] {
    ScaleLevels levels;
    Map map;
    depot::MutexLock lock(map.mutex());
    info = load_map_file_as_saved(path, levels, map);
  });
  if (info.levels > 0) {
    const ScaleLevels levels = ScaleLevels::make(info.levels, info.scale_factor);
    depot::fuzz::expect_clean(path, [&] {
      Map map;
      depot::MutexLock lock(map.mutex());
      load_map_file(path, info.camera, levels, info.vocabulary, map);
    });
  }
  return 0;
}
