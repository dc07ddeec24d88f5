#pragma once
// Reads an MCAP file: checks both magics and the footer, the summary's CRC
// when it has one, and each chunk's CRC when it is decompressed; lists every
// message (from the chunk and message indexes when the file has them, else
// by one pass over the data section) so any message can be read on its own.
// Memory holds the message list and one decompressed chunk.
//
// One thread: the chunk cache makes reading a mutation.
#include <cstdint>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "dataset/mcap/mcap_records.h"

namespace depot::mcap {

// Where a message lies: in a chunk (the chunk record's file offset and the
// message's offset in its uncompressed records) or, outside chunks, at
// `offset` in the file (chunk_offset 0).
struct MessageRef {
  uint16_t channel_id = 0;
  uint64_t log_time = 0;
  uint64_t chunk_offset = 0;
  uint64_t offset = 0;
};

struct Message {
  uint16_t channel_id = 0;
  uint32_t sequence = 0;
  uint64_t log_time = 0, publish_time = 0;
  std::string data;
};

class Reader {
 public:
  // Throws depot::Error "<path>: <problem>" for a missing file, a file that
  // is not MCAP (magic), a truncated one, a summary whose CRC does not match
  // or a record that does not parse.
  explicit Reader(const std::string& path);

  const std::string& path() const { return path_; }
  const std::string& profile() const { return profile_; }
  const std::map<uint16_t, Schema>& schemas() const { return schemas_; }
  const std::map<uint16_t, Channel>& channels() const { return channels_; }
  // The channel on `topic`, if any.
  const Channel* channel(const std::string& topic) const;
  // Every message, in log-time order (file order among equal times).
  const std::vector<MessageRef>& messages() const { return messages_; }
  // Reads one message; a chunk whose CRC does not match throws.
  Message read(const MessageRef& ref);

 private:
  std::string read_at(uint64_t offset, uint64_t n, const std::string& what);
  void read_summary(uint64_t summary_start, uint64_t summary_end, uint32_t crc);
  void scan_data_section(uint64_t end);
  void list_chunk(uint64_t chunk_offset, const std::string& records);
  void add_schema_or_channel(uint8_t op, const std::string& content);
  const std::string& chunk_records(uint64_t chunk_offset);

  std::string path_;
  std::ifstream in_;
  uint64_t size_ = 0;
  std::string profile_;
  std::map<uint16_t, Schema> schemas_;
  std::map<uint16_t, Channel> channels_;
  std::vector<MessageRef> messages_;
  // Chunk indexes of the summary: chunk offset -> (message index start, length).
  std::vector<std::pair<uint64_t, uint64_t>> chunk_offsets_;
  std::optional<uint64_t> cached_chunk_;
  std::string cached_records_;
};

}  // namespace depot::mcap
