// libFuzzer target: TUM trajectories ("timestamp tx ty tz qx qy qz qw"),
// with the file-kind detection and the timestamp column every TUM text
// file shares (common/tum_io.h).
#include <cstddef>
#include <cstdint>

#include "common/tum_io.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = depot::fuzz::write_input("trajectory.txt", data, size);
  depot::fuzz::expect_clean(path, [&] { depot::read_tum_trajectory(path); });
  depot::fuzz::expect_clean(path, [&] { depot::detect_tum_file_kind(path); });
  depot::fuzz::expect_clean(path, [&] { depot::read_timestamps(path); });
  return 0;
}
