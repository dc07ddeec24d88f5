#include "dataset/mcap/mcap_writer.h"

#include <algorithm>

#include <zlib.h>

#include "common/error.h"
#include "dataset/mcap/chunk_compression.h"
#include "dataset/mcap/record_io.h"

namespace depot::mcap {

namespace {

uint32_t crc_update(uint32_t crc, const std::string& bytes) {
  return static_cast<uint32_t>(
      crc32(crc, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())));
}

std::string schema_record(const Schema& s) {
  RecordWriter r;
  r.u16(s.id);
  r.string(s.name);
  r.string(s.encoding);
  r.string(s.data);  // uint32-length-prefixed bytes, as a string
  return r.framed(Opcode::kSchema);
}

std::string channel_record(const Channel& c) {
  RecordWriter r;
  r.u16(c.id);
  r.u16(c.schema_id);
  r.string(c.topic);
  r.string(c.message_encoding);
  r.string_map(c.metadata);
  return r.framed(Opcode::kChannel);
}

}  // namespace

Writer::Writer(const std::string& path, WriterOptions options)
    : options_(std::move(options)), file_(path) {
  emit(std::string(kMagic, sizeof kMagic));
  RecordWriter header;
  header.string(options_.profile);
  header.string(options_.library);
  emit(header.framed(Opcode::kHeader));
}

Writer::~Writer() = default;  // an unclosed file_ removes its partial file

void Writer::emit(const std::string& bytes) {
  file_.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!file_.stream()) fail(file_.final_path(), "cannot write the MCAP file (disk full?)");
  data_crc_ = crc_update(data_crc_, bytes);
  position_ += bytes.size();
}

uint16_t Writer::add_schema(const std::string& name, const std::string& encoding,
                            const std::string& data) {
  Schema s{static_cast<uint16_t>(schemas_.size() + 1), name, encoding, data};
  emit(schema_record(s));
  schemas_.push_back(std::move(s));
  return schemas_.back().id;
}

uint16_t Writer::add_channel(uint16_t schema_id, const std::string& topic,
                             const std::string& message_encoding,
                             std::vector<std::pair<std::string, std::string>> metadata) {
  if (schema_id > schemas_.size())
    throw Error("mcap::Writer: channel " + topic + " names schema " + std::to_string(schema_id) +
                ", which was never added");
  Channel c{static_cast<uint16_t>(channels_.size() + 1), schema_id, topic, message_encoding,
            std::move(metadata)};
  emit(channel_record(c));
  channels_.push_back(std::move(c));
  channel_sequence_.push_back(0);
  return channels_.back().id;
}

void Writer::write(uint16_t channel_id, uint64_t log_time, uint64_t publish_time,
                   const std::string& data) {
  if (channel_id == 0 || channel_id > channels_.size())
    throw Error("mcap::Writer: message on channel " + std::to_string(channel_id) +
                ", which was never added");
  RecordWriter r;
  r.u16(channel_id);
  r.u32(channel_sequence_[channel_id - 1]++);
  r.u64(log_time);
  r.u64(publish_time);
  r.bytes(data);
  if (chunk_.empty()) chunk_start_ = chunk_end_ = log_time;
  chunk_index_[channel_id].emplace_back(log_time, chunk_.size());
  chunk_ += r.framed(Opcode::kMessage);
  chunk_start_ = std::min(chunk_start_, log_time);
  chunk_end_ = std::max(chunk_end_, log_time);
  if (totals_.messages == 0) start_time_ = end_time_ = log_time;
  start_time_ = std::min(start_time_, log_time);
  end_time_ = std::max(end_time_, log_time);
  ++totals_.messages;
  ++channel_counts_[channel_id];
  if (chunk_.size() >= options_.chunk_size) flush_chunk();
}

