#pragma once
// Writes an MCAP file as ROS 2 tools expect it (profile "ros2"): schemas
// and channels in the data section, messages in compressed chunks each
// followed by its message indexes, then the summary (schemas, channels,
// chunk indexes, statistics), summary offsets and a footer, with the CRCs
// of every chunk, the data section and the summary. Streamed: only the chunk
// being filled is held in memory. The file appears at its path only when
// close() succeeds (common/staged_file.h).
//
// One thread: a writer is not shared.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/staged_file.h"
#include "dataset/mcap/mcap_records.h"

namespace depot::mcap {

struct WriterOptions {
  Compression compression = Compression::kZstd;
  // A chunk is closed once its records pass this size: a few frames of
  // 640x480 RGB-D, so a reader seeking to one decompresses little.
  size_t chunk_size = 4u << 20;
  // CRCs of chunks, the data section and the summary (false: zero, "not
  // computed" in the spec; the fuzz target's seed, so mutations reach the
  // parsers instead of the CRC checks).
  bool crcs = true;
  std::string profile = "ros2";
  std::string library = "depot-slam";
};

struct WriterTotals {
  uint64_t messages = 0;
  uint32_t chunks = 0;
  uint64_t uncompressed_bytes = 0;  // of the chunks' records
  uint64_t file_bytes = 0;          // after close()
};

class Writer {
 public:
  // Throws depot::Error naming `path` when it cannot be written.
  Writer(const std::string& path, WriterOptions options = {});
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Ids count from 1 in the order added; a schema is written once.
  uint16_t add_schema(const std::string& name, const std::string& encoding,
                      const std::string& data);
  uint16_t add_channel(uint16_t schema_id, const std::string& topic,
                       const std::string& message_encoding,
                       std::vector<std::pair<std::string, std::string>> metadata = {});
  // Appends a message; `sequence` counts the channel's messages from 0.
  void write(uint16_t channel_id, uint64_t log_time, uint64_t publish_time,
             const std::string& data);
  // Ends the data section, writes the summary and footer, and moves the file
  // into place. Without it (an exception on the way) no file is left.
  void close();
  const WriterTotals& totals() const { return totals_; }

 private:
  struct ChunkIndexEntry {
    uint64_t start_time, end_time, offset, length;
    std::map<uint16_t, uint64_t> message_index_offsets;
    uint64_t message_index_length;
    uint64_t compressed_size, uncompressed_size;
  };
  void emit(const std::string& bytes);
  void flush_chunk();

  WriterOptions options_;
  StagedFile file_;
  uint64_t position_ = 0;
  uint32_t data_crc_ = 0;
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::vector<uint32_t> channel_sequence_;
  std::map<uint16_t, uint64_t> channel_counts_;
  // The chunk being filled: its records and each channel's (log time,
  // offset in the records) pairs.
  std::string chunk_;
  std::map<uint16_t, std::vector<std::pair<uint64_t, uint64_t>>> chunk_index_;
  uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::vector<ChunkIndexEntry> chunk_indexes_;
  uint64_t start_time_ = 0, end_time_ = 0;
  WriterTotals totals_;
  bool closed_ = false;
};

}  // namespace depot::mcap
