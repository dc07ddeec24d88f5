// The MCAP writer and reader on files of their own: round trips through each
// compression, the index and the linear paths, and every damage the reader
// must name (truncation, CRCs, unknown compression, not MCAP at all).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/binary_io.h"
#include "common/testing/error_of.h"
#include "common/testing/temp_path.h"
#include "dataset/mcap/mcap_reader.h"
#include "dataset/mcap/mcap_writer.h"

namespace depot::mcap {
namespace {

using ::testing::HasSubstr;

// 40 messages on two channels, some larger than a chunk, so a file has
// several chunks and messages that straddle nothing.
std::string write_sample(Compression compression, size_t chunk_size = 4096) {
  const std::string path = testkit::temp_path("sample") + ".mcap";
  Writer w(path, {compression, chunk_size});
  const uint16_t s = w.add_schema("test/msg/Blob", "ros2msg", "uint8[] data\n");
  const uint16_t a = w.add_channel(s, "/a", "cdr", {{"k", "v"}});
  const uint16_t b = w.add_channel(s, "/b", "cdr");
  for (int i = 0; i < 20; ++i) {
    w.write(a, 1000u + 10u * i, 1000u + 10u * i, std::string(100 + 300 * i, char('a' + i)));
    w.write(b, 1005u + 10u * i, 1005u + 10u * i, "b" + std::to_string(i));
  }
  w.close();
  EXPECT_EQ(w.totals().messages, 40u);
  EXPECT_GT(w.totals().chunks, 3u);
  EXPECT_EQ(w.totals().file_bytes, std::filesystem::file_size(path));
  return path;
}

void expect_sample(const std::string& path) {
  Reader r(path);
  EXPECT_EQ(r.profile(), "ros2");
  ASSERT_EQ(r.messages().size(), 40u);
  ASSERT_NE(r.channel("/a"), nullptr);
  EXPECT_EQ(r.channel("/a")->metadata.at(0).second, "v");
  EXPECT_EQ(r.schemas().at(r.channel("/b")->schema_id).name, "test/msg/Blob");
  for (size_t k = 0; k < 40; ++k) {
    const Message m = r.read(r.messages()[k]);
    const int i = static_cast<int>(k / 2);
    if (k % 2 == 0) {
      EXPECT_EQ(m.data, std::string(100 + 300 * i, char('a' + i)));
      EXPECT_EQ(m.log_time, 1000u + 10u * i);
    } else {
      EXPECT_EQ(m.data, "b" + std::to_string(i));
    }
    EXPECT_EQ(m.sequence, static_cast<uint32_t>(i));
  }
}

std::string bytes_of(const std::string& path) {
  return read_binary_file(path, "MCAP");
}
void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

TEST(Mcap, ZstdLz4AndPlainChunksRoundTripThroughTheIndexes) {
  for (Compression c : {Compression::kZstd, Compression::kLz4, Compression::kNone}) {
    SCOPED_TRACE(compression_name(c));
    expect_sample(write_sample(c));
  }
}

TEST(Mcap, AFileWithoutSummaryIsReadByOnePassOverItsData) {
  // Cut the summary off: footer offsets zero, as a streamed writer leaves it.
  const std::string path = write_sample(Compression::kZstd);
  std::string bytes = bytes_of(path);
  uint64_t summary_start;
  std::memcpy(&summary_start, bytes.data() + bytes.size() - 8 - 20, 8);
  std::string footer(1, '\x02');
  const uint64_t length = 20, zero = 0;
  footer.append(reinterpret_cast<const char*>(&length), 8);
  footer.append(reinterpret_cast<const char*>(&zero), 8);
  footer.append(reinterpret_cast<const char*>(&zero), 8);
  footer.append(4, '\0');
  const std::string cut = bytes.substr(0, summary_start) + footer + bytes.substr(bytes.size() - 8);
  write_bytes(path, cut);
  expect_sample(path);
}

TEST(Mcap, EveryDamageIsOneErrorNamingTheFile) {
  const std::string good = write_sample(Compression::kZstd);
  const std::string bytes = bytes_of(good);
  const std::string bad = testkit::temp_path("bad") + ".mcap";

  write_bytes(bad, bytes.substr(0, bytes.size() / 2));
  EXPECT_THAT(error_of([&] { Reader r(bad); }), HasSubstr(bad + ": truncated MCAP file"));

  write_bytes(bad, "PNG is not MCAP at all, but long enough to have a footer and magic here.");
  EXPECT_THAT(error_of([&] { Reader r(bad); }), HasSubstr("not an MCAP file"));

  EXPECT_THAT(error_of([&] { Reader r(bad + ".none"); }), HasSubstr("no such MCAP file"));

  // One flipped byte inside the summary: its CRC names it.
  std::string flipped = bytes;
  flipped[flipped.size() - 8 - 29 - 40] ^= 0x5a;
  write_bytes(bad, flipped);
  EXPECT_THAT(error_of([&] { Reader r(bad); }), HasSubstr("summary CRC mismatch"));

  // One flipped byte inside the first chunk's compressed records (no
  // compression, so the bytes decompress and the CRC must catch it).
  const std::string plain = write_sample(Compression::kNone);
  std::string damaged = bytes_of(plain);
  const size_t chunk = damaged.find(std::string(50, 'b'));  // message 1's data ("bbb...")
  ASSERT_NE(chunk, std::string::npos);
  damaged[chunk] = 'X';
  write_bytes(bad, damaged);
  Reader r(bad);
  EXPECT_THAT(error_of([&] {
                for (const MessageRef& m : r.messages()) r.read(m);
              }),
              HasSubstr("CRC mismatch (the chunk says"));
}

TEST(Mcap, AnUnknownChunkCompressionIsNamed) {
  const std::string path = write_sample(Compression::kLz4);
  std::string bytes = bytes_of(path);
  // The first chunk record's compression name (its index in the summary keeps
  // "lz4", so the summary CRC still holds).
  const size_t at = bytes.find(std::string("\x03\0\0\0lz4", 7));
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at + 4, 3, "lzx");
  write_bytes(path, bytes);
  Reader r(path);
  EXPECT_THAT(error_of([&] { r.read(r.messages().front()); }),
              HasSubstr(path + " (chunk at byte "));
  EXPECT_THAT(error_of([&] { r.read(r.messages().front()); }),
              HasSubstr("unknown chunk compression 'lzx' (known: zstd, lz4, none)"));
}

TEST(Mcap, AWriterThatIsNotClosedLeavesNoFile) {
  const std::string path = testkit::temp_path("unclosed") + ".mcap";
  {
    Writer w(path);
    const uint16_t s = w.add_schema("x", "ros2msg", "");
    w.write(w.add_channel(s, "/x", "cdr"), 1, 1, "data");
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  for (const auto& e :
       std::filesystem::directory_iterator(std::filesystem::path(path).parent_path()))
    EXPECT_THAT(e.path().filename().string(), ::testing::Not(HasSubstr("unclosed")));
}

TEST(Mcap, TimesComeBackAsTheDatasetsDecimalText) {
  for (double t : {1403636579.763555, 0.000001, 1305031102.175304, 12.5}) {
    EXPECT_EQ(seconds_of(nanoseconds_of(t)), t);
  }
}

}  // namespace
}  // namespace depot::mcap
