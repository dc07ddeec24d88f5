// The vocabulary on real photographs: training is reproducible, an image is
// most similar to a warped view of itself, and the file format rejects bad
// files with one clear error.
#include "slam/place/vocabulary.h"

#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "common/testing/scratch_folder.h"
#include "slam/feature/orb_extractor.h"
#include "slam/place/vocabulary_file.h"
#include "slam/place/vocabulary_training.h"

namespace depot::slam {
namespace {

namespace fs = std::filesystem;

const std::string kPhotos = std::string(DEPOT_SHARED_DATA) + "/photos";

std::vector<cv::Mat> photos() {
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(kPhotos))
    if (e.path().extension() == ".jpg") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  std::vector<cv::Mat> out;
  for (const std::string& f : files) {
    cv::Mat gray = cv::imread(f, cv::IMREAD_GRAYSCALE), small;
    cv::resize(gray, small, cv::Size(640, 480));
    out.push_back(small);
  }
  return out;
}

cv::Mat descriptors_of(const cv::Mat& gray) {
  OrbExtractor extractor(OrbParams{});
  std::vector<cv::KeyPoint> kps;
  cv::Mat d;
  extractor.extract(gray, cv::Mat(), kps, d);
  return d;
}

// The photo seen from a little to the side: rotated 8 deg, scaled 1.1.
cv::Mat warped(const cv::Mat& gray) {
  cv::Mat out;
  cv::warpAffine(gray, out, cv::getRotationMatrix2D({320, 240}, 8, 1.1), gray.size());
  return out;
}

struct Trained {
  std::vector<cv::Mat> images;
  std::vector<cv::Mat> descriptors;
  Vocabulary vocabulary;
};

const Trained& trained() {
  static const Trained t = [] {
    Trained t;
    t.images = photos();
    for (const cv::Mat& im : t.images) t.descriptors.push_back(descriptors_of(im));
    t.vocabulary = train_vocabulary(t.descriptors, {6, 4, 10, 1});
    return t;
  }();
  return t;
}

TEST(Vocabulary, TrainingIsReproducibleAndTheSeedMatters) {
  const Trained& t = trained();
  ASSERT_GE(t.images.size(), 5u);
  EXPECT_GT(t.vocabulary.n_words(), 200u);
  const Vocabulary again = train_vocabulary(t.descriptors, {6, 4, 10, 1});
  EXPECT_EQ(vocabulary_identity(again), vocabulary_identity(t.vocabulary));
  const Vocabulary other_seed = train_vocabulary(t.descriptors, {6, 4, 10, 2});
  EXPECT_NE(vocabulary_identity(other_seed), vocabulary_identity(t.vocabulary));
}

TEST(Vocabulary, DescriptorsLandOnTheirNearestLeafAndBowIsNormalised) {
  const Trained& t = trained();
  BowVector bow;
  FeatureVector direct;
  t.vocabulary.transform(t.descriptors[0], bow, direct);
  double sum = 0;
  for (const auto& [w, v] : bow) sum += v;
  EXPECT_NEAR(sum, 1.0, 1e-9);
  size_t indexed = 0;
  for (const auto& [node, idx] : direct) {
    EXPECT_EQ(static_cast<int>(t.vocabulary.nodes()[node].depth), Vocabulary::kDirectLevel);
    indexed += idx.size();
  }
  EXPECT_EQ(indexed, static_cast<size_t>(t.descriptors[0].rows));
  EXPECT_NEAR(bow_similarity(bow, bow), 1.0, 1e-9);
}

TEST(Vocabulary, AWarpedViewIsMostSimilarToItsOwnPhoto) {
  const Trained& t = trained();
  for (size_t query = 0; query < t.images.size(); ++query) {
    BowVector q;
    t.vocabulary.transform(descriptors_of(warped(t.images[query])), q);
    size_t best = 0;
    double best_score = -1;
    for (size_t i = 0; i < t.images.size(); ++i) {
      BowVector b;
      t.vocabulary.transform(t.descriptors[i], b);
      const double s = bow_similarity(q, b);
      if (s > best_score) best_score = s, best = i;
    }
    EXPECT_EQ(best, query) << "photo " << query;
  }
}

TEST(VocabularyFile, RoundTripKeepsTheIdentity) {
  const testkit::ScratchFolder scratch("voc_test");
  const std::string path = scratch.file("roundtrip.voc");
  save_vocabulary(trained().vocabulary, path);
  const Vocabulary loaded = load_vocabulary(path);
  EXPECT_EQ(vocabulary_identity(loaded), vocabulary_identity(trained().vocabulary));
  EXPECT_EQ(loaded.n_words(), trained().vocabulary.n_words());
}

std::string error_of(const std::string& path) {
  try {
    load_vocabulary(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(VocabularyFile, BadFilesFailWithOneClearLine) {
  const testkit::ScratchFolder scratch("voc_test");
  const std::string good = scratch.file("good.voc");
  save_vocabulary(trained().vocabulary, good);
  std::ifstream in(good, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

  auto write = [](const std::string& path, const std::string& content) {
    std::ofstream(path, std::ios::binary) << content;
  };
  const std::string missing = scratch.file("missing.voc");
  EXPECT_THAT(error_of(missing), ::testing::HasSubstr("no such vocabulary file"));

  const std::string truncated = scratch.file("truncated.voc");
  write(truncated, bytes.substr(0, bytes.size() / 2));
  EXPECT_THAT(error_of(truncated), ::testing::HasSubstr("truncated")) << error_of(truncated);

  const std::string corrupt = scratch.file("corrupt.voc");
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  write(corrupt, flipped);
  EXPECT_THAT(error_of(corrupt), ::testing::HasSubstr("checksum")) << error_of(corrupt);

  const std::string wide = scratch.file("wide.voc");
  std::string other_size = bytes;
  other_size[12] = 64;  // the descriptor-bytes field
  write(wide, other_size);
  EXPECT_THAT(error_of(wide), ::testing::HasSubstr("64-byte descriptors")) << error_of(wide);

  const std::string text = scratch.file("text.voc");
  write(text, "# an ORB-SLAM2 text vocabulary\n10 6 0 0\n");
  EXPECT_THAT(error_of(text), ::testing::HasSubstr("not a depot vocabulary")) << error_of(text);

  for (const std::string& p : {missing, truncated, corrupt, wide, text})
    EXPECT_EQ(error_of(p).find('\n'), std::string::npos);
}

}  // namespace
}  // namespace depot::slam
