#pragma once
// The MCAP spec's serialisation of record fields (little-endian integers,
// uint32-length-prefixed strings and maps), shared by the writer and the
// reader so the two cannot drift apart.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/binary_io.h"
#include "dataset/mcap/mcap_records.h"

namespace depot::mcap {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "MCAP integers are little-endian; depot::BinaryWriter writes the machine's order");

// A record's content, then framed as <opcode><uint64 length><content>.
class RecordWriter {
 public:
  void u8(uint8_t v) { out_.put(v); }
  void u16(uint16_t v) { out_.put(v); }
  void u32(uint32_t v) { out_.put(v); }
  void u64(uint64_t v) { out_.put(v); }
  void string(const std::string& s) {
    u32(static_cast<uint32_t>(s.size()));
    out_.put_bytes(s.data(), s.size());
  }
  void bytes(const std::string& s) { out_.put_bytes(s.data(), s.size()); }
  void string_map(const std::vector<std::pair<std::string, std::string>>& map) {
    RecordWriter body;
    for (const auto& [key, value] : map) {
      body.string(key);
      body.string(value);
    }
    u32(static_cast<uint32_t>(body.content().size()));
    bytes(body.content());
  }
  const std::string& content() { return out_.bytes(); }
  // The whole record: opcode, content length, content.
  std::string framed(Opcode op) {
    RecordWriter head;
    head.u8(static_cast<uint8_t>(op));
    head.u64(out_.bytes().size());
    return head.out_.bytes() + out_.bytes();
  }

 private:
  BinaryWriter out_;
};

// A record's content as read; running past its end is "<where>: truncated
// <what>".
class RecordReader {
 public:
  RecordReader(std::string content, const std::string& where, const std::string& what)
      : content_(std::move(content)), in_(content_, where, what) {}
  uint8_t u8() { return in_.take<uint8_t>(); }
  uint16_t u16() { return in_.take<uint16_t>(); }
  uint32_t u32() { return in_.take<uint32_t>(); }
  uint64_t u64() { return in_.take<uint64_t>(); }
  std::string bytes(size_t n) {
    in_.require(n);  // "truncated" before allocating
    std::string s(n, '\0');
    in_.take_bytes(s.data(), n);
    return s;
  }
  std::string string() { return bytes(u32()); }
  std::vector<std::pair<std::string, std::string>> string_map() {
    const uint32_t length = u32();
    const size_t end = in_.at() + length;
    std::vector<std::pair<std::string, std::string>> map;
    while (in_.at() < end) {
      std::string key = string();
      map.emplace_back(std::move(key), string());
    }
    return map;
  }
  // Skips a uint32-length-prefixed array or map.
  void skip_block() { bytes(u32()); }
  size_t at() const { return in_.at(); }
  size_t left() const { return in_.left(); }

 private:
  std::string content_;  // owned: BinaryReader refers to it
  BinaryReader in_;
};

}  // namespace depot::mcap
