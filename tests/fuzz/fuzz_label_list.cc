// libFuzzer target: a simulated dataset's labels.txt, the list of its label images
// (dataset/label_images.h).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "dataset/label_images.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string dir = [] {
    const std::string d = depot::fuzz::scratch_dir() + "/dataset";
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::string path = depot::fuzz::write_file(dir, "labels.txt", data, size);
  depot::fuzz::expect_clean(path, [&] { depot::dataset::read_label_list(dir); });
  return 0;
}
