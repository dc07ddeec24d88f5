#pragma once
// A chunk's records compressed and back: zstd (libzstd) or the LZ4 frame
// format (liblz4), as MCAP names them.
#include <string>

#include "dataset/mcap/mcap_records.h"

namespace depot::mcap {

std::string compress(Compression c, const std::string& records);
// Throws depot::Error "<where>: ..." when the bytes do not decompress to
// exactly `uncompressed_size` bytes.
std::string decompress(Compression c, const std::string& compressed, size_t uncompressed_size,
                       const std::string& where);

}  // namespace depot::mcap
