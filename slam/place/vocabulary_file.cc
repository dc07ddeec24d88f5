#include "slam/place/vocabulary_file.h"

#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

#include "common/binary_io.h"
#include "common/error.h"
#include "common/staged_file.h"

namespace depot::slam {
namespace {

constexpr char kMagic[8] = {'D', 'E', 'P', 'O', 'T', 'V', 'O', 'C'};
constexpr uint32_t kVersion = 1;
constexpr size_t kHeaderBytes = 8 + 5 * 4;
constexpr size_t kNodeBytes = 4 * 4 + 32;

std::string serialise(const Vocabulary& v) {
  BinaryWriter out;
  out.bytes().reserve(kHeaderBytes + v.n_nodes() * kNodeBytes + 4);
  out.put_bytes(kMagic, sizeof(kMagic));
  out.put<uint32_t>(kVersion);
  out.put<uint32_t>(32);
  out.put<uint32_t>(static_cast<uint32_t>(v.branching()));
  out.put<uint32_t>(static_cast<uint32_t>(v.levels()));
  out.put<uint32_t>(static_cast<uint32_t>(v.n_nodes()));
  for (const VocabularyNode& n : v.nodes()) {
    out.put<uint32_t>(n.parent);
    out.put<uint32_t>(n.depth);
    out.put<int32_t>(n.word);
    out.put<float>(n.idf);
    out.put_bytes(n.descriptor.data(), n.descriptor.size());
  }
  out.put_checksum();
  return std::move(out.bytes());
}

}  // namespace

void save_vocabulary(const Vocabulary& vocabulary, const std::string& path) {
  if (vocabulary.empty()) fail(path, "cannot save an empty vocabulary");
  StagedFile file(path);
  const std::string bytes = serialise(vocabulary);
  file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

Vocabulary load_vocabulary(const std::string& path) {
  const std::string bytes = read_binary_file(path, "vocabulary");
  if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
    fail(path,
         "not a depot vocabulary (no DEPOTVOC header; train one with `depot vocabulary train`)");
  if (bytes.size() < kHeaderBytes)
    fail(path, "truncated vocabulary: " + std::to_string(bytes.size()) +
                   " bytes, header alone is " + std::to_string(kHeaderBytes));
  BinaryReader in_bytes(bytes, path, "vocabulary", sizeof(kMagic));
  const auto version = in_bytes.take<uint32_t>();
  const auto descriptor_bytes = in_bytes.take<uint32_t>();
  const auto branching = in_bytes.take<uint32_t>();
  const auto levels = in_bytes.take<uint32_t>();
  const auto n_nodes = in_bytes.take<uint32_t>();
  if (version != kVersion)
    fail(path, "vocabulary format version " + std::to_string(version) + ", this build reads " +
                   std::to_string(kVersion));
  if (descriptor_bytes != 32)
    fail(path, "vocabulary of " + std::to_string(descriptor_bytes) +
                   "-byte descriptors; depot's ORB descriptors have 32 bytes");
  const uint64_t expected = kHeaderBytes + static_cast<uint64_t>(n_nodes) * kNodeBytes + 4;
  if (bytes.size() < expected)
    fail(path, "truncated vocabulary: " + std::to_string(bytes.size()) + " bytes of " +
                   std::to_string(expected));
  if (bytes.size() > expected)
    fail(path, "vocabulary has " + std::to_string(bytes.size() - expected) +
                   " unexpected bytes after its end");
  if (BinaryReader(bytes, path, "vocabulary", expected - 4).take<uint32_t>() !=
      crc32_of(bytes, expected - 4))
    fail(path, "corrupt vocabulary (checksum mismatch)");
  std::vector<VocabularyNode> nodes(n_nodes);
  for (VocabularyNode& n : nodes) {
    n.parent = in_bytes.take<uint32_t>();
    n.depth = in_bytes.take<uint32_t>();
    n.word = in_bytes.take<int32_t>();
    n.idf = in_bytes.take<float>();
    in_bytes.take_bytes(n.descriptor.data(), 32);
  }
  return Vocabulary(static_cast<int>(branching), static_cast<int>(levels), std::move(nodes), path);
}

std::shared_ptr<const Vocabulary> load_vocabulary_shared(const std::string& path) {
  static std::mutex mutex;
  static std::map<std::string, std::pair<std::string, std::weak_ptr<const Vocabulary>>> cache;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  const auto time = std::filesystem::last_write_time(path, ec);
  const std::string stamp =
      ec ? "" : std::to_string(size) + "@" + std::to_string(time.time_since_epoch().count());
  std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find(path);
  if (!stamp.empty() && it != cache.end() && it->second.first == stamp)
    if (auto held = it->second.second.lock()) return held;
  auto loaded = std::make_shared<const Vocabulary>(load_vocabulary(path));
  cache[path] = {stamp, loaded};
  return loaded;
}

uint32_t vocabulary_identity(const Vocabulary& vocabulary) {
  const std::string bytes = serialise(vocabulary);
  return crc32_of(bytes, bytes.size() - 4);
}

std::string format_vocabulary_identity(uint32_t identity) {
  return fmt::format("{:08x}", identity);
}

std::string default_vocabulary_path() {
  if (const char* env = std::getenv("DEPOT_VOCABULARY"); env && *env) return env;
  return DEPOT_DEFAULT_VOCABULARY;
}

}  // namespace depot::slam
