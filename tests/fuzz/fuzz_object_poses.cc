// libFuzzer target: a simulated dataset's object_poses.txt (dataset/object_poses.h).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "dataset/object_poses.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string dir = [] {
    const std::string d = depot::fuzz::scratch_dir() + "/dataset";
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::string path = depot::fuzz::write_file(dir, "object_poses.txt", data, size);
  depot::fuzz::expect_clean(path, [&] { depot::dataset::read_object_poses(dir); });
  return 0;
}
