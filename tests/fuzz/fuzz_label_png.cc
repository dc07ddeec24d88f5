// libFuzzer target: label images (16-bit PNG instance ids) through
// dataset/label_images.h, and the same bytes as a colour image
// (common/png_codec.h: libpng for PNG, OpenCV for anything else).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "common/png_codec.h"
#include "dataset/label_images.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string dir = [] {
    const std::string d = depot::fuzz::scratch_dir() + "/dataset";
    std::filesystem::create_directories(d + "/labels");
    return d;
  }();
  const std::string path = depot::fuzz::write_file(dir, "labels/1.000000.png", data, size);
  depot::fuzz::expect_clean(path,
                            [&] { depot::dataset::read_label_image(dir, "labels/1.000000.png"); });
  depot::fuzz::expect_clean(path, [&] { depot::read_image(path, depot::ImageRead::kColor); });
  return 0;
}
