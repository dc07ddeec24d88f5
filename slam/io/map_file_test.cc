// The map file on a synthetic map (tests/support/ba_scene.h): what is
// loaded is what was saved, and every bad file is one clear error.
#include "slam/io/map_file.h"

#include "slam/camera/lens_distortion.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/binary_io.h"
#include "common/error.h"
#include "common/testing/temp_path.h"
#include "slam/data/map_point.h"
#include "tests/support/ba_scene.h"

namespace depot::slam {
namespace {

using namespace depot::slam::test;

// Magic, version, vocabulary, camera (2 x i32, 10 x f64), levels, scale.
constexpr size_t kHeaderBytes = 8 + 4 + 4 + 8 + 10 * 8 + 4 + 4;

// The same file as version 2 wrote it: without each keyframe's map and
// origin flag and each point's map (walks the records of map_file.h's
// layout), its checksum renewed.
std::string as_version_2(const std::string& v3) {
  std::string out = v3.substr(0, kHeaderBytes);
  out[8] = 2;
  size_t at = kHeaderBytes;
  auto copy = [&](size_t n) {
    out += v3.substr(at, n);
    at += n;
  };
  auto count = [&]() {
    uint32_t n = 0;
    std::memcpy(&n, &v3[at], 4);
    copy(4);
    return n;
  };
  const uint32_t keyframes = count();
  for (uint32_t k = 0; k < keyframes; ++k) {
    copy(3 * 8);  // id, frame id, timestamp
    at += 4 + 1;  // map, origin
    copy(12 * 8 + 8);
    copy(8 * size_t{count()});   // loop edges
    copy(12 * size_t{count()});  // covisible keyframes
    const uint32_t n = count();
    copy(n * size_t{7 * 4 + 3 + 8 + 32});
  }
  const uint32_t points = count();
  for (uint32_t p = 0; p < points; ++p) {
    copy(8);  // id
    at += 4;  // map
    copy(3 * 8 + 8 + 8 + 4 + 4 + 32 + 3 * 8 + 4 + 4);
  }
  copy(4);
  const uint32_t crc = crc32_of(out, out.size() - 4);
  std::memcpy(&out[out.size() - 4], &crc, 4);
  return out;
}

class MapFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    build_ba_scene(scene_, 41);
    for (MapPoint* mp : scene_.map.map_points()) mp->update_descriptor();
    // A spanning tree, a loop edge and a culled keyframe and point, as a
    // real map has them.
    scene_.kfs[4]->loop_edges.insert(scene_.kfs[0]);
    scene_.kfs[0]->loop_edges.insert(scene_.kfs[4]);
    scene_.kfs[2]->set_bad();
    scene_.map.erase_keyframe(scene_.kfs[2]);
    MapPoint* culled = *scene_.map.map_points().begin();
    culled->set_bad();
    scene_.map.erase_map_point(culled);
    path_ = testkit::temp_path("map_file_test") + ".map";
    save_map_file(scene_.map, camera_, levels(), kVocabulary, path_);
  }
  void TearDown() override { std::filesystem::remove(path_); }

