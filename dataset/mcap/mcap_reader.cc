#include "dataset/mcap/mcap_reader.h"

#include <algorithm>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>
#include <zlib.h>

#include "common/error.h"
#include "dataset/mcap/chunk_compression.h"
#include "dataset/mcap/record_io.h"

namespace depot::mcap {

namespace {

constexpr uint64_t kRecordHead = 9;                   // opcode + uint64 length
constexpr uint64_t kFooterRecord = kRecordHead + 20;  // summary offsets + CRC

uint32_t crc_of(const std::string& bytes) {
  return static_cast<uint32_t>(
      crc32(0, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())));
}

// One record of a byte string: its opcode and content, advancing `at`.
struct RawRecord {
  uint8_t op;
  std::string content;
};

RawRecord next_record(const std::string& bytes, uint64_t& at, const std::string& where) {
  RecordReader head(bytes.substr(at, kRecordHead), where, "record");
  const uint8_t op = head.u8();
  const uint64_t length = head.u64();
  if (length > bytes.size() - at - kRecordHead)
    fail(where, fmt::format("truncated record (opcode 0x{:02x} at byte {} says {} bytes, {} left)",
                            op, at, length, bytes.size() - at - kRecordHead));
  RawRecord r{op, bytes.substr(at + kRecordHead, length)};
  at += kRecordHead + length;
  return r;
}

Message parse_message(const std::string& content, const std::string& where) {
  RecordReader r(content, where, "message record");
  Message m;
  m.channel_id = r.u16();
  m.sequence = r.u32();
  m.log_time = r.u64();
  m.publish_time = r.u64();
  m.data = content.substr(r.at());
  return m;
}

}  // namespace

Reader::Reader(const std::string& path) : path_(path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "no such MCAP file");
  in_.open(path, std::ios::binary);
  if (!in_) fail(path, "cannot open the MCAP file");
  size_ = std::filesystem::file_size(path, ec);
  const uint64_t smallest = 2 * sizeof kMagic + kRecordHead + kFooterRecord;
  if (size_ >= sizeof kMagic &&
      std::memcmp(read_at(0, sizeof kMagic, "magic").data(), kMagic, sizeof kMagic) != 0)
    fail(path, "not an MCAP file (it does not start with the MCAP magic)");
  if (size_ < smallest)
    fail(path, fmt::format("truncated MCAP file ({} bytes; the smallest is {})", size_, smallest));
  if (std::memcmp(read_at(size_ - sizeof kMagic, sizeof kMagic, "magic").data(), kMagic,
                  sizeof kMagic) != 0)
    fail(path, "truncated MCAP file (no magic at its end: cut short or never closed)");

  const uint64_t footer_at = size_ - sizeof kMagic - kFooterRecord;
  RecordReader footer(read_at(footer_at, kFooterRecord, "footer"), path, "footer");
  if (footer.u8() != static_cast<uint8_t>(Opcode::kFooter) || footer.u64() != 20)
    fail(path, "truncated MCAP file (no footer record before the closing magic)");
  const uint64_t summary_start = footer.u64();
  const uint64_t summary_offset_start = footer.u64();
  const uint32_t summary_crc = footer.u32();

  RecordReader header(read_at(sizeof kMagic, kRecordHead, "header"), path, "header");
  if (header.u8() != static_cast<uint8_t>(Opcode::kHeader))
    fail(path, "malformed MCAP file (no header record after the magic)");
  const uint64_t header_length = header.u64();
  if (header_length > footer_at) fail(path, "malformed MCAP file (header longer than the file)");
  profile_ =
      RecordReader(read_at(sizeof kMagic + kRecordHead, header_length, "header"), path, "header")
          .string();

  if (summary_start != 0) {
    if (summary_start > footer_at || summary_offset_start > footer_at)
      fail(path, "malformed MCAP footer (summary offsets past the footer)");
    read_summary(summary_start, footer_at, summary_crc);
  }
  if (chunk_offsets_.empty()) scan_data_section(summary_start != 0 ? summary_start : footer_at);
  std::stable_sort(
      messages_.begin(), messages_.end(),
      [](const MessageRef& a, const MessageRef& b) { return a.log_time < b.log_time; });
}

