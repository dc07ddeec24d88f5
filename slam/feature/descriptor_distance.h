#pragma once
// Hamming distance between 256-bit binary (ORB) descriptors.
#include <cstdint>
#include <cstring>

#include <opencv2/core/mat.hpp>

namespace depot::slam {

// Bytes in one ORB descriptor (256 bits); a descriptor matrix is N x 32 CV_8U.
inline constexpr int kDescriptorBytes = 32;

// Number of differing bits between two 32-byte descriptors (0..256). Reads the
// bytes as four 64-bit words (memcpy: no alignment requirement, no aliasing UB).
// __builtin_popcountll is one POPCNT instruction when the translation unit is
// compiled with -mpopcnt (or -march=x86-64-v2 and up); with the generic x86-64
// baseline GCC calls libgcc's __popcountdi2 instead, which is still exact.
inline int descriptor_distance(const std::uint8_t* a, const std::uint8_t* b) {
  std::uint64_t wa[4];
  std::uint64_t wb[4];
  std::memcpy(wa, a, sizeof(wa));
  std::memcpy(wb, b, sizeof(wb));
  return __builtin_popcountll(wa[0] ^ wb[0]) + __builtin_popcountll(wa[1] ^ wb[1]) +
         __builtin_popcountll(wa[2] ^ wb[2]) + __builtin_popcountll(wa[3] ^ wb[3]);
}

// Same for two descriptor rows (1 x 32 CV_8U, e.g. descriptors.row(i)). The shape
// is checked with CV_DbgAssert only (debug builds): this sits in matching loops.
inline int descriptor_distance(const cv::Mat& a, const cv::Mat& b) {
  CV_DbgAssert(a.type() == CV_8UC1 && b.type() == CV_8UC1 && a.total() == 32 && b.total() == 32);
  return descriptor_distance(a.ptr<std::uint8_t>(), b.ptr<std::uint8_t>());
}

}  // namespace depot::slam
