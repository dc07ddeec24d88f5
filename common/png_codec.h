#pragma once
// PNG images, with libpng directly. Encoding uses a fixed row filter and
// zlib strategy per image kind instead of libpng's adaptive filter search
// (OpenCV's default), which halves the cost of writing a frame. Decoding
// reports a damaged file as one error naming it, where OpenCV would let
// libpng print its own lines to stderr first.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace depot {

enum class PngKind {
  kColor,   // noisy colour: SUB filter, Huffman-only entropy coding
  kDepth,   // 16-bit depth: no filter, LZ matching (runs of equal values)
  kLabels,  // 16-bit instance ids: no filter, LZ matching
};

// Encodes CV_8UC3 (BGR), CV_16UC1 or CV_8UC1 to PNG bytes (lossless).
std::vector<unsigned char> encode_png(const cv::Mat& image, PngKind kind,
                                      int compression_level = 1);

// Encodes `image` as encode_png does and writes it to `path`; returns the
// bytes written. Throws depot::Error("<path>: write failed ...").
size_t write_png(const std::string& path, const cv::Mat& image, PngKind kind,
                 int compression_level = 1);

enum class ImageRead {
  kColor,      // CV_8UC3 BGR, as cv::IMREAD_COLOR
  kUnchanged,  // bit depth and channels as stored (alpha dropped), as cv::IMREAD_UNCHANGED
};

// Reads an image file: PNG with libpng, other formats with OpenCV. Throws
// depot::Error("<path>: <problem>") for a missing, damaged or unknown file.
cv::Mat read_image(const std::string& path, ImageRead mode);

}  // namespace depot