std::string Reader::read_at(uint64_t offset, uint64_t n, const std::string& what) {
  if (offset > size_ || n > size_ - offset)
    fail(path_, fmt::format("truncated MCAP file ({} of {} bytes at byte {} are past its end)",
                            what, n, offset));
  std::string bytes(n, '\0');
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(offset));
  in_.read(bytes.data(), static_cast<std::streamsize>(n));
  if (!in_) fail(path_, "cannot read the MCAP file at byte " + std::to_string(offset));
  return bytes;
}

void Reader::add_schema_or_channel(uint8_t op, const std::string& content) {
  if (op == static_cast<uint8_t>(Opcode::kSchema)) {
    RecordReader r(content, path_, "schema record");
    Schema s;
    s.id = r.u16();
    s.name = r.string();
    s.encoding = r.string();
    s.data = r.string();
    if (s.id != 0) schemas_[s.id] = std::move(s);  // id 0 is invalid: ignored, as the spec says
  } else if (op == static_cast<uint8_t>(Opcode::kChannel)) {
    RecordReader r(content, path_, "channel record");
    Channel c;
    c.id = r.u16();
    c.schema_id = r.u16();
    c.topic = r.string();
    c.message_encoding = r.string();
    c.metadata = r.string_map();
    channels_[c.id] = std::move(c);
  }
}

void Reader::read_summary(uint64_t summary_start, uint64_t footer_at, uint32_t crc) {
  // The CRC covers the summary and the footer up to its CRC field.
  const std::string covered =
      read_at(summary_start, footer_at + kRecordHead + 16 - summary_start, "summary");
  if (crc != 0 && crc_of(covered) != crc)
    fail(path_, fmt::format("summary CRC mismatch (footer says {:08x}, the bytes give {:08x}): "
                            "the file is damaged",
                            crc, crc_of(covered)));
  const std::string summary = covered.substr(0, footer_at - summary_start);
  uint64_t at = 0;
  std::vector<std::pair<uint64_t, uint64_t>> index_spans;
  while (at < summary.size()) {
    const RawRecord rec = next_record(summary, at, path_ + " (summary)");
    if (rec.op == static_cast<uint8_t>(Opcode::kSchema) ||
        rec.op == static_cast<uint8_t>(Opcode::kChannel)) {
      add_schema_or_channel(rec.op, rec.content);
    } else if (rec.op == static_cast<uint8_t>(Opcode::kChunkIndex)) {
      RecordReader r(rec.content, path_, "chunk index record");
      r.u64();  // start time
      r.u64();  // end time
      const uint64_t chunk_offset = r.u64();
      const uint64_t chunk_length = r.u64();
      r.skip_block();  // per-channel message index offsets: the span below holds them all
      const uint64_t index_length = r.u64();
      chunk_offsets_.emplace_back(chunk_offset, chunk_length);
      index_spans.emplace_back(chunk_offset + chunk_length, index_length);
    }
  }
  for (size_t k = 0; k < chunk_offsets_.size(); ++k) {
    const std::string indexes =
        read_at(index_spans[k].first, index_spans[k].second, "message index");
    uint64_t i = 0;
    while (i < indexes.size()) {
      const RawRecord rec = next_record(indexes, i, path_ + " (message index)");
      if (rec.op != static_cast<uint8_t>(Opcode::kMessageIndex)) continue;
      RecordReader r(rec.content, path_, "message index record");
      const uint16_t channel = r.u16();
      const uint32_t bytes = r.u32();
      if (bytes % 16 != 0 || bytes > r.left())
        fail(path_, "malformed message index record (its array is not of (time, offset) pairs)");
      for (uint32_t e = 0; e < bytes / 16; ++e) {
        const uint64_t time = r.u64();
        messages_.push_back({channel, time, chunk_offsets_[k].first, r.u64()});
      }
    }
  }
}

void Reader::list_chunk(uint64_t chunk_offset, const std::string& records) {
  uint64_t at = 0;
  while (at < records.size()) {
    const uint64_t record_at = at;
    const RawRecord rec =
        next_record(records, at, path_ + fmt::format(" (chunk at byte {})", chunk_offset));
    if (rec.op == static_cast<uint8_t>(Opcode::kMessage)) {
      RecordReader r(rec.content, path_, "message record");
      const uint16_t channel = r.u16();
      r.u32();
      messages_.push_back({channel, r.u64(), chunk_offset, record_at});
    } else {
      add_schema_or_channel(rec.op, rec.content);
    }
  }
}

