// Local mapping on keyframes of the synthetic room's frame (synchronous mode, so each
// step is observable): culling of weak new points, culling of redundant
// keyframes, fusion of duplicate points, and failures reaching the caller.
#include "slam/mapping/local_mapper.h"

#include <chrono>
#include <thread>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "slam/feature/orb_extractor.h"
#include "tests/support/synthetic_room.h"

namespace depot::slam {
namespace {

class LocalMapperTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const test::RealFrame real = test::room_frame();
    cv::Mat gray;
    cv::cvtColor(real.bgr, gray, cv::COLOR_BGR2GRAY);
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    OrbExtractor(OrbParams{}).extract(gray, cv::Mat(), keypoints, descriptors);
    features_ = Features(keypoints, descriptors, real.depth, PinholeCamera{}, &levels_);
  }

  // A keyframe of the room frame at the origin; `points(i)` gives the map
  // point of keypoint i (nullptr: none).
  template <typename PointOf>
  KeyFrame* add_keyframe(PointOf points) {
    Frame frame(static_cast<long>(map_.all_keyframes().size()), 0.1 * map_.n_keyframes(),
                features_);
    frame.has_pose = true;
    KeyFrame* kf = map_.create_keyframe(frame);
    for (size_t i = 0; i < frame.size(); ++i)
      if (MapPoint* mp = points(i, kf)) kf->add_map_point(mp, i);
    return kf;
  }

  // What tracking does for a keyframe's own new point: from depth, observed
  // by that keyframe only.
  MapPoint* point_from_depth(KeyFrame* kf, size_t i) {
    if (!features_.has_depth(i)) return nullptr;
    const cv::KeyPoint& kp = features_.keypoints[i];
    MapPoint* mp =
        map_.create_map_point(features_.camera.unproject(kp.pt.x, kp.pt.y, features_.depth[i]), kf);
    mp->add_observation(kf, i);
    mp->update_descriptor();
    mp->update_normal_and_depth();
    return mp;
  }

  KeyFrame* add_first_keyframe() {
    return add_keyframe([&](size_t i, KeyFrame* kf) { return point_from_depth(kf, i); });
  }

  // A keyframe that tracking matched to `source`'s points in every slot.
  KeyFrame* add_keyframe_seeing(KeyFrame* source) {
    return add_keyframe([source](size_t i, KeyFrame*) { return source->map_points[i]; });
  }

  void process(LocalMapper& mapper, KeyFrame* kf) {
    mapper.insert_keyframe(kf);
    mapper.run_pending();
  }

  ScaleLevels levels_ = ScaleLevels::make(8, 1.2f);
  Features features_;
  Map map_;
};

TEST_F(LocalMapperTest, CullsNewPointsFoundInUnderAQuarterOfThePredictedFrames) {
  LocalMapper mapper(map_, false);
  KeyFrame* first = add_first_keyframe();
  process(mapper, first);
  // Tracking predicted half of the new points in 20 frames and found them
  // in 2 only; the others were found where predicted.
  std::vector<MapPoint*> weak, strong;
  for (MapPoint* mp : first->map_points) {
    if (!mp) continue;
    if (mp->id % 2) {
      mp->visible = 20;
      mp->found = 2;
      weak.push_back(mp);
    } else {
      mp->visible = 20;
      mp->found = 18;
      strong.push_back(mp);
    }
  }
  ASSERT_GT(weak.size(), 100u);
  process(mapper, add_keyframe_seeing(first));
  for (MapPoint* mp : weak) {
    EXPECT_TRUE(mp->bad);
    EXPECT_EQ(map_.map_points().count(mp), 0u);
    EXPECT_EQ(mp->n_observations(), 0);
  }
  for (MapPoint* mp : strong) EXPECT_FALSE(mp->bad);
  EXPECT_EQ(mapper.stats().points_culled, static_cast<long>(weak.size()));
  EXPECT_EQ(first->tracked_map_points(0), static_cast<int>(strong.size()));
}

