// The camera's clearance to the static scene: a path through a crate stack is
// refused before anything is rendered (one error line naming the scenario,
// the frames and the crates), an explicit opt-out renders with a warning, and
// every shipped scenario keeps its clearance.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/testing/error_of.h"
#include "sim/camera/camera_motion.h"
#include "sim/pipeline/export_truth.h"
#include "sim/scenario/scenario_loader.h"
#include "sim/scene/obstacles.h"
#include "sim/world/camera_clearance.h"
#include "sim/world/simulated_sequence.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace fs = std::filesystem;

namespace depot::test {
namespace {

// A robot camera driving east at 0.5 m height along y = -2.4, through the
// crate stack 'crates_e' (scenes/depot.yaml: centre (8.2, -2.4), 2 x 3 crates,
// x 7.6..8.8), then out and back.
std::string through_crates(const std::string& extra_motion_keys = "") {
  return std::string("scene: ") + DEPOT_SOURCE_DIR +
         "/scenes/depot.yaml\nclasses: " + DEPOT_SOURCE_DIR +
         "/scenes/classes.yaml\nframes: 560\n"
         "motion: {type: waypoints, path: [[5.0, -2.4], [9.3, -2.4]], loop: false, height: 0.5, "
         "speed: 0.5" +
         extra_motion_keys + "}\n";
}

struct Measured {
  sim::Scenario scenario;
  sim::CameraClearance clearance;
  std::vector<Eigen::Vector3d> positions;  // camera centre per frame
};

Measured measure(const std::string& path, std::optional<uint64_t> seed = {}) {
  Measured m;
  m.scenario = sim::load_scenario(path);
  if (seed) m.scenario.seed = *seed;
  const auto stamps = sim::frame_timestamps(m.scenario);
  const sim::StaticObstacles obstacles(m.scenario.layout,
                                       m.scenario.world_seed());
  const sim::CameraMotion motion(m.scenario.motion, m.scenario.seed, stamps.front().first);
  m.clearance = sim::measure_camera_clearance(m.scenario, obstacles, motion, stamps);
  for (const auto& s : stamps) m.positions.push_back(motion.pose_at(s.first).translation());
  return m;
}

TEST(CameraClearance, FindsTheFramesThroughACrateStack) {
  const Measured m = measure(write_yaml("crates", through_crates()));
  ASSERT_FALSE(m.clearance.too_close.empty());
  EXPECT_DOUBLE_EQ(m.clearance.required, 0.4) << "default: the sensor's min_depth";
  // Out and back: two runs of frames, each around the crates.
  ASSERT_EQ(m.clearance.too_close.size(), 2u) << sim::describe_too_close(m.clearance);
  // How far the camera is from the stack's footprint along x (its y and
  // height are within the stack's).
  auto off_the_stack = [&](int f) {
    return std::max({7.57 - m.positions[f].x(), m.positions[f].x() - 8.83, 0.0});
  };
  for (const sim::TooCloseRange& r : m.clearance.too_close) {
    EXPECT_EQ(r.nearest.object, "'crates_e' (crate)");
    EXPECT_LE(r.nearest.distance, 0.0) << "the camera drives into the crates";
    // The frames flagged are those within the clearance of the stack (up to
    // a few cm of crate jitter), and their neighbours are not.
    for (int f = r.first; f <= r.last; ++f) EXPECT_LT(off_the_stack(f), 0.4 + 0.05) << f;
    EXPECT_GT(off_the_stack(r.first - 1), 0.4 - 0.05) << r.first - 1;
    EXPECT_GT(off_the_stack(r.last + 1), 0.4 - 0.05) << r.last + 1;
  }
  // Every frame with the camera over the stack is flagged.
  for (size_t f = 0; f < m.positions.size(); ++f) {
    const bool flagged = std::any_of(
        m.clearance.too_close.begin(), m.clearance.too_close.end(),
        [&](const sim::TooCloseRange& r) { return r.first <= int(f) && int(f) <= r.last; });
    if (off_the_stack(int(f)) == 0.0) {
      EXPECT_TRUE(flagged) << "frame " << f;
    }
  }
}

TEST(CameraClearance, RefusesBeforeRenderingWithOneLine) {
  const std::string yaml = write_yaml("crates", through_crates());
  for (const char* command : {"sim render --width 64", "sim truth"}) {
    const std::string out = temp_path("out");
    const DepotResult r = depot(std::string(command) + " " + yaml + " -q -o " + out);
    EXPECT_NE(r.code, 0) << command << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_EQ(r.output.rfind("depot: error: " + yaml + ": ", 0), 0u) << r.output;
    EXPECT_THAT(r.output, ::testing::HasSubstr("closer than 0.40 m")) << r.output;
    EXPECT_THAT(r.output, ::testing::HasSubstr("frames ")) << r.output;
    EXPECT_THAT(r.output, ::testing::HasSubstr("'crates_e'")) << r.output;
    EXPECT_THAT(r.output, ::testing::HasSubstr("allow_close")) << r.output;
    EXPECT_FALSE(fs::exists(out)) << command << " wrote output";
  }
  // The frames in the message are the ones measured.
  const Measured m = measure(yaml);
  const std::string frames = std::to_string(m.clearance.too_close[0].first) + "-" +
                             std::to_string(m.clearance.too_close[0].last);
  const std::string message = error_of([&] { sim::export_truth(m.scenario, {}); });
  EXPECT_THAT(message, ::testing::HasSubstr(frames)) << message << " should name " << frames;
}

TEST(CameraClearance, OptOutRendersWithAWarningNamingTheFrames) {
  const std::string yaml = write_yaml("crates_allowed", through_crates(", allow_close: true"));
  const std::string out = temp_path("out");
  DepotResult r = depot("sim truth " + yaml + " -q -o " + out);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("depot: warning: " + yaml + ": ")) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("frames ")) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("'crates_e'")) << r.output;
  EXPECT_TRUE(fs::exists(out + "/groundtruth.txt"));
}