void Writer::flush_chunk() {
  if (chunk_.empty()) return;
  const std::string compressed = compress(options_.compression, chunk_);
  RecordWriter chunk;
  chunk.u64(chunk_start_);
  chunk.u64(chunk_end_);
  chunk.u64(chunk_.size());
  chunk.u32(options_.crcs ? crc_update(0, chunk_) : 0);
  chunk.string(compression_name(options_.compression));
  chunk.u64(compressed.size());
  chunk.bytes(compressed);
  ChunkIndexEntry entry{chunk_start_, chunk_end_, position_,         0,
                        {},           0,          compressed.size(), chunk_.size()};
  emit(chunk.framed(Opcode::kChunk));
  entry.length = position_ - entry.offset;
  const uint64_t indexes_start = position_;
  for (const auto& [channel, entries] : chunk_index_) {
    RecordWriter index;
    index.u16(channel);
    index.u32(static_cast<uint32_t>(entries.size() * 16));
    for (const auto& [time, offset] : entries) {
      index.u64(time);
      index.u64(offset);
    }
    entry.message_index_offsets[channel] = position_;
    emit(index.framed(Opcode::kMessageIndex));
  }
  entry.message_index_length = position_ - indexes_start;
  chunk_indexes_.push_back(std::move(entry));
  totals_.uncompressed_bytes += chunk_.size();
  ++totals_.chunks;
  chunk_.clear();
  chunk_index_.clear();
}

void Writer::close() {
  if (closed_) return;
  flush_chunk();
  RecordWriter data_end;
  data_end.u32(options_.crcs ? data_crc_ : 0);
  emit(data_end.framed(Opcode::kDataEnd));

  // The summary, grouped by opcode, each group found by a summary offset.
  const uint64_t summary_start = position_;
  data_crc_ = 0;  // from here on: the summary's CRC
  std::vector<std::tuple<Opcode, uint64_t, uint64_t>> groups;
  auto group = [&](Opcode op, const std::vector<std::string>& records) {
    if (records.empty()) return;
    const uint64_t start = position_;
    for (const std::string& r : records) emit(r);
    groups.emplace_back(op, start, position_ - start);
  };
  std::vector<std::string> records;
  for (const Schema& s : schemas_) records.push_back(schema_record(s));
  group(Opcode::kSchema, records);
  records.clear();
  for (const Channel& c : channels_) records.push_back(channel_record(c));
  group(Opcode::kChannel, records);
  records.clear();
  for (const ChunkIndexEntry& e : chunk_indexes_) {
    RecordWriter r;
    r.u64(e.start_time);
    r.u64(e.end_time);
    r.u64(e.offset);
    r.u64(e.length);
    r.u32(static_cast<uint32_t>(e.message_index_offsets.size() * 10));
    for (const auto& [channel, offset] : e.message_index_offsets) {
      r.u16(channel);
      r.u64(offset);
    }
    r.u64(e.message_index_length);
    r.string(compression_name(options_.compression));
    r.u64(e.compressed_size);
    r.u64(e.uncompressed_size);
    records.push_back(r.framed(Opcode::kChunkIndex));
  }
  group(Opcode::kChunkIndex, records);
  RecordWriter stats;
  stats.u64(totals_.messages);
  stats.u16(static_cast<uint16_t>(schemas_.size()));
  stats.u32(static_cast<uint32_t>(channels_.size()));
  stats.u32(0);  // attachments
  stats.u32(0);  // metadata
  stats.u32(totals_.chunks);
  stats.u64(start_time_);
  stats.u64(end_time_);
  stats.u32(static_cast<uint32_t>(channel_counts_.size() * 10));
  for (const auto& [channel, count] : channel_counts_) {
    stats.u16(channel);
    stats.u64(count);
  }
  group(Opcode::kStatistics, {stats.framed(Opcode::kStatistics)});

  const uint64_t summary_offset_start = position_;
  for (const auto& [op, start, length] : groups) {
    RecordWriter r;
    r.u8(static_cast<uint8_t>(op));
    r.u64(start);
    r.u64(length);
    emit(r.framed(Opcode::kSummaryOffset));
  }
  // The footer's CRC covers the summary through its own offset fields.
  RecordWriter footer_head;
  footer_head.u8(static_cast<uint8_t>(Opcode::kFooter));
  footer_head.u64(20);
  footer_head.u64(summary_start);
  footer_head.u64(summary_offset_start);
  emit(footer_head.content());
  RecordWriter footer_crc;
  footer_crc.u32(options_.crcs ? data_crc_ : 0);
  emit(footer_crc.content());
  emit(std::string(kMagic, sizeof kMagic));
  file_.commit();
  totals_.file_bytes = position_;
  closed_ = true;
}

}  // namespace depot::mcap
