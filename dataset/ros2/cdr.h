#pragma once
// ROS 2's message serialisation: OMG CDR, little-endian (encapsulation
// header 00 01 00 00), each primitive aligned to its size counted from after
// the header, strings as uint32 length with the NUL, sequences as a uint32
// count then elements, fixed arrays as elements only.
#include <cstdint>
#include <cstring>
#include <string>

#include "common/error.h"

namespace depot::ros2 {

class CdrWriter {
 public:
  CdrWriter() : out_("\x00\x01\x00\x00", 4) {}
  void u8(uint8_t v) { put(v); }
  void boolean(bool v) { put<uint8_t>(v ? 1 : 0); }
  void u32(uint32_t v) { put(v); }
  void i32(int32_t v) { put(v); }
  void f64(double v) { put(v); }
  void string(const std::string& s) {
    put(static_cast<uint32_t>(s.size() + 1));
    out_.append(s);
    out_.push_back('\0');
  }
  // uint8[]: count, then the bytes.
  void byte_sequence(const void* data, size_t n) {
    put(static_cast<uint32_t>(n));
    out_.append(static_cast<const char*>(data), n);
  }
  void sequence_length(size_t n) { put(static_cast<uint32_t>(n)); }
  std::string& bytes() { return out_; }

 private:
  template <typename T>
  void put(T v) {
    while ((out_.size() - 4) % sizeof(T) != 0) out_.push_back('\0');
    char raw[sizeof(T)];
    std::memcpy(raw, &v, sizeof(T));
    out_.append(raw, sizeof(T));
  }
  std::string out_;
};

// Reads what a CdrWriter wrote; `where` names the message for the errors
// ("<where>: truncated CDR ...", a big-endian or unknown encapsulation).
class CdrReader {
 public:
  CdrReader(const std::string& bytes, std::string where) : in_(bytes), where_(std::move(where)) {
    if (in_.size() < 4)
      fail(where_, "truncated CDR message (" + std::to_string(in_.size()) + " bytes)");
    if (in_[0] != 0 || in_[1] != 1)
      fail(where_, in_[0] == 0 && in_[1] == 0
                       ? "big-endian CDR is not supported (ROS 2 writes little-endian)"
                       : "not a CDR message (unknown encapsulation header)");
    at_ = 4;
  }
  uint8_t u8() { return take<uint8_t>(); }
  bool boolean() { return take<uint8_t>() != 0; }
  uint32_t u32() { return take<uint32_t>(); }
  int32_t i32() { return take<int32_t>(); }
  double f64() { return take<double>(); }
  std::string string() {
    const uint32_t n = take<uint32_t>();
    if (n == 0) return "";  // some writers send an empty string as length 0
    need(n);
    std::string s(in_.data() + at_, n - 1);
    at_ += n;
    return s;
  }
  std::string byte_sequence() {
    const uint32_t n = take<uint32_t>();
    need(n);
    std::string s(in_.data() + at_, n);
    at_ += n;
    return s;
  }
  uint32_t sequence_length() {
    const uint32_t n = take<uint32_t>();
    // Every element takes at least one byte: a count past the end is damage.
    if (n > in_.size() - at_)
      fail(where_, "truncated CDR message (a sequence of " + std::to_string(n) + ")");
    return n;
  }

 private:
  template <typename T>
  T take() {
    while ((at_ - 4) % sizeof(T) != 0) ++at_;
    need(sizeof(T));
    T v;
    std::memcpy(&v, in_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  void need(size_t n) const {
    if (at_ > in_.size() || n > in_.size() - at_)
      fail(where_, "truncated CDR message (" + std::to_string(in_.size()) + " bytes)");
  }
  const std::string& in_;
  std::string where_;
  size_t at_ = 0;
};

}  // namespace depot::ros2
