#pragma once
// Helpers for the detector tests: where the shared real data is, and a
// scratch folder removed at the end of a test.
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

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

// A fresh folder under the system temp dir, removed on destruction.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("depot_detect_test_" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(file(name), std::ios::binary) << text;
    return file(name);
  }
  // `bytes` pseudo-random bytes from a fixed seed (same file every run).
  std::string write_random(const std::string& name, size_t bytes, unsigned seed = 7) const {
    std::mt19937 gen(seed);
    std::string s(bytes, '\0');
    for (char& c : s) c = static_cast<char>(gen() & 0xFF);
    return write(name, s);
  }

 private:
  std::filesystem::path path_;
};

}  // namespace depot::slam::test
