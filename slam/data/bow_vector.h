#pragma once
// What a vocabulary makes of one image's descriptors: a bag of words (the
// image's words with their TF-IDF weights, L1-normalised) and a direct index
// (the vocabulary node at a fixed tree level above each keypoint's word, with
// the keypoints under it), which guides descriptor matching between two
// images to keypoints that fall under the same node.
#include <cstdint>
#include <map>
#include <vector>

namespace depot::slam {

using WordId = uint32_t;
using NodeId = uint32_t;

// Sorted by word, so two vectors are compared in one merge pass.
using BowVector = std::map<WordId, double>;

// Node -> indices of the keypoints whose descriptors pass through it.
using FeatureVector = std::map<NodeId, std::vector<size_t>>;

// Similarity of two L1-normalised bags of words in [0, 1] (DBoW2's L1
// score): 1 - |a - b|_1 / 2, summed over the words both hold.
double bow_similarity(const BowVector& a, const BowVector& b);

}  // namespace depot::slam