// ORB-SLAM2's rule for RGB-D: two keyframes later a new point must have
// weighted observations above 3, an observation with depth weighing 2.
TEST_F(LocalMapperTest, CullsNewPointsSeenWithDepthByOneKeyframeTwoKeyframesLater) {
  LocalMapper mapper(map_, false);
  KeyFrame* first = add_first_keyframe();
  process(mapper, first);
  // The second keyframe sees the points i % 3 = 0 and 1 (with depth, as
  // the first), the third only i % 3 = 0. Both wait in the queue together,
  // so fusion (which runs once the queue is empty) cannot add the others
  // to them before culling looks at those.
  auto seen = [first](int max_class) {
    return [first, max_class](size_t i, KeyFrame*) {
      return static_cast<int>(i % 3) <= max_class ? first->map_points[i] : nullptr;
    };
  };
  mapper.insert_keyframe(add_keyframe(seen(1)));
  mapper.insert_keyframe(add_keyframe(seen(0)));
  mapper.run_pending();
  int alive[3] = {0, 0, 0}, total[3] = {0, 0, 0};
  for (size_t i = 0; i < features_.size(); ++i) {
    if (!features_.has_depth(i)) continue;
    total[i % 3]++;
    alive[i % 3] += first->map_points[i] && !first->map_points[i]->bad;
  }
  ASSERT_GT(total[2], 100);
  EXPECT_EQ(alive[0], total[0]) << "seen with depth by three keyframes";
  EXPECT_EQ(alive[1], total[1]) << "seen with depth by two keyframes";
  EXPECT_EQ(alive[2], 0) << "seen by one keyframe, two keyframes later";
}

TEST_F(LocalMapperTest, CullsKeyframesWhosePointsThreeOthersSeeAtTheSameScale) {
  LocalMapper mapper(map_, false);
  KeyFrame* first = add_first_keyframe();
  process(mapper, first);
  std::vector<KeyFrame*> later;
  for (int k = 0; k < 4; ++k) {
    later.push_back(add_keyframe_seeing(first));
    process(mapper, later.back());
  }
  // Each keyframe sees exactly what the first one sees. Keyframe 1 turns
  // redundant once four others see its points (at keyframe 3), keyframe 2
  // at keyframe 4; keyframe 3 then has only three observers per point, one
  // too few; the first keyframe is never culled.
  EXPECT_FALSE(first->bad);
  EXPECT_TRUE(later[0]->bad);
  EXPECT_TRUE(later[1]->bad);
  EXPECT_FALSE(later[2]->bad);
  EXPECT_FALSE(later[3]->bad);
  EXPECT_EQ(mapper.stats().keyframes_culled, 2);
  EXPECT_EQ(map_.n_keyframes(), 3u);
  EXPECT_EQ(map_.keyframes().count(later[0]), 0u);
}

TEST_F(LocalMapperTest, FusesDuplicatePointsOfTheSameKeypoints) {
  LocalMapper mapper(map_, false);
  KeyFrame* first = add_first_keyframe();
  process(mapper, first);
  // The second keyframe (same view) was matched to the first one's even
  // points; for the odd keypoints tracking made new points from depth:
  // duplicates of the first keyframe's odd points.
  std::vector<MapPoint*> originals(features_.size(), nullptr),
      duplicates(features_.size(), nullptr);
  KeyFrame* second = add_keyframe([&](size_t i, KeyFrame* kf) -> MapPoint* {
    if (i % 2 == 0) return first->map_points[i];
    originals[i] = first->map_points[i];
    duplicates[i] = point_from_depth(kf, i);
    return duplicates[i];
  });
  process(mapper, second);
  int pairs = 0, fused = 0;
  for (size_t i = 1; i < features_.size(); i += 2) {
    if (!originals[i] || !duplicates[i]) continue;
    ++pairs;
    MapPoint* survivor = follow_replacements(originals[i]);
    const bool one_point = survivor && first->map_points[i] == survivor &&
                           second->map_points[i] == survivor &&
                           (originals[i]->bad != duplicates[i]->bad);
    if (one_point) {
      ++fused;
      EXPECT_EQ(survivor->n_observations(), 2);
      MapPoint* gone = originals[i]->bad ? originals[i] : duplicates[i];
      EXPECT_EQ(gone->replaced_by, survivor);
    }
  }
  ASSERT_GT(pairs, 100);
  // A few keypoints share a cell with a better-matching twin; nearly all fuse.
  EXPECT_GT(fused, 0.9 * pairs) << fused << " of " << pairs << " duplicates fused";
}

