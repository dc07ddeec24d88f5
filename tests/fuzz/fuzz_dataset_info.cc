// libFuzzer target: a simulated dataset's info.json (dataset/dataset_info.h).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "dataset/dataset_info.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string dir = [] {
    const std::string d = depot::fuzz::scratch_dir() + "/dataset";
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::string path = depot::fuzz::write_file(dir, "info.json", data, size);
  depot::fuzz::expect_clean(path, [&] { depot::dataset::read_info(dir); });
  return 0;
}
