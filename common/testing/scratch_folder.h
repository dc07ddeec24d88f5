#pragma once
// A test's scratch folder: fresh under the system temp dir, named after the
// test and made unique, removed with everything in it on destruction.
// (The test kit's namespace is testkit, so that code inside namespace depot
// still means gtest's when it names `testing` unqualified.)
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace depot::testkit {

class ScratchFolder {
 public:
  explicit ScratchFolder(const std::string& name = "test") {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("depot_" + name + "_" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // The path of `name` inside the folder (not created).
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  // Writes `text` to `name` (binary, as given) and returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(file(name), std::ios::binary) << text;
    return file(name);
  }
  // `bytes` pseudo-random bytes from a fixed seed (the same file every run).
  std::string write_random(const std::string& name, size_t bytes, unsigned seed = 7) const {
    std::mt19937 gen(seed);
    std::string s(bytes, '\0');
    for (char& c : s) c = static_cast<char>(gen() & 0xFF);
    return write(name, s);
  }

 private:
  std::filesystem::path path_;
};

}  // namespace depot::testkit