TEST_F(LocalMapperTest, AQueuedKeyframeFollowsPointsFusedMeanwhile) {
  LocalMapper mapper(map_, false);
  KeyFrame* first = add_first_keyframe();
  process(mapper, first);
  KeyFrame* queued = add_keyframe_seeing(first);
  // While it waited, the first keyframe's points were fused into others.
  size_t replaced = 0;
  for (size_t i = 0; i < first->map_points.size(); ++i) {
    MapPoint* mp = first->map_points[i];
    if (!mp || i % 3) continue;
    MapPoint* other = map_.create_map_point(mp->position, first);
    other->descriptor = mp->descriptor.clone();
    mp->replace(other);
    ++replaced;
  }
  ASSERT_GT(replaced, 50u);
  process(mapper, queued);
  for (size_t i = 0; i < queued->map_points.size(); ++i) {
    MapPoint* mp = queued->map_points[i];
    if (!first->map_points[i]) continue;
    ASSERT_NE(mp, nullptr) << "slot " << i;
    EXPECT_FALSE(mp->bad) << "slot " << i;
    EXPECT_EQ(mp, first->map_points[i]) << "slot " << i;
    EXPECT_EQ(mp->observations.count(queued), 1u);
  }
}

TEST_F(LocalMapperTest, AFailureInTheMappingThreadReachesTheCallerAsOneError) {
  LocalMapper mapper(map_, true);
  // A keyframe whose map point slots do not match its keypoints: mapping
  // cannot process it.
  Frame broken(0, 0.0, features_);
  broken.map_points.resize(3);
  KeyFrame* kf = map_.create_keyframe(broken);
  mapper.insert_keyframe(kf);
  for (int i = 0; i < 2000 && !mapper.idle(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_TRUE(mapper.idle()) << "a failed mapper must not look busy forever";
  try {
    mapper.throw_if_failed();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "local mapping: keyframe 0: has 3 map point slots for " +
                                         std::to_string(features_.size()) + " keypoints");
  }
  // It stays failed, takes no more work, and stops cleanly.
  EXPECT_THROW(mapper.throw_if_failed(), Error);
  mapper.insert_keyframe(kf);
  EXPECT_EQ(mapper.queued(), 0u);
  mapper.stop();
}

TEST_F(LocalMapperTest, APauseEndsWithItsScopeEvenWhenTheCorrectionThrows) {
  LocalMapper mapper(map_, true);
  KeyFrame* kf = add_first_keyframe();
  try {
    const MappingPause paused(mapper);
    mapper.insert_keyframe(kf);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_EQ(mapper.queued(), 1u) << "held while paused";
    fail("loop closing", "a correction failed");
  } catch (const Error&) {
  }
  for (int i = 0; i < 2000 && !mapper.idle(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_TRUE(mapper.idle()) << "mapping stayed paused";
  EXPECT_EQ(mapper.queued(), 0u);
  mapper.throw_if_failed();
  mapper.stop();
}

TEST_F(LocalMapperTest, AFailureInSynchronousModeIsThrownAtOnceTheSameWay) {
  LocalMapper mapper(map_, false);
  Frame broken(0, 0.0, features_);
  broken.map_points.resize(3);
  mapper.insert_keyframe(map_.create_keyframe(broken));
  try {
    mapper.run_pending();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("local mapping: keyframe 0: has 3 map point slots", 0),
              0u)
        << e.what();
  }
}

}  // namespace
}  // namespace depot::slam
