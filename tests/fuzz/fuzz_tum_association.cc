// libFuzzer target: TUM associations ("t_rgb rgb t_depth depth") and image
// lists ("timestamp path"), then pairing the two columns of stamps the way
// evaluation pairs trajectories (common/tum_io.h, common/tum_association.h).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/tum_association.h"
#include "common/tum_io.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = depot::fuzz::write_input("associations.txt", data, size);
  depot::fuzz::expect_clean(path, [&] {
    const std::vector<depot::Association> pairs = depot::read_associations(path);
    // The rgb stamps increase (the reader checks); the depth stamps are
    // sorted here as a caller would before pairing.
    std::vector<double> rgb, depth;
    for (const auto& a : pairs) rgb.push_back(a.rgb_timestamp), depth.push_back(a.depth_timestamp);
    std::sort(depth.begin(), depth.end());
    depot::associate(rgb, depth);
    depot::associate(rgb, depth, {0.5, 0.01});
  });
  depot::fuzz::expect_clean(path, [&] { depot::read_file_list(path); });
  return 0;
}
