#pragma once
// A vocabulary tree of binary ORB words (Galvez-Lopez and Tardos, "Bags of
// Binary Words", 2012, as ORB-SLAM2 uses it): each node holds a 256-bit
// descriptor, its children partition the descriptors beneath it (k-means in
// Hamming space), and the leaves are the words. A descriptor descends from
// the root to the nearest child at every level and lands on one word. Words
// carry inverse document frequency weights learnt from the training images.
//
// Plain data after construction: immutable and safe to share between threads
// (tracking, local mapping and loop closing read one instance).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/data/bow_vector.h"

namespace depot::slam {

using BinaryDescriptor = std::array<uint8_t, 32>;

struct VocabularyNode {
  uint32_t parent = 0;  // the root is its own parent
  uint32_t depth = 0;   // 0 at the root
  BinaryDescriptor descriptor{};
  std::vector<NodeId> children;
  int32_t word = -1;  // word id of a leaf, -1 for inner nodes
  float idf = 0;      // weight of a leaf: log(N images / images holding it)
};

class Vocabulary {
 public:
  Vocabulary() = default;
  // Nodes in breadth-first order (node 0 is the root, each node's children
  // follow their parent); words are numbered in node order. Throws
  // depot::Error when the tree is malformed (`where` names the source).
  Vocabulary(int branching, int levels, std::vector<VocabularyNode> nodes,
             const std::string& where);

  int branching() const { return branching_; }
  int levels() const { return levels_; }
  size_t n_words() const { return word_nodes_.size(); }
  size_t n_nodes() const { return nodes_.size(); }
  const std::vector<VocabularyNode>& nodes() const { return nodes_; }
  bool empty() const { return nodes_.empty(); }

  // The word of one descriptor (32 bytes) and the node it passes at
  // `direct_level` (depth from the root; clamped to the leaf's depth).
  WordId word_of(const uint8_t* descriptor, int direct_level, NodeId* direct_node) const;
  // The bag of words and direct index of an image's descriptors (N x 32
  // CV_8U). The direct index uses nodes at depth `direct_level` (ORB-SLAM2
  // uses the level four above the leaves of its six-level tree: depth 2).
  void transform(const cv::Mat& descriptors, BowVector& bow, FeatureVector& direct,
                 int direct_level = kDirectLevel) const;
  void transform(const cv::Mat& descriptors, BowVector& bow) const;

  static constexpr int kDirectLevel = 2;

 private:
  int branching_ = 0;
  int levels_ = 0;
  std::vector<VocabularyNode> nodes_;
  std::vector<NodeId> word_nodes_;  // word id -> node
};

}  // namespace depot::slam
