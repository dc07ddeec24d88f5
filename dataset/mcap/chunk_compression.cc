#include "dataset/mcap/chunk_compression.h"

#include <lz4frame.h>
#include <zstd.h>

#include "common/error.h"

namespace depot::mcap {

namespace {

// Level 3 is zstd's default: 5-8x faster than level 19 at 5-10 % more bytes
// on images, which keeps export near the TUM folder's own PNG speed.
constexpr int kZstdLevel = 3;

std::string zstd_compress(const std::string& in) {
  std::string out(ZSTD_compressBound(in.size()), '\0');
  const size_t n = ZSTD_compress(out.data(), out.size(), in.data(), in.size(), kZstdLevel);
  if (ZSTD_isError(n)) throw Error(std::string("zstd: ") + ZSTD_getErrorName(n));
  out.resize(n);
  return out;
}

std::string lz4_compress(const std::string& in) {
  LZ4F_preferences_t prefs{};
  prefs.frameInfo.contentSize = in.size();
  std::string out(LZ4F_compressFrameBound(in.size(), &prefs), '\0');
  const size_t n = LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), &prefs);
  if (LZ4F_isError(n)) throw Error(std::string("lz4: ") + LZ4F_getErrorName(n));
  out.resize(n);
  return out;
}

void zstd_decompress(const std::string& in, std::string& out, const std::string& where) {
  const size_t n = ZSTD_decompress(out.data(), out.size(), in.data(), in.size());
  if (ZSTD_isError(n))
    fail(where, std::string("zstd chunk does not decompress: ") + ZSTD_getErrorName(n));
  if (n != out.size())
    fail(where, "zstd chunk holds " + std::to_string(n) + " bytes, its header says " +
                    std::to_string(out.size()));
}

void lz4_decompress(const std::string& in, std::string& out, const std::string& where) {
  LZ4F_dctx* ctx = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&ctx, LZ4F_VERSION)))
    throw Error("lz4: cannot create a decompression context");
  size_t written = 0, read = 0;
  size_t status = 1;
  while (status != 0 && read < in.size()) {
    size_t out_n = out.size() - written, in_n = in.size() - read;
    status = LZ4F_decompress(ctx, out.data() + written, &out_n, in.data() + read, &in_n, nullptr);
    if (LZ4F_isError(status)) {
      const std::string why = LZ4F_getErrorName(status);
      LZ4F_freeDecompressionContext(ctx);
      fail(where, "lz4 chunk does not decompress: " + why);
    }
    written += out_n;
    read += in_n;
    if (out_n == 0 && in_n == 0) break;  // no progress: the output is full
  }
  LZ4F_freeDecompressionContext(ctx);
  if (status != 0 || written != out.size())
    fail(where, "lz4 chunk holds " + std::to_string(written) + " bytes, its header says " +
                    std::to_string(out.size()));
}

}  // namespace

std::string compress(Compression c, const std::string& records) {
  switch (c) {
    case Compression::kZstd:
      return zstd_compress(records);
    case Compression::kLz4:
      return lz4_compress(records);
    case Compression::kNone:
      break;
  }
  return records;
}

std::string decompress(Compression c, const std::string& compressed, size_t uncompressed_size,
                       const std::string& where) {
  if (c == Compression::kNone) {
    if (compressed.size() != uncompressed_size)
      fail(where, "uncompressed chunk holds " + std::to_string(compressed.size()) +
                      " bytes, its header says " + std::to_string(uncompressed_size));
    return compressed;
  }
  std::string out(uncompressed_size, '\0');
  if (c == Compression::kZstd)
    zstd_decompress(compressed, out, where);
  else
    lz4_decompress(compressed, out, where);
  return out;
}

}  // namespace depot::mcap
