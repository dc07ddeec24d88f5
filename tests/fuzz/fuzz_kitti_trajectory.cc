// libFuzzer target: KITTI poses (12 numbers a line), a format systems under
// test write (common/tum_io.h).
#include <cstddef>
#include <cstdint>

#include "common/tum_io.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = depot::fuzz::write_input("poses.txt", data, size);
  depot::fuzz::expect_clean(path, [&] { depot::read_kitti_poses(path); });
  return 0;
}