  std::string bytes() const {
    std::ifstream in(path_, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  void write(const std::string& b) const {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out << b;
  }
  // The error message loading gives, "" when it loads.
  std::string load_error(uint32_t vocabulary = kVocabulary,
                         const PinholeCamera* camera = nullptr) const {
    Map map;
    try {
      load_map_file(path_, camera ? *camera : camera_, levels(), vocabulary, map);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }

  static constexpr uint32_t kVocabulary = 0x1234abcd;
  BaScene scene_;
  PinholeCamera camera_;
  std::string path_;
};

TEST_F(MapFileTest, WhatIsLoadedIsWhatWasSaved) {
  Map loaded;
  const MapFileInfo info = load_map_file(path_, camera_, levels(), kVocabulary, loaded);
  EXPECT_EQ(info.version, 3u);
  EXPECT_EQ(info.maps, 1u);
  EXPECT_EQ(info.keyframes, scene_.map.n_keyframes());
  EXPECT_EQ(info.points, scene_.map.n_map_points());
  ASSERT_EQ(loaded.n_keyframes(), 4u);  // the culled one left out
  ASSERT_EQ(loaded.n_map_points(), scene_.map.n_map_points());
  // Saved order = id order: the i-th saved keyframe is the i-th loaded one.
  std::vector<KeyFrame*> a(scene_.map.keyframes().begin(), scene_.map.keyframes().end());
  std::vector<KeyFrame*> b(loaded.keyframes().begin(), loaded.keyframes().end());
  std::map<const KeyFrame*, const KeyFrame*> same;
  for (size_t k = 0; k < a.size(); ++k) same[a[k]] = b[k];
  std::vector<MapPoint*> pa(scene_.map.map_points().begin(), scene_.map.map_points().end());
  std::vector<MapPoint*> pb(loaded.map_points().begin(), loaded.map_points().end());
  std::map<const MapPoint*, const MapPoint*> same_point;
  for (size_t p = 0; p < pa.size(); ++p) same_point[pa[p]] = pb[p];
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_TRUE(a[k]->T_cw.isApprox(b[k]->T_cw, 0.0));
    EXPECT_EQ(a[k]->timestamp, b[k]->timestamp);
    ASSERT_EQ(a[k]->features.size(), b[k]->features.size());
    for (size_t i = 0; i < a[k]->features.size(); ++i) {
      EXPECT_EQ(a[k]->features.keypoints[i].pt, b[k]->features.keypoints[i].pt);
      EXPECT_EQ(a[k]->features.keypoints[i].octave, b[k]->features.keypoints[i].octave);
      EXPECT_EQ(a[k]->features.depth[i], b[k]->features.depth[i]);
      EXPECT_NEAR(a[k]->features.u_right[i], b[k]->features.u_right[i], 1e-3);
      const MapPoint* mp = a[k]->map_points[i];
      EXPECT_EQ(mp && !mp->bad ? same_point[mp] : nullptr, b[k]->map_points[i]);
    }
    EXPECT_EQ(cv::norm(a[k]->features.descriptors, b[k]->features.descriptors, cv::NORM_HAMMING),
              0);
    EXPECT_EQ(a[k]->parent() ? same[a[k]->parent()] : nullptr, b[k]->parent());
    const std::vector<KeyFrame*> ca = a[k]->covisibles(), cb = b[k]->covisibles();
    ASSERT_EQ(ca.size(), cb.size());
    for (size_t c = 0; c < ca.size(); ++c) {
      EXPECT_EQ(same[ca[c]], cb[c]);
      EXPECT_EQ(a[k]->weight(ca[c]), b[k]->weight(cb[c]));
    }
    EXPECT_EQ(a[k]->loop_edges.size(), b[k]->loop_edges.size());
  }
  for (size_t p = 0; p < pa.size(); ++p) {
    EXPECT_EQ(pa[p]->position, pb[p]->position);
    EXPECT_EQ(pa[p]->normal, pb[p]->normal);
    EXPECT_EQ(pa[p]->min_distance, pb[p]->min_distance);
    EXPECT_EQ(pa[p]->max_distance, pb[p]->max_distance);
    EXPECT_EQ(cv::norm(pa[p]->descriptor, pb[p]->descriptor, cv::NORM_HAMMING), 0);
    EXPECT_EQ(pa[p]->observations.size(), pb[p]->observations.size());
  }
}

TEST_F(MapFileTest, BadFilesAreOneClearError) {
  const std::string good = bytes();
  auto expect = [&](const std::string& error, const std::string& needle) {
    EXPECT_THAT(error, ::testing::HasSubstr(path_)) << error;
    EXPECT_THAT(error, ::testing::HasSubstr(needle)) << error;
  };
  write(good.substr(0, good.size() / 2));
  expect(load_error(), "checksum");
  write(good.substr(0, 10));
  expect(load_error(), "truncated");
  std::string corrupt = good;
  corrupt[good.size() / 2] ^= 0x40;
  write(corrupt);
  expect(load_error(), "checksum");
  std::string other_version = good;
  other_version[8] = 4;
  write(other_version);
  expect(load_error(), "version 4, this build reads 1 to 3");
  write("not a map at all");
  expect(load_error(), "not a depot map");
  write(good);
  EXPECT_EQ(load_error(), "");
  // Identities in hex, as `map info` and `vocabulary info` print them.
  expect(load_error(kVocabulary + 1),
         "another vocabulary (identity 1234abcd, this run's is 1234abce;");
  PinholeCamera other = camera_;
  other.fx += 10;
  expect(load_error(kVocabulary, &other), "another camera");
  std::filesystem::remove(path_);
  expect(load_error(), "no such map file");
}

// Found by fuzzing (tests/fuzz/fuzz_map_file): a count the file's bytes
// cannot hold, behind a valid checksum, asked for gigabytes of memory.
TEST_F(MapFileTest, ACountLargerThanTheFileIsOneClearError) {
  std::string bad = bytes();
  // The first keyframe's loop edge count: after the header, the
  // keyframe count and its id, frame id, timestamp, map, origin, pose and
  // parent.
  const size_t loops_at = kHeaderBytes + 4 + 3 * 8 + 4 + 1 + 12 * 8 + 8;
  const uint32_t huge = 0xfffffff0u;
  std::memcpy(&bad[loops_at], &huge, 4);
  const uint32_t crc = crc32_of(bad, bad.size() - 4);
  std::memcpy(&bad[bad.size() - 4], &crc, 4);
  write(bad);
  const std::string error = load_error();
  EXPECT_EQ(error.rfind(path_ + ": truncated map (keyframe ", 0), 0u) << error;
  EXPECT_NE(error.find(" claims 4294967280 loop edges)"), std::string::npos) << error;
}

// Found by fuzzing (tests/fuzz/fuzz_map_file): a keypoint far outside the
// image overflowed the keyframe's grid index.
TEST_F(MapFileTest, AKeypointOutsideTheImageIsOneClearError) {
  std::string bad = bytes();
  // The first keypoint's x: after the first keyframe's loop edges, its
  // covisible keyframes and its keypoint count.
  const size_t loops_at = kHeaderBytes + 4 + 3 * 8 + 4 + 1 + 12 * 8 + 8;
  uint32_t n_loops = 0, n_covisible = 0;
  std::memcpy(&n_loops, &bad[loops_at], 4);
  const size_t covisible_at = loops_at + 4 + 8 * n_loops;
  std::memcpy(&n_covisible, &bad[covisible_at], 4);
  const size_t x_at = covisible_at + 4 + 12 * n_covisible + 4;
  const float far = -1.6e28f;
  std::memcpy(&bad[x_at], &far, 4);
  const uint32_t crc = crc32_of(bad, bad.size() - 4);
  std::memcpy(&bad[bad.size() - 4], &crc, 4);
  write(bad);
  const std::string error = load_error();
  EXPECT_EQ(error.rfind(path_ + ": corrupt map (keyframe ", 0), 0u) << error;
  EXPECT_NE(error.find(": keypoint 0 far outside the image)"), std::string::npos) << error;
}

TEST_F(MapFileTest, TheLensIsPartOfTheCameraAndVersionOneFilesStillLoad) {
  auto expect = [](const std::string& error, const std::string& needle) {
    EXPECT_THAT(error, ::testing::HasSubstr(needle)) << error;
  };
  // A version 2 file (one map) loads as it did.
  const std::string v2 = as_version_2(bytes());
  write(v2);
  EXPECT_EQ(load_error(), "");
  // A version 1 file: the same map without the five distortion values.
  std::string v1 = v2;
  v1.erase(kHeaderBytes - 8 - 40, 40);
  v1[8] = 1;
  uint32_t crc = crc32_of(v1, v1.size() - 4);
  std::memcpy(&v1[v1.size() - 4], &crc, 4);
  write(v1);
  EXPECT_EQ(load_error(), "");
  // A lens makes another camera, in either direction.
  PinholeCamera lensed = camera_;
  lensed.lens.k1 = -0.25;
  lensed.lens.k2 = 0.08;
  set_undistorted_bounds(lensed, "test");
  expect(load_error(kVocabulary, &lensed), "another camera");
  save_map_file(scene_.map, lensed, levels(), kVocabulary, path_);
  expect(load_error(), "k1 -0.25, k2 0.08, p1 0, p2 0, k3 0; this dataset's is");
  Map loaded;
  const MapFileInfo info = load_map_file(path_, lensed, levels(), kVocabulary, loaded);
  EXPECT_EQ(info.camera.lens.k1, -0.25);
  EXPECT_EQ(info.camera.lens.k2, 0.08);
  EXPECT_EQ(info.keyframes, scene_.map.n_keyframes());
}

// The atlas: every map is saved with its id and origin, and loads as it
// was; maps begun after loading get new ids.
TEST_F(MapFileTest, EveryMapOfTheAtlasIsSavedAndLoaded) {
  // The scene's last two keyframes and their points as a second map.
  std::vector<KeyFrame*> kfs(scene_.map.keyframes().begin(), scene_.map.keyframes().end());
  for (size_t k = kfs.size() - 2; k < kfs.size(); ++k) kfs[k]->map_id = 3;
  kfs[kfs.size() - 2]->map_origin = true;
  for (MapPoint* mp : scene_.map.map_points())
    if (mp->reference && mp->reference->map_id == 3) mp->map_id = 3;
  // A point seen from both maps would tie them: let each keep its own.
  for (MapPoint* mp : scene_.map.map_points()) {
    std::vector<KeyFrame*> others;
    for (const auto& [kf, index] : mp->observations)
      if (kf->map_id != mp->map_id) others.push_back(kf);
    for (KeyFrame* kf : others) {
      kf->erase_map_point(mp->observations.at(kf));
      mp->erase_observation(kf);
    }
  }
  save_map_file(scene_.map, camera_, levels(), kVocabulary, path_);
  Map loaded;
  const MapFileInfo info = load_map_file(path_, camera_, levels(), kVocabulary, loaded);
  EXPECT_EQ(info.maps, 2u);
  EXPECT_EQ(loaded.map_ids(), (std::vector<int>{0, 3}));
  std::vector<KeyFrame*> back(loaded.keyframes().begin(), loaded.keyframes().end());
  ASSERT_EQ(back.size(), kfs.size());
  for (size_t k = 0; k < kfs.size(); ++k) {
    EXPECT_EQ(back[k]->map_id, kfs[k]->map_id) << k;
    EXPECT_EQ(back[k]->map_origin, kfs[k]->map_origin) << k;
  }
  for (MapPoint* mp : loaded.map_points())
    for (const auto& [kf, index] : mp->observations) EXPECT_EQ(kf->map_id, mp->map_id);
  EXPECT_EQ(loaded.active_map(), 0) << "the map with most keyframes";
  EXPECT_EQ(loaded.begin_map(), 4) << "a new map's id is above every loaded one";
}

TEST_F(MapFileTest, LoadsOnlyIntoAnEmptyMap) {
  EXPECT_THROW(load_map_file(path_, camera_, levels(), kVocabulary, scene_.map), Error);
}

}  // namespace
}  // namespace depot::slam
