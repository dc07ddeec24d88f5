#include "slam/place/vocabulary_file.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

#include <zlib.h>

#include "common/error.h"
#include "common/staged_file.h"

namespace depot::slam {
namespace {

constexpr char kMagic[8] = {'D', 'E', 'P', 'O', 'T', 'V', 'O', 'C'};
constexpr uint32_t kVersion = 1;
constexpr size_t kHeaderBytes = 8 + 5 * 4;
constexpr size_t kNodeBytes = 4 * 4 + 32;

template <typename T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

template <typename T>
T take(const std::string& in, size_t& at) {
  T value;
  std::memcpy(&value, in.data() + at, sizeof(T));
  at += sizeof(T);
  return value;
}

uint32_t crc_of(const std::string& bytes, size_t n) {
  return static_cast<uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(n)));
}

std::string serialise(const Vocabulary& v) {
  std::string out;
  out.reserve(kHeaderBytes + v.n_nodes() * kNodeBytes + 4);
  out.append(kMagic, sizeof(kMagic));
  put<uint32_t>(out, kVersion);
  put<uint32_t>(out, 32);
  put<uint32_t>(out, static_cast<uint32_t>(v.branching()));
  put<uint32_t>(out, static_cast<uint32_t>(v.levels()));
  put<uint32_t>(out, static_cast<uint32_t>(v.n_nodes()));
  for (const VocabularyNode& n : v.nodes()) {
    put<uint32_t>(out, n.parent);
    put<uint32_t>(out, n.depth);
    put<int32_t>(out, n.word);
    put<float>(out, n.idf);
    out.append(reinterpret_cast<const char*>(n.descriptor.data()), n.descriptor.size());
  }
  put<uint32_t>(out, crc_of(out, out.size()));
  return out;
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
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path, "no such vocabulary file");
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a folder, not a vocabulary file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the vocabulary file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string bytes = buffer.str();
  if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
    fail(path,
         "not a depot vocabulary (no DEPOTVOC header; train one with `depot vocabulary train`)");
  if (bytes.size() < kHeaderBytes)
    fail(path, "truncated vocabulary: " + std::to_string(bytes.size()) +
                   " bytes, header alone is " + std::to_string(kHeaderBytes));
  size_t at = sizeof(kMagic);
  const auto version = take<uint32_t>(bytes, at);
  const auto descriptor_bytes = take<uint32_t>(bytes, at);
  const auto branching = take<uint32_t>(bytes, at);
  const auto levels = take<uint32_t>(bytes, at);
  const auto n_nodes = take<uint32_t>(bytes, at);
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
  size_t crc_at = expected - 4;
  if (take<uint32_t>(bytes, crc_at) != crc_of(bytes, expected - 4))
    fail(path, "corrupt vocabulary (checksum mismatch)");
  std::vector<VocabularyNode> nodes(n_nodes);
  for (VocabularyNode& n : nodes) {
    n.parent = take<uint32_t>(bytes, at);
    n.depth = take<uint32_t>(bytes, at);
    n.word = take<int32_t>(bytes, at);
    n.idf = take<float>(bytes, at);
    std::memcpy(n.descriptor.data(), bytes.data() + at, 32);
    at += 32;
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
  return crc_of(bytes, bytes.size() - 4);
}

std::string default_vocabulary_path() {
  if (const char* env = std::getenv("DEPOT_VOCABULARY"); env && *env) return env;
  return DEPOT_DEFAULT_VOCABULARY;
}

}  // namespace depot::slam