TEST(CameraClearance, IsAScenarioKey) {
  // A clearance of 0 still refuses a camera inside the crates; a path that
  // stops 0.3 m short passes with clearance 0.25 and fails with the default.
  EXPECT_FALSE(
      measure(write_yaml("zero", through_crates(", clearance: 0"))).clearance.too_close.empty());
  const std::string shy = std::string("scene: ") + DEPOT_SOURCE_DIR +
                          "/scenes/depot.yaml\nframes: 200\n"
                          "motion: {type: waypoints, path: [[4.0, -2.4], [7.25, -2.4]], "
                          "loop: false, height: 0.5, speed: 0.5";
  const Measured relaxed = measure(write_yaml("shy", shy + ", clearance: 0.25}\n"));
  EXPECT_TRUE(relaxed.clearance.too_close.empty()) << sim::describe_too_close(relaxed.clearance);
  EXPECT_DOUBLE_EQ(relaxed.clearance.required, 0.25);
  EXPECT_FALSE(measure(write_yaml("shy_default", shy + "}\n")).clearance.too_close.empty());
  EXPECT_NE(error_of([] {
              sim::load_scenario(write_yaml("neg", through_crates(", clearance: -1")));
            }).find("out of range"),
            std::string::npos);
}

TEST(CameraClearance, ShippedScenariosKeepIt) {
  // Every shipped scenario, at its own seed and two others (the seed moves
  // the goods on the shelves by a few centimetres).
  for (const std::string& name :
       sim::list_scenarios(std::string(DEPOT_SOURCE_DIR) + "/scenarios")) {
    for (std::optional<uint64_t> seed :
         {std::optional<uint64_t>(), std::optional<uint64_t>(1), std::optional<uint64_t>(2)}) {
      const Measured m = measure(scenario_path(name), seed);
      EXPECT_TRUE(m.clearance.too_close.empty())
          << name << " seed " << m.scenario.seed << ": " << sim::describe_too_close(m.clearance);
      if (!seed) {
        const Eigen::Vector3d& p = m.positions[m.clearance.frame];
        std::printf("%-26s min camera clearance %.2f m to %s at frame %d (%.2f, %.2f, %.2f)\n",
                    name.c_str(), m.clearance.nearest.distance, m.clearance.nearest.object.c_str(),
                    m.clearance.frame, p.x(), p.y(), p.z());
      }
    }
  }
}

}  // namespace
}  // namespace depot::test
