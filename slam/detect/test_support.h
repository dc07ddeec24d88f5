#pragma once
// Helpers for the detector tests: where the shared real data is, and a
// scratch folder removed at the end of a test.
#include <filesystem>
#include <string>

#include "common/testing/scratch_folder.h"

namespace depot::slam::test {

inline std::string shared_data() {
  return DEPOT_SHARED_DATA;
}
inline std::string source_dir() {
  return DEPOT_SOURCE_DIR;
}
inline std::string tum_frame() {
  return shared_data() + "/tum/fr3_walking_xyz_frame/rgb/1341846313.592026.png";
}
inline std::string yolo_fastest_dir() {
  return shared_data() + "/models/yolo-fastest-1.1";
}
inline std::string fastestdet_dir() {
  return shared_data() + "/models/fastestdet";
}
inline bool have_shared_data() {
  return std::filesystem::exists(tum_frame());
}

#define DEPOT_REQUIRE_SHARED_DATA()                                                          \
  do {                                                                                       \
    if (!::depot::slam::test::have_shared_data())                                            \
      GTEST_SKIP() << "shared real data not found at " << ::depot::slam::test::shared_data() \
                   << " (needs models/ and tum/fr3_walking_xyz_frame/)";                     \
  } while (0)

// A scratch folder removed at the end of a test (common/testing).
using TempDir = ::depot::testkit::ScratchFolder;

}  // namespace depot::slam::test
