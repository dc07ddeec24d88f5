#pragma once
// Fast PNG encoding for datasets, with libpng directly: a fixed row filter
// and zlib strategy per image kind instead of libpng's adaptive filter
// search (OpenCV's default), which halves the cost of writing a frame.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace depot::sim {

enum class PngKind {
  kColor,   // noisy colour: SUB filter, Huffman-only entropy coding
  kDepth,   // 16-bit depth: no filter, LZ matching (runs of equal values)
  kLabels,  // 16-bit instance ids: no filter, LZ matching
};

// Encodes CV_8UC3 (BGR), CV_16UC1 or CV_8UC1 to PNG bytes (lossless).
std::vector<unsigned char> encode_png(const cv::Mat& image, PngKind kind,
                                      int compression_level = 1);

}  // namespace depot::sim
