#pragma once
// The pieces of the MCAP container format (https://mcap.dev/spec, major
// version 0) that the writer and the reader share: magic, record opcodes,
// chunk compressions, and the plain records a user of the file sees.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace depot::mcap {

// 0x89 'M' 'C' 'A' 'P' '0' '\r' '\n': first and last eight bytes of a file.
inline constexpr char kMagic[8] = {'\x89', 'M', 'C', 'A', 'P', '0', '\r', '\n'};

enum class Opcode : uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

// How a chunk's records are compressed: "" (none), "zstd" or "lz4" (the LZ4
// frame format), the spec's well-known names.
enum class Compression { kNone, kZstd, kLz4 };
std::string compression_name(Compression c);
// Throws depot::Error "<where>: unknown chunk compression '<name>' ..." for
// any other name.
Compression parse_compression(const std::string& name, const std::string& where);

struct Schema {
  uint16_t id = 0;  // never 0 in a file
  std::string name;
  std::string encoding;  // "ros2msg" here
  std::string data;      // the definition text
};

struct Channel {
  uint16_t id = 0;
  uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;  // "cdr" here
  std::vector<std::pair<std::string, std::string>> metadata;
};

// Nanoseconds since the epoch of the dataset's timestamps (TUM: Unix time).
uint64_t nanoseconds_of(double seconds);
double seconds_of(uint64_t nanoseconds);

}  // namespace depot::mcap
