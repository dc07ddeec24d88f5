// The keyframe database and BoW-guided matching on real photographs: a
// warped view of a photo finds that photo's keyframe first, and the
// matches it gives agree with the known warp.
#include "slam/place/keyframe_database.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/data/map.h"
#include "slam/feature/orb_extractor.h"
#include "slam/match/orb_matcher.h"
#include "slam/place/vocabulary_training.h"

namespace depot::slam {
namespace {

namespace fs = std::filesystem;

struct Scene {
  std::vector<cv::Mat> images;
  std::shared_ptr<const Vocabulary> vocabulary;
  ScaleLevels levels = ScaleLevels::make(8, 1.2f);
};

Frame frame_of(long id, const cv::Mat& gray, const ScaleLevels* levels) {
  OrbExtractor extractor(OrbParams{});
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  extractor.extract(gray, cv::Mat(), kps, desc);
  const cv::Mat no_depth = cv::Mat::zeros(gray.size(), CV_32F);
  return Frame(id, id, Features(kps, desc, no_depth, PinholeCamera{}, levels));
}

const cv::Mat kWarp = cv::getRotationMatrix2D({320, 240}, 8, 1.1);

cv::Mat warped(const cv::Mat& gray) {
  cv::Mat out;
  cv::warpAffine(gray, out, kWarp, gray.size());
  return out;
}

const Scene& scene() {
  static const Scene s = [] {
    Scene s;
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(std::string(DEPOT_SHARED_DATA) + "/photos"))
      if (e.path().extension() == ".jpg") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    std::vector<cv::Mat> descriptors;
    for (const std::string& f : files) {
      cv::Mat small;
      cv::resize(cv::imread(f, cv::IMREAD_GRAYSCALE), small, cv::Size(640, 480));
      s.images.push_back(small);
      descriptors.push_back(frame_of(0, small, &s.levels).features.descriptors);
    }
    s.vocabulary = std::make_shared<const Vocabulary>(train_vocabulary(descriptors, {8, 4, 10, 1}));
    return s;
  }();
  return s;
}

// One keyframe per photo, each keypoint with a map point (positions do not
// matter here).
struct Database {
  Map map;
  KeyFrameDatabase db{scene().vocabulary};
  std::vector<KeyFrame*> keyframes;
  Database() {
    for (size_t i = 0; i < scene().images.size(); ++i) {
      KeyFrame* kf =
          map.create_keyframe(frame_of(static_cast<long>(i), scene().images[i], &scene().levels));
      for (size_t k = 0; k < kf->features.size(); ++k) {
        MapPoint* mp = map.create_map_point(Eigen::Vector3d(0, 0, 1), kf);
        mp->add_observation(kf, k);
        kf->add_map_point(mp, k);
      }
      db.describe(*kf);
      db.add(kf);
      keyframes.push_back(kf);
    }
  }
};

TEST(KeyFrameDatabase, AWarpedViewFindsItsKeyFrameFirst) {
  Database d;
  ASSERT_EQ(d.db.size(), scene().images.size());
  for (size_t i = 0; i < scene().images.size(); ++i) {
    Frame query = frame_of(100, warped(scene().images[i]), &scene().levels);
    const std::vector<KeyFrame*> found = d.db.relocalisation_candidates(query);
    ASSERT_FALSE(found.empty()) << "photo " << i;
    EXPECT_EQ(found.front(), d.keyframes[i]) << "photo " << i;
  }
}

TEST(KeyFrameDatabase, ErasedKeyFramesAreNotFound) {
  Database d;
  d.db.erase(d.keyframes[2]);
  EXPECT_EQ(d.db.size(), scene().images.size() - 1);
  Frame query = frame_of(100, warped(scene().images[2]), &scene().levels);
  for (KeyFrame* kf : d.db.relocalisation_candidates(query)) EXPECT_NE(kf, d.keyframes[2]);
  d.db.clear();
  EXPECT_TRUE(d.db.relocalisation_candidates(query).empty());
}

TEST(KeyFrameDatabase, LoopCandidatesLeaveOutTheQueryAndItsNeighbours) {
  Database d;
  // A keyframe of the same photo, connected to the query: not a loop.
  KeyFrame* query = d.keyframes[1];
  for (const KeyFrame* kf : d.db.loop_candidates(*query, 0.0)) EXPECT_NE(kf, query);
}

TEST(MatchByBow, MatchesAgreeWithTheKnownWarp) {
  Database d;
  for (size_t i = 0; i < scene().images.size(); ++i) {
    Frame query = frame_of(100, warped(scene().images[i]), &scene().levels);
    d.db.describe(query);
    std::vector<MapPoint*> matches;
    const int n = match_by_bow(*d.keyframes[i], query, matches, 0.75f);
    EXPECT_GE(n, 50) << "photo " << i;
    int right = 0;
    for (size_t f = 0; f < matches.size(); ++f) {
      if (!matches[f]) continue;
      const size_t k = matches[f]->observations.begin()->second;
      const cv::Point2f p = d.keyframes[i]->features.keypoints[k].pt;
      const cv::Point2f q = query.features.keypoints[f].pt;
      const double u =
          kWarp.at<double>(0, 0) * p.x + kWarp.at<double>(0, 1) * p.y + kWarp.at<double>(0, 2);
      const double v =
          kWarp.at<double>(1, 0) * p.x + kWarp.at<double>(1, 1) * p.y + kWarp.at<double>(1, 2);
      right += std::hypot(u - q.x, v - q.y) < 4.0;
    }
    EXPECT_GE(right, 0.85 * n) << "photo " << i << ": " << right << " of " << n;
  }
}

}  // namespace
}  // namespace depot::slam
