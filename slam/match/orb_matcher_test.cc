// The matcher on a real TUM frame: by descriptor against a shifted copy, and
// by projection against itself with a known pose.
#include "slam/match/orb_matcher.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/data/map.h"
#include "slam/feature/orb_extractor.h"

namespace depot::slam {
namespace {

const std::string kFrame = std::string(DEPOT_SHARED_DATA) + "/tum/fr3_walking_xyz_frame";

struct Images {
  cv::Mat gray, depth;
};

Images load() {
  Images im;
  for (const auto& e : std::filesystem::directory_iterator(kFrame + "/rgb"))
    im.gray = cv::imread(e.path().string(), cv::IMREAD_GRAYSCALE);
  for (const auto& e : std::filesystem::directory_iterator(kFrame + "/depth")) {
    cv::Mat raw = cv::imread(e.path().string(), cv::IMREAD_UNCHANGED);
    raw.convertTo(im.depth, CV_32F, 1.0 / 5000.0);
  }
  return im;
}

Frame make_frame(long id, const cv::Mat& gray, const cv::Mat& depth, const ScaleLevels* levels) {
  OrbExtractor extractor(OrbParams{});
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  extractor.extract(gray, cv::Mat(), kps, desc);
  return Frame(id, id * 0.033, Features(kps, desc, depth, PinholeCamera{}, levels));
}

// A keyframe from `frame` with a map point for every keypoint with depth.
KeyFrame* make_keyframe(Map& map, Frame& frame) {
  frame.has_pose = true;
  KeyFrame* kf = map.create_keyframe(frame);
  for (size_t i = 0; i < frame.size(); ++i) {
    if (!frame.features.has_depth(i)) continue;
    const auto& kp = frame.features.keypoints[i];
    MapPoint* mp = map.create_map_point(
        frame.features.camera.unproject(kp.pt.x, kp.pt.y, frame.features.depth[i]), kf);
    mp->add_observation(kf, i);
    kf->add_map_point(mp, i);
    mp->update_descriptor();
    mp->update_normal_and_depth();
    frame.map_points[i] = mp;
  }
  return kf;
}

TEST(OrbMatcher, ByDescriptorFindsTheShiftedKeypoints) {
  if (!std::filesystem::exists(kFrame)) GTEST_SKIP() << "shared data missing: " << kFrame;
  Images im = load();
  const ScaleLevels levels = ScaleLevels::make(8, 1.2f);
  Frame first = make_frame(0, im.gray, im.depth, &levels);
  Map map;
  KeyFrame* kf = make_keyframe(map, first);
  cv::Mat shifted_gray, shifted_depth;
  cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 12, 0, 1, -7);
  cv::warpAffine(im.gray, shifted_gray, shift, im.gray.size());
  cv::warpAffine(im.depth, shifted_depth, shift, im.depth.size(), cv::INTER_NEAREST);
  Frame second = make_frame(1, shifted_gray, shifted_depth, &levels);
  std::vector<MapPoint*> matches;
  const int n = match_by_descriptor(*kf, second, matches, 0.7f);
  ASSERT_GT(n, 150);
  int correct = 0;
  for (size_t i = 0; i < matches.size(); ++i) {
    if (!matches[i]) continue;
    const size_t k = matches[i]->observations.at(kf);
    const cv::Point2f expected = kf->features.keypoints[k].pt + cv::Point2f(12, -7);
    correct += cv::norm(second.features.keypoints[i].pt - expected) < 2.0;
  }
  EXPECT_GT(correct, 0.9 * n) << correct << " of " << n;  // repeated textures give a few wrong ones
}

TEST(OrbMatcher, ByProjectionWithTheTruePoseMatchesTheSameKeypoints) {
  if (!std::filesystem::exists(kFrame)) GTEST_SKIP() << "shared data missing: " << kFrame;
  Images im = load();
  const ScaleLevels levels = ScaleLevels::make(8, 1.2f);
  Frame last = make_frame(0, im.gray, im.depth, &levels);
  Map map;
  make_keyframe(map, last);
  Frame current = make_frame(1, im.gray, im.depth, &levels);
  current.T_cw = last.T_cw;
  const int n = match_by_projection(current, last, 7.0f);
  int with_point = 0;
  for (MapPoint* mp : last.map_points) with_point += mp != nullptr;
  EXPECT_GT(n, 0.9 * with_point);
  int same = 0;
  for (size_t i = 0; i < current.size(); ++i)
    if (current.map_points[i] && current.map_points[i] == last.map_points[i]) ++same;
  EXPECT_GT(same, 0.95 * n);
  // A wrong pose (30 cm sideways) finds far fewer.
  Frame moved = make_frame(2, im.gray, im.depth, &levels);
  moved.T_cw = last.T_cw;
  moved.T_cw.translation().x() += 0.3;
  EXPECT_LT(match_by_projection(moved, last, 7.0f), 0.3 * n);
}

}  // namespace
}  // namespace depot::slam
