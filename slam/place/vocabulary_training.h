#pragma once
// Learning a vocabulary tree from training images' ORB descriptors:
// hierarchical k-means with k-means++ seeding in Hamming space, centres by
// bitwise majority (DBoW2's way for binary descriptors), then inverse
// document frequency weights from how many images hold each word.
// Deterministic: the same descriptors, parameters and seed give the same tree.
#include <cstdint>
#include <functional>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/place/vocabulary.h"

namespace depot::slam {

struct VocabularyTrainingParams {
  int branching = 10;       // k: children per node
  int levels = 5;           // depth of the leaves: up to k^levels words
  int max_iterations = 15;  // k-means rounds per node (stops earlier when stable)
  uint64_t seed = 1;
};

// `images`: one N x 32 CV_8U descriptor matrix per training image. `progress`
// (may be empty) gets the share of descriptors that reached a leaf, in [0, 1].
// Throws depot::Error for bad parameters or no descriptors.
Vocabulary train_vocabulary(const std::vector<cv::Mat>& images,
                            const VocabularyTrainingParams& params,
                            const std::function<void(double)>& progress = {});

}  // namespace depot::slam
