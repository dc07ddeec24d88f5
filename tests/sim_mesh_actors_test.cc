// Mesh-style actors (actors_style: mesh): skinned MakeHuman people and
// catalogue animals whose labels come from MuJoCo's skins in the
// segmentation pass. Label pixels must
// agree with depth and the person's ground-truth pose, moving flags must
// follow the walk, and the same scenario and seed must give the same bytes.
#include <set>

#include <gtest/gtest.h>

#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace depot::test {
namespace {

const std::vector<std::pair<std::string, std::string>> kMesh = {{"actors_style", "mesh"}};

SmallRender mesh_render(int frames, int width, bool ideal, std::optional<uint64_t> seed = {},
                        const std::string& scenario = "depot_walking_xyz") {
  SmallRender r{scenario, frames, width, ideal, seed};
  r.set = kMesh;
  return r;
}

// Pixels labelled `id` with depth, and how many of them back-project (with
// the calibration and the ground-truth camera pose) into the instance's
// extent at `pose`, inflated by `margin`.
struct Agreement {
  int pixels = 0;
  int inside = 0;
};
Agreement labels_against_pose(const Dataset& d, size_t frame, int id, const Pose& pose,
                              double margin) {
  const Calibration& c = d.calibration;
  const cv::Mat depth = d.depth_metres(frame), labels = d.labels_image(frame);
  Eigen::AlignedBox3d box = d.objects.at(id).extent;
  box.min().array() -= margin;
  box.max().array() += margin;
  const Pose object_from_camera = pose.inverse() * d.groundtruth[frame].pose;
  Agreement a;
  for (int v = 0; v < depth.rows; ++v)
    for (int u = 0; u < depth.cols; ++u) {
      if (labels.at<uint16_t>(v, u) != id) continue;
      const double z = depth.at<float>(v, u);
      // Ideal sensor: every labelled pixel has depth (renderer zeroes only
      // unlabelled ones), so a skin labelled as background would show here.
      EXPECT_GT(z, 0.0) << "labelled pixel without depth at " << u << "," << v;
      if (z <= 0) continue;
      const Eigen::Vector3d p =
          object_from_camera * Eigen::Vector3d((u - c.cx) * z / c.fx, (v - c.cy) * z / c.fy, z);
      ++a.pixels;
      a.inside += box.contains(p);
    }
  return a;
}

struct Checked {
  int people = 0, frames = 0, pixels = 0;  // people: actors of the classes checked
};
Checked check_actors(const Dataset& d, const std::set<std::string>& classes, int min_pixels) {
  Checked c;
  for (const auto& [id, info] : d.objects) {
    if (!classes.count(info.class_name)) continue;
    ++c.people;
    for (size_t f = 0; f < d.frames.size(); f += 3) {
      const Pose pose = d.object_poses[f].at(id).pose;
      const Agreement a = labels_against_pose(d, f, id, pose, 0.03);
      if (a.pixels < min_pixels) continue;
      ++c.frames;
      c.pixels += a.pixels;
      EXPECT_EQ(a.inside, a.pixels) << info.name << " frame " << f;
      // A wrong pose must not fit: shifted by more than the person's depth.
      Pose shifted = pose;
      shifted.translation() += pose.linear().col(0) * (info.extent.sizes().x() + 0.3);
      const Agreement off = labels_against_pose(d, f, id, shifted, 0.03);
      EXPECT_LT(off.inside, 0.9 * off.pixels) << info.name << " frame " << f;
    }
  }
  return c;
}
Checked check_people(const Dataset& d) {
  return check_actors(d, {"person"}, 100);
}

TEST(SimMeshActors, PersonLabelsAgreeWithDepthAndPose) {
  const Checked c = check_people(read_dataset(render_small(mesh_render(24, 160, true))));
  EXPECT_GE(c.people, 2);
  EXPECT_GE(c.frames, 8) << "the walkers must be seen";
  EXPECT_GT(c.pixels, 8 * 1000) << "mesh people must cover a good part of the 160x120 frames";
}

TEST(SimMeshActors, SeatedPersonLabelsAgreeWithDepthAndPose) {
  const Checked c = check_people(
      read_dataset(render_small(mesh_render(6, 160, true, {}, "depot_sitting_static"))));
  EXPECT_GE(c.people, 2);
  EXPECT_GE(c.frames, 2) << "the sitters must be seen";
  EXPECT_GT(c.pixels, 2 * 500);
}

TEST(SimMeshActors, AnimalLabelsAgreeWithDepthAndPose) {
  // The patrol starts facing the cat and the pig, both drawn from the
  // catalogue (the pig's legs swung procedurally, the cat's by its clip).
  const Dataset d = read_dataset(render_small(mesh_render(12, 320, true, {}, "depot_patrol")));
  const Checked c = check_actors(d, {"cat", "pig"}, 40);
  EXPECT_EQ(c.people, 2);
  EXPECT_GE(c.frames, 6) << "the cat and the pig must be seen";
  EXPECT_GT(c.pixels, 6 * 100);
  // Both walk: every frame flags them moving.
  for (const char* name : {"cat_1", "pig_1"}) {
    const int id = d.object(name).id;
    for (size_t f = 0; f < d.frames.size(); ++f)
      EXPECT_TRUE(d.object_poses[f].at(id).moving) << name << " frame " << f;
  }
}

TEST(SimMeshActors, PeopleOfAScenePickDifferentModels) {
  // Three people in walking_xyz, five people models in the catalogue: every
  // person wears a different one, whatever the seed.
  for (uint64_t seed : {1, 2, 3}) {
    const Dataset d = read_dataset(render_small(mesh_render(1, 64, true, seed)));
    std::set<std::string> models;
    int people = 0;
    for (const auto& [id, info] : d.objects) {
      if (info.class_name != "person") continue;
      ++people;
      EXPECT_FALSE(info.asset.empty()) << info.name;
      models.insert(info.asset);
    }
    EXPECT_EQ(people, 3);
    EXPECT_EQ(models.size(), 3u) << "seed " << seed;
  }
}

TEST(SimMeshActors, WalkingMeshPersonIsFlaggedMoving) {
  const Dataset d = read_dataset(render_small(mesh_render(20, 160, true)));
  const int walker = d.object("walker_1").id;
  EXPECT_EQ(d.objects.at(walker).class_name, "person");
  int moving = 0;
  for (size_t f = 0; f < d.frames.size(); ++f) moving += d.object_poses[f].at(walker).moving;
  EXPECT_EQ(moving, static_cast<int>(d.frames.size()));
}

TEST(SimMeshActors, SameSeedGivesByteIdenticalDatasets) {
  const std::string a = render_small(mesh_render(8, 160, false, 42));
  const std::string b = render_small(mesh_render(8, 160, false, 42));
  EXPECT_EQ(compare_trees(a, b), "");
  // And the style really changes the pictures.
  SmallRender primitive{"depot_walking_xyz", 8, 160, false, 42};
  primitive.set = {{"actors_style", "primitive"}};
  EXPECT_NE(compare_trees(a, render_small(primitive)), "");
}

}  // namespace
}  // namespace depot::test
