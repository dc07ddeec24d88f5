#pragma once
// Shared pieces of the libFuzzer targets (tests/fuzz/, tools/fuzz.sh).
//
// The readers take paths: each input is written to a file in a scratch
// folder of the process (removed at exit) and read from there. The oracle,
// beyond the sanitizers: bad input must end in depot::Error, whose message
// is one line naming the file (or folder) read. Any other exception, or an
// error that does not name the file, aborts: libFuzzer records the input
// as a crash.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/binary_io.h"
#include "common/error.h"

namespace depot::fuzz {

// The process's scratch folder, removed when it exits.
inline const std::string& scratch_dir() {
  static const std::string dir = [] {
    const std::filesystem::path p =
        std::filesystem::temp_directory_path() / ("depot-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(p);
    return p.string();
  }();
  static const struct Cleanup {
    ~Cleanup() {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  } cleanup;
  return dir;
}

// Writes `size` bytes to `dir`/`name` (created or truncated); returns its path.
inline std::string write_file(const std::string& dir, const std::string& name, const uint8_t* data,
                              size_t size) {
  const std::string path = (std::filesystem::path(dir) / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

// The input as the file `name` in the scratch folder.
inline std::string write_input(const std::string& name, const uint8_t* data, size_t size) {
  return write_file(scratch_dir(), name, data, size);
}

[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz finding: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

// Runs `read`. A depot::Error is the expected way to refuse bad input: its
// message must be one line that contains `names` (the file or folder read).
// Anything else that escapes is a finding.
template <typename Read>
void expect_clean(const std::string& names, Read read) {
  try {
    read();
  } catch (const Error& e) {
    const std::string m = e.what();
    if (m.find('\n') != std::string::npos) finding("error of more than one line: " + m);
    if (m.find(names) == std::string::npos) finding("error does not name '" + names + "': " + m);
  } catch (const std::exception& e) {
    finding(std::string("escaped exception that is not depot::Error: ") + e.what());
  } catch (...) {
    finding("escaped exception of unknown type");
  }
}

// For LLVMFuzzerInitialize of a target whose seed the project's own writer
// makes: with DEPOT_FUZZ_WRITE_SEED=PATH (tools/fuzz.sh) the seed is written
// there by `write_seed` and the process ends.
template <typename WriteSeed>
void write_seed_if_asked(WriteSeed write_seed) {
  if (const char* seed = std::getenv("DEPOT_FUZZ_WRITE_SEED")) {
    write_seed(seed);
    std::exit(0);
  }
}

// The input with a valid CRC-32 over all but its last 4 bytes written into
// them (as the map and vocabulary files end), so mutations get past the
// checksum into the body.
inline std::string with_valid_checksum(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (bytes.size() >= 16) {
    const uint32_t crc = crc32_of(bytes, bytes.size() - 4);
    std::memcpy(&bytes[bytes.size() - 4], &crc, 4);
  }
  return bytes;
}

}  // namespace depot::fuzz
