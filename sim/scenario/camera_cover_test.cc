// Camera cover intervals: which times they cover, and the loader's one-line
// errors for intervals that are malformed, out of range or overlapping.
#include "sim/scenario/camera_cover.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/testing/error_of.h"
#include "sim/scenario/scenario_loader.h"

namespace depot::sim {
namespace {

const std::string kPatrol = std::string(DEPOT_SOURCE_DIR) + "/scenarios/depot_patrol.yaml";

TEST(CameraCover, CoversHalfOpenIntervals) {
  const std::vector<CoverInterval> cover = {{1.0, 2.0}, {2.0, 2.5}, {4.0, 4.1}};
  EXPECT_FALSE(is_covered(cover, 0.999));
  EXPECT_TRUE(is_covered(cover, 1.0));
  EXPECT_TRUE(is_covered(cover, 2.0)) << "back-to-back intervals leave no gap";
  EXPECT_FALSE(is_covered(cover, 2.5));
  EXPECT_TRUE(is_covered(cover, 4.05));
  EXPECT_FALSE(is_covered(cover, 4.1));
  EXPECT_FALSE(is_covered({}, 1.0));
}

TEST(CameraCover, ValidIntervalsHaveNoProblem) {
  EXPECT_EQ(camera_cover_problem({}, 10.0), "");
  EXPECT_EQ(camera_cover_problem({{0.0, 1.0}, {1.0, 10.0}}, 10.0), "");
  EXPECT_EQ(camera_cover_problem({{50.0, 60.0}}, 0.0), "") << "duration unknown: no upper bound";
}

TEST(CameraCover, NamesEachProblem) {
  EXPECT_NE(camera_cover_problem({{-1.0, 1.0}}, 10).find("before the first frame"),
            std::string::npos);
  EXPECT_NE(camera_cover_problem({{2.0, 2.0}}, 10).find("must end after it starts"),
            std::string::npos);
  EXPECT_NE(camera_cover_problem({{3.0, 2.0}}, 10).find("must end after it starts"),
            std::string::npos);
  EXPECT_NE(camera_cover_problem({{10.0, 11.0}}, 10).find("starts after the last frame"),
            std::string::npos);
  EXPECT_NE(camera_cover_problem({{9.0, 11.0}}, 10).find("ends after the last frame"),
            std::string::npos);
  const std::string overlap = camera_cover_problem({{1.0, 3.0}, {2.0, 4.0}}, 10);
  EXPECT_NE(overlap.find("interval 2 [2, 4] overlaps or comes before interval 1 [1, 3]"),
            std::string::npos)
      << overlap;
  EXPECT_NE(camera_cover_problem({{5.0, 6.0}, {1.0, 2.0}}, 10).find("overlaps or comes before"),
            std::string::npos);
}

// The loader's error for `camera_cover: value` on the patrol (1080 frames at
// 30 Hz: 36 s).
std::string load_error(const std::string& value) {
  return error_of([&] { load_scenario(kPatrol, {{"camera_cover", value}}); });
}

TEST(CameraCover, LoadsFromTheScenario) {
  const Scenario s = load_scenario(kPatrol, {{"camera_cover", "[[1, 2.5], [30, 36]]"}});
  ASSERT_EQ(s.camera_cover.size(), 2u);
  EXPECT_DOUBLE_EQ(s.camera_cover[0].start, 1.0);
  EXPECT_DOUBLE_EQ(s.camera_cover[1].end, 36.0);
  EXPECT_TRUE(load_scenario(kPatrol).camera_cover.empty());
}

TEST(CameraCover, BadIntervalsAreOneErrorNamingFileAndKey) {
  for (const char* value : {"5", "[3]", "[[1, 2, 3]]", "[[a, b]]", "[[-1, 2]]", "[[2, 1]]",
                            "[[35, 40]]", "[[40, 41]]", "[[1, 3], [2, 4]]", "[[.nan, 2]]"}) {
    const std::string error = load_error(value);
    EXPECT_THAT(error, ::testing::HasSubstr("depot_patrol.yaml")) << value << ": " << error;
    EXPECT_THAT(error, ::testing::HasSubstr("'camera_cover'")) << value << ": " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << value << ": " << error;
  }
  EXPECT_THAT(load_error("[[35, 40]]"), ::testing::HasSubstr("the sequence lasts 36 s"));
  // The scenario's own length bounds the cover: fewer frames, shorter cover.
  EXPECT_NE(error_of([] {
              load_scenario(kPatrol, {{"frames", "30"}, {"camera_cover", "[[0.5, 2]]"}});
            }).find("ends after the last frame"),
            std::string::npos);
}

}  // namespace
}  // namespace depot::sim
