#include "dataset/mcap/mcap_records.h"

#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

#include "common/error.h"

namespace depot::mcap {

std::string compression_name(Compression c) {
  switch (c) {
    case Compression::kZstd:
      return "zstd";
    case Compression::kLz4:
      return "lz4";
    case Compression::kNone:
      break;
  }
  return "";
}

Compression parse_compression(const std::string& name, const std::string& where) {
  if (name.empty() || name == "none") return Compression::kNone;
  if (name == "zstd") return Compression::kZstd;
  if (name == "lz4") return Compression::kLz4;
  fail(where, "unknown chunk compression '" + name + "' (known: zstd, lz4, none)");
}

uint64_t nanoseconds_of(double seconds) {
  // Rounded, so a timestamp written with six decimals comes back as written.
  return static_cast<uint64_t>(std::llround(seconds * 1e6)) * 1000u;
}

double seconds_of(uint64_t nanoseconds) {
  // Through the decimal text a TUM list holds ("%.6f"), so a time comes back
  // as the very double the folder's reader parses from rgb.txt.
  const uint64_t micro = (nanoseconds + 500u) / 1000u;
  const std::string text = fmt::format("{}.{:06d}", micro / 1000000u, micro % 1000000u);
  return std::strtod(text.c_str(), nullptr);
}

}  // namespace depot::mcap
