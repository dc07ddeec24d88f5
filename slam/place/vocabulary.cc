#include "slam/place/vocabulary.h"

#include <cmath>

#include "common/error.h"
#include "slam/feature/descriptor_distance.h"

namespace depot::slam {

double bow_similarity(const BowVector& a, const BowVector& b) {
  // For L1-normalised vectors |a - b|_1 = 2 - sum over shared words of
  // (|a_i| + |b_i| - |a_i - b_i|); only shared words need visiting.
  double shared = 0;
  auto ia = a.begin();
  auto ib = b.begin();
  while (ia != a.end() && ib != b.end()) {
    if (ia->first < ib->first) {
      ia = a.lower_bound(ib->first);
    } else if (ib->first < ia->first) {
      ib = b.lower_bound(ia->first);
    } else {
      shared += std::abs(ia->second) + std::abs(ib->second) - std::abs(ia->second - ib->second);
      ++ia, ++ib;
    }
  }
  return 0.5 * shared;
}

Vocabulary::Vocabulary(int branching, int levels, std::vector<VocabularyNode> nodes,
                       const std::string& where)
    : branching_(branching), levels_(levels), nodes_(std::move(nodes)) {
  if (branching_ < 2 || levels_ < 1) fail(where, "branching must be >= 2 and levels >= 1");
  if (nodes_.empty()) fail(where, "the vocabulary has no nodes");
  for (size_t i = 0; i < nodes_.size(); ++i) {
    VocabularyNode& n = nodes_[i];
    if (i > 0 && (n.parent >= i || nodes_[n.parent].depth + 1 != n.depth))
      fail(where, "node " + std::to_string(i) + " has a bad parent (not breadth-first)");
    if (static_cast<int>(n.depth) > levels_)
      fail(where, "node " + std::to_string(i) + " is deeper than the tree's levels");
    n.children.clear();
  }
  for (size_t i = 1; i < nodes_.size(); ++i)
    nodes_[nodes_[i].parent].children.push_back(static_cast<NodeId>(i));
  for (size_t i = 0; i < nodes_.size(); ++i) {
    VocabularyNode& n = nodes_[i];
    if (static_cast<int>(n.children.size()) > branching_)
      fail(where, "node " + std::to_string(i) + " has more children than the branching factor");
    const bool leaf = n.children.empty();
    if (leaf != (n.word >= 0))
      fail(where, "node " + std::to_string(i) +
                      (leaf ? " is a leaf without a word" : " is an inner node with a word"));
    if (leaf) {
      if (n.word != static_cast<int32_t>(word_nodes_.size()))
        fail(where, "words are not numbered in node order at node " + std::to_string(i));
      if (!std::isfinite(n.idf) || n.idf < 0)
        fail(where, "word " + std::to_string(n.word) + " has a bad weight");
      word_nodes_.push_back(static_cast<NodeId>(i));
    }
  }
  if (nodes_.size() == 1) fail(where, "the vocabulary has no words below its root");
}

WordId Vocabulary::word_of(const uint8_t* descriptor, int direct_level, NodeId* direct_node) const {
  NodeId id = 0;
  if (direct_node) *direct_node = 0;
  while (!nodes_[id].children.empty()) {
    int best = 257;
    NodeId best_id = nodes_[id].children.front();
    for (NodeId c : nodes_[id].children) {
      const int d = descriptor_distance(descriptor, nodes_[c].descriptor.data());
      if (d < best) best = d, best_id = c;
    }
    id = best_id;
    if (direct_node && static_cast<int>(nodes_[id].depth) <= direct_level) *direct_node = id;
  }
  return static_cast<WordId>(nodes_[id].word);
}

void Vocabulary::transform(const cv::Mat& descriptors, BowVector& bow, FeatureVector& direct,
                           int direct_level) const {
  bow.clear();
  direct.clear();
  if (empty() || descriptors.empty()) return;
  double total = 0;
  for (int i = 0; i < descriptors.rows; ++i) {
    NodeId node = 0;
    const WordId w = word_of(descriptors.ptr<uint8_t>(i), direct_level, &node);
    const double idf = nodes_[word_nodes_[w]].idf;
    if (idf > 0) {
      bow[w] += idf;
      total += idf;
    }
    direct[node].push_back(static_cast<size_t>(i));
  }
  if (total > 0)
    for (auto& [w, v] : bow) v /= total;
}

void Vocabulary::transform(const cv::Mat& descriptors, BowVector& bow) const {
  FeatureVector unused;
  transform(descriptors, bow, unused, 0);
}

}  // namespace depot::slam
