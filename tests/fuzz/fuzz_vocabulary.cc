// libFuzzer target: vocabulary files (slam/place/vocabulary_file.h), then
// one descriptor through the loaded tree.
//
// A vocabulary ends in a CRC-32 of the bytes before it: the target writes
// the right one over the input's last four bytes, so the fuzzer reaches the
// tree. Seeds come from the writer: DEPOT_FUZZ_WRITE_SEED=FILE
// fuzz_vocabulary writes a small vocabulary and exits.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "common/binary_io.h"
#include "slam/place/vocabulary_file.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

using namespace depot::slam;

// Branching 2, levels 2: a root, two inner nodes, four words.
void write_seed(const std::string& path) {
  std::vector<VocabularyNode> nodes(7);
  for (uint32_t i = 1; i < 7; ++i) {
    nodes[i].parent = i < 3 ? 0 : 1 + (i - 3) / 2;
    nodes[i].depth = i < 3 ? 1 : 2;
    for (size_t b = 0; b < nodes[i].descriptor.size(); ++b)
      nodes[i].descriptor[b] = static_cast<uint8_t>(i * 29 + b);
    if (i >= 3) {
      nodes[i].word = static_cast<int32_t>(i - 3);
      nodes[i].idf = 0.5f * static_cast<float>(i);
    }
  }
  save_vocabulary(Vocabulary(2, 2, std::move(nodes), path), path);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  depot::fuzz::write_seed_if_asked(write_seed);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes = depot::fuzz::with_valid_checksum(data, size);
  const std::string path = depot::fuzz::write_input(
      "vocabulary.voc", reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  depot::fuzz::expect_clean(path, [&] {
    const Vocabulary vocabulary = load_vocabulary(path);
    uint8_t descriptor[32] = {};
    vocabulary.word_of(descriptor, 1, nullptr);
  });
  return 0;
}
