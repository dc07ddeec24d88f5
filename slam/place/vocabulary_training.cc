#include "slam/place/vocabulary_training.h"

#include <cmath>
#include <cstring>
#include <deque>
#include <random>
#include <set>

#include "common/error.h"
#include "slam/feature/descriptor_distance.h"

namespace depot::slam {
namespace {

const std::string kWhere = "vocabulary training";

BinaryDescriptor majority(const std::vector<BinaryDescriptor>& all,
                          const std::vector<size_t>& members) {
  std::array<int, 256> ones{};
  for (size_t m : members) {
    const BinaryDescriptor& d = all[m];
    for (int byte = 0; byte < 32; ++byte)
      for (int bit = 0; bit < 8; ++bit) ones[byte * 8 + bit] += (d[byte] >> (7 - bit)) & 1;
  }
  BinaryDescriptor out{};
  const int n = static_cast<int>(members.size());
  for (int i = 0; i < 256; ++i)
    if (2 * ones[i] >= n) out[i / 8] |= static_cast<uint8_t>(1 << (7 - i % 8));
  return out;
}

int distance(const BinaryDescriptor& a, const BinaryDescriptor& b) {
  return descriptor_distance(a.data(), b.data());
}

// k-means++ seeds: the first uniformly, each next one with probability
// proportional to its squared distance to the nearest seed so far.
std::vector<BinaryDescriptor> seed_centres(const std::vector<BinaryDescriptor>& all,
                                           const std::vector<size_t>& members, int k,
                                           std::mt19937_64& rng) {
  std::vector<BinaryDescriptor> centres;
  std::uniform_int_distribution<size_t> first(0, members.size() - 1);
  centres.push_back(all[members[first(rng)]]);
  std::vector<double> nearest(members.size());
  for (size_t i = 0; i < members.size(); ++i) nearest[i] = distance(all[members[i]], centres[0]);
  while (static_cast<int>(centres.size()) < k) {
    double total = 0;
    for (double d : nearest) total += d * d;
    if (total <= 0) break;  // every member equals a seed
    std::uniform_real_distribution<double> pick(0, total);
    double target = pick(rng);
    size_t chosen = members.size() - 1;
    for (size_t i = 0; i < members.size(); ++i) {
      target -= nearest[i] * nearest[i];
      if (target <= 0 && nearest[i] > 0) {
        chosen = i;
        break;
      }
    }
    centres.push_back(all[members[chosen]]);
    for (size_t i = 0; i < members.size(); ++i)
      nearest[i] = std::min<double>(nearest[i], distance(all[members[i]], centres.back()));
  }
  return centres;
}

// Clusters `members` into at most k groups; empty groups are dropped.
std::vector<std::pair<BinaryDescriptor, std::vector<size_t>>> cluster(
    const std::vector<BinaryDescriptor>& all, const std::vector<size_t>& members, int k,
    int max_iterations, std::mt19937_64& rng) {
  std::vector<std::pair<BinaryDescriptor, std::vector<size_t>>> groups;
  if (static_cast<int>(members.size()) <= k) {
    // Too few to cluster: each distinct descriptor is a group (DBoW2).
    for (size_t m : members) {
      bool merged = false;
      for (auto& g : groups)
        if (g.first == all[m]) g.second.push_back(m), merged = true;
      if (!merged) groups.push_back({all[m], {m}});
    }
    return groups;
  }
  std::vector<BinaryDescriptor> centres = seed_centres(all, members, k, rng);
  std::vector<int> assignment(members.size(), -1);
  for (int round = 0; round < max_iterations; ++round) {
    bool changed = false;
    for (size_t i = 0; i < members.size(); ++i) {
      int best = 257, best_c = 0;
      for (size_t c = 0; c < centres.size(); ++c) {
        const int d = distance(all[members[i]], centres[c]);
        if (d < best) best = d, best_c = static_cast<int>(c);
      }
      if (assignment[i] != best_c) assignment[i] = best_c, changed = true;
    }
    if (!changed) break;
    std::vector<std::vector<size_t>> parts(centres.size());
    for (size_t i = 0; i < members.size(); ++i) parts[assignment[i]].push_back(members[i]);
    for (size_t c = 0; c < centres.size(); ++c)
      if (!parts[c].empty()) centres[c] = majority(all, parts[c]);
  }
  std::vector<std::vector<size_t>> parts(centres.size());
  for (size_t i = 0; i < members.size(); ++i) parts[assignment[i]].push_back(members[i]);
  for (size_t c = 0; c < centres.size(); ++c)
    if (!parts[c].empty()) groups.push_back({centres[c], std::move(parts[c])});
  return groups;
}

}  // namespace

Vocabulary train_vocabulary(const std::vector<cv::Mat>& images,
                            const VocabularyTrainingParams& params,
                            const std::function<void(double)>& progress) {
  if (params.branching < 2 || params.branching > 64)
    fail(kWhere, "branching must be in [2, 64], got " + std::to_string(params.branching));
  if (params.levels < 1 || params.levels > 8)
    fail(kWhere, "levels must be in [1, 8], got " + std::to_string(params.levels));
  if (params.max_iterations < 1) fail(kWhere, "max_iterations must be >= 1");
  std::vector<BinaryDescriptor> all;
  for (size_t img = 0; img < images.size(); ++img) {
    const cv::Mat& d = images[img];
    if (d.empty()) continue;
    if (d.type() != CV_8U || d.cols != kDescriptorBytes)
      fail(kWhere, "image " + std::to_string(img) + " has descriptors that are not N x 32 bytes");
    for (int r = 0; r < d.rows; ++r) {
      BinaryDescriptor b;
      std::memcpy(b.data(), d.ptr<uint8_t>(r), b.size());
      all.push_back(b);
    }
  }
  if (all.size() < static_cast<size_t>(params.branching))
    fail(kWhere, "too few descriptors to train on (" + std::to_string(all.size()) + ")");

  // Breadth-first: a node's id is its place in `nodes`, children follow.
  std::vector<VocabularyNode> nodes(1);
  std::vector<std::vector<size_t>> members(1);
  members[0].resize(all.size());
  for (size_t i = 0; i < all.size(); ++i) members[0][i] = i;
  size_t placed = 0;
  for (size_t id = 0; id < nodes.size(); ++id) {
    std::vector<size_t> mine = std::move(members[id]);
    const bool leaf = static_cast<int>(nodes[id].depth) == params.levels || mine.size() <= 1;
    if (!leaf) {
      // A per-node stream keeps the result independent of the visiting order.
      std::mt19937_64 rng(params.seed * 0x9E3779B97F4A7C15ull + id);
      auto groups = cluster(all, mine, params.branching, params.max_iterations, rng);
      if (groups.size() > 1) {
        for (auto& [centre, part] : groups) {
          VocabularyNode child;
          child.parent = static_cast<uint32_t>(id);
          child.depth = nodes[id].depth + 1;
          child.descriptor = centre;
          nodes.push_back(child);
          members.push_back(std::move(part));
        }
        continue;
      }
    }
    placed += mine.size();
    nodes[id].word = 0;  // numbered below
    if (progress) progress(static_cast<double>(placed) / all.size());
  }
  int32_t next_word = 0;
  for (VocabularyNode& n : nodes)
    if (n.word >= 0) n.word = next_word++;

  // idf = log(N / n_w), N the images with descriptors, n_w those holding w.
  Vocabulary tree(params.branching, params.levels, nodes, kWhere);
  std::vector<int> images_with(tree.n_words(), 0);
  int n_images = 0;
  for (const cv::Mat& d : images) {
    if (d.empty()) continue;
    ++n_images;
    std::set<WordId> words;
    for (int r = 0; r < d.rows; ++r) words.insert(tree.word_of(d.ptr<uint8_t>(r), 0, nullptr));
    for (WordId w : words) images_with[w]++;
  }
  for (VocabularyNode& n : nodes)
    if (n.word >= 0) {
      const int holders = std::max(1, images_with[n.word]);
      n.idf = static_cast<float>(std::log(static_cast<double>(n_images) / holders));
    }
  return Vocabulary(params.branching, params.levels, std::move(nodes), kWhere);
}

}  // namespace depot::slam
