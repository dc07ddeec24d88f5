// libFuzzer target: EuRoC CSV trajectories ("timestamp[ns],px,py,pz,qw,qx,
// qy,qz"), a format systems under test write (common/tum_io.h).
#include <cstddef>
#include <cstdint>

#include "common/tum_io.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = depot::fuzz::write_input("trajectory.csv", data, size);
  depot::fuzz::expect_clean(path, [&] { depot::read_euroc_trajectory(path); });
  return 0;
}