void Reader::scan_data_section(uint64_t end) {
  uint64_t at = sizeof kMagic;
  while (at < end) {
    RecordReader head(read_at(at, kRecordHead, "record"), path_, "record");
    const uint8_t op = head.u8();
    const uint64_t length = head.u64();
    if (length > end - at - kRecordHead)
      fail(path_, fmt::format("truncated record (opcode 0x{:02x} at byte {} says {} bytes)", op, at,
                              length));
    if (op == static_cast<uint8_t>(Opcode::kDataEnd)) break;
    if (op == static_cast<uint8_t>(Opcode::kSchema) || op == static_cast<uint8_t>(Opcode::kChannel))
      add_schema_or_channel(op, read_at(at + kRecordHead, length, "record"));
    else if (op == static_cast<uint8_t>(Opcode::kMessage)) {
      RecordReader r(read_at(at + kRecordHead, 14, "message record"), path_, "message record");
      const uint16_t channel = r.u16();
      r.u32();
      messages_.push_back({channel, r.u64(), 0, at});
    } else if (op == static_cast<uint8_t>(Opcode::kChunk)) {
      list_chunk(at, chunk_records(at));
    }
    at += kRecordHead + length;
  }
}

const std::string& Reader::chunk_records(uint64_t chunk_offset) {
  if (cached_chunk_ == chunk_offset) return cached_records_;
  const std::string where = path_ + fmt::format(" (chunk at byte {})", chunk_offset);
  RecordReader head(read_at(chunk_offset, kRecordHead, "chunk"), path_, "chunk");
  if (head.u8() != static_cast<uint8_t>(Opcode::kChunk))
    fail(where, "no chunk record there (the chunk index is wrong)");
  const uint64_t length = head.u64();
  const std::string content = read_at(chunk_offset + kRecordHead, length, "chunk");
  RecordReader r(content, where, "chunk record");
  r.u64();  // start time
  r.u64();  // end time
  const uint64_t uncompressed_size = r.u64();
  const uint32_t crc = r.u32();
  const Compression compression = parse_compression(r.string(), where);
  const uint64_t compressed_size = r.u64();
  if (compressed_size > r.left()) fail(where, "truncated chunk record");
  // No chunk of a real bag comes near this; a damaged size must not make us
  // allocate it.
  constexpr uint64_t kMaxChunk = uint64_t{1} << 30;
  if (uncompressed_size > kMaxChunk)
    fail(where, fmt::format("chunk says it holds {} bytes uncompressed (more than 1 GiB: damaged)",
                            uncompressed_size));
  cached_chunk_.reset();
  cached_records_ =
      decompress(compression, content.substr(r.at(), compressed_size), uncompressed_size, where);
  if (crc != 0 && crc_of(cached_records_) != crc)
    fail(where, fmt::format("CRC mismatch (the chunk says {:08x}, its records give {:08x}): "
                            "the file is damaged",
                            crc, crc_of(cached_records_)));
  cached_chunk_ = chunk_offset;
  return cached_records_;
}

const Channel* Reader::channel(const std::string& topic) const {
  for (const auto& [id, c] : channels_)
    if (c.topic == topic) return &c;
  return nullptr;
}

Message Reader::read(const MessageRef& ref) {
  std::string content;
  if (ref.chunk_offset != 0) {
    const std::string& records = chunk_records(ref.chunk_offset);
    uint64_t at = ref.offset;
    if (at >= records.size())
      fail(path_, fmt::format("message index points past its chunk (offset {})", ref.offset));
    const RawRecord rec = next_record(records, at, path_);
    if (rec.op != static_cast<uint8_t>(Opcode::kMessage))
      fail(path_, fmt::format("message index points at a record of opcode 0x{:02x}", rec.op));
    content = rec.content;
  } else {
    RecordReader head(read_at(ref.offset, kRecordHead, "message"), path_, "message");
    head.u8();
    content = read_at(ref.offset + kRecordHead, head.u64(), "message");
  }
  return parse_message(content, path_);
}

}  // namespace depot::mcap
