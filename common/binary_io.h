#pragma once
// Little helpers for the project's own binary files (vocabulary, map): plain
// values appended to a byte string and read back with bounds checks, and the
// CRC-32 (zlib) that such files end with.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <zlib.h>

#include "common/error.h"

namespace depot {

// The whole of a binary file; `what` names its kind in the errors ("no such
// map file", "is a folder, not a map file", "cannot open the map file").
inline std::string read_binary_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path, "no such " + what + " file");
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a folder, not a " + what + " file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the " + what + " file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

inline uint32_t crc32_of(const std::string& bytes, size_t n) {
  return static_cast<uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(n)));
}

// Appends trivially copyable values in the machine's byte order (the files
// are read back on the machines that wrote them: x86-64 and arm64, both
// little-endian).
class BinaryWriter {
 public:
  template <typename T>
  void put(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    bytes_.append(raw, sizeof(T));
  }
  void put_bytes(const void* data, size_t n) { bytes_.append(static_cast<const char*>(data), n); }
  // Appends the CRC-32 of everything written so far.
  void put_checksum() { put<uint32_t>(crc32_of(bytes_, bytes_.size())); }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

// Reads what a BinaryWriter wrote; running past the end is depot::Error
// "<path>: truncated <what>".
class BinaryReader {
 public:
  BinaryReader(const std::string& bytes, std::string path, std::string what, size_t at = 0)
      : bytes_(bytes), path_(std::move(path)), what_(std::move(what)), at_(at) {}

  template <typename T>
  T take() {
    T value;
    std::memcpy(&value, need(sizeof(T)), sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  void take_bytes(void* out, size_t n) {
    std::memcpy(out, need(n), n);
    at_ += n;
  }
  size_t at() const { return at_; }
  size_t left() const { return bytes_.size() - at_; }
  // Throws "truncated" unless `n` more bytes are there (before a caller
  // allocates for them).
  void require(size_t n) const { need(n); }

 private:
  const char* need(size_t n) const {
    if (n > bytes_.size() - at_)
      fail(path_, "truncated " + what_ + " (" + std::to_string(bytes_.size()) + " bytes)");
    return bytes_.data() + at_;
  }
  const std::string& bytes_;
  std::string path_, what_;
  size_t at_;
};

}  // namespace depot
