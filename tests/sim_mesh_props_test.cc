// Mesh props (props_style: mesh): office chairs and desks drawn as catalogue
// meshes over hidden primitive collision geoms. Label pixels must agree with
// depth and the prop's pose (and come from the mesh, not the hidden
// primitives), physics and ground truth must not change, the same scenario
// and seed must give the same bytes, and primitive props stay as they were.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "dataset/dataset_info.h"
#include "sim/camera/camera_motion.h"
#include "sim/render/renderer.h"
#include "sim/scenario/scenario_loader.h"
#include "sim/world/world.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace depot::test {
namespace {

const std::pair<std::string, std::string> kMeshProps = {"props_style", "mesh"};

SmallRender props_render(int frames, int width, bool ideal, bool mesh,
                         std::optional<uint64_t> seed = {}) {
  SmallRender r{"depot_walking_xyz", frames, width, ideal, seed};
  r.set = {mesh ? kMeshProps : std::pair<std::string, std::string>{"props_style", "primitive"}};
  return r;
}

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Label pixels of instance `id` with depth, back-projected (calibration and
// ground-truth camera pose) into the frame of the instance at `pose`.
std::vector<Eigen::Vector3d> labelled_points(const Dataset& d, size_t frame, int id,
                                             const Pose& pose) {
  const Calibration& c = d.calibration;
  const cv::Mat depth = d.depth_metres(frame), labels = d.labels_image(frame);
  const Pose object_from_camera = pose.inverse() * d.groundtruth[frame].pose;
  std::vector<Eigen::Vector3d> out;
  for (int v = 0; v < depth.rows; ++v)
    for (int u = 0; u < depth.cols; ++u) {
      if (labels.at<uint16_t>(v, u) != id) continue;
      const double z = depth.at<float>(v, u);
      // Ideal sensor: the renderer zeroes depth only where nothing is labelled.
      EXPECT_GT(z, 0.0) << "labelled pixel without depth at " << u << "," << v;
      if (z > 0)
        out.push_back(object_from_camera *
                      Eigen::Vector3d((u - c.cx) * z / c.fx, (v - c.cy) * z / c.fy, z));
    }
  return out;
}

int inside(const std::vector<Eigen::Vector3d>& points, Eigen::AlignedBox3d box, double margin) {
  box.min().array() -= margin;
  box.max().array() += margin;
  int n = 0;
  for (const auto& p : points) n += box.contains(p);
  return n;
}

TEST(SimMeshProps, ChairAndDeskLabelsAgreeWithDepthAndPoseAndComeFromTheMesh) {
  const Dataset mesh = read_dataset(render_small(props_render(24, 320, true, true)));
  const Dataset primitive = read_dataset(render_small(props_render(1, 160, true, false)));
  int chair_frames = 0, desk_frames = 0, chair_pixels = 0, beyond_primitive = 0;
  for (const auto& [id, info] : mesh.objects) {
    if (info.class_name != "chair" && info.class_name != "desk") continue;
    const bool chair = info.class_name == "chair";
    const Eigen::AlignedBox3d primitive_extent = primitive.object(info.name).extent;
    EXPECT_EQ(info.asset, chair                       ? "office_chair"
                          : info.name == "desk_stage" ? "table"
                                                      : "desk")
        << info.name;
    EXPECT_EQ(primitive.object(info.name).asset, "") << info.name;
    EXPECT_TRUE(info.extent.contains(primitive_extent)) << info.name;
    for (size_t f = 0; f < mesh.frames.size(); f += 3) {
      const Pose pose = chair ? mesh.object_poses[f].at(id).pose : info.pose;
      const std::vector<Eigen::Vector3d> points = labelled_points(mesh, f, id, pose);
      if (points.size() < 50) continue;
      (chair ? chair_frames : desk_frames)++;
      EXPECT_EQ(inside(points, info.extent, 0.03), static_cast<int>(points.size()))
          << info.name << " frame " << f;
      // A wrong pose must not fit: shifted by more than the prop's depth.
      Pose shifted = pose;
      shifted.translation() += pose.linear().col(0) * (info.extent.sizes().x() + 0.3);
      EXPECT_LT(inside(labelled_points(mesh, f, id, shifted), info.extent, 0.03),
                0.9 * points.size())
          << info.name << " frame " << f;
      if (chair) {
        // The office chair's five-legged base, taller backrest and armrests
        // reach beyond the primitive chair: those pixels are the mesh's.
        chair_pixels += static_cast<int>(points.size());
        beyond_primitive +=
            static_cast<int>(points.size()) - inside(points, primitive_extent, 0.03);
      }
    }
  }
  EXPECT_GE(chair_frames, 8) << "the chairs must be seen";
  EXPECT_GE(desk_frames, 6) << "the desk must be seen";
  EXPECT_GT(beyond_primitive, chair_pixels / 20)
      << "chair labels must come from the mesh (" << beyond_primitive << " of " << chair_pixels
      << " px outside the primitive chair)";
}

TEST(SimMeshProps, PhysicsAndTruthDoNotChange) {
  const std::string mesh = render_small(props_render(100, 160, true, true));
  const std::string primitive = render_small(props_render(100, 160, true, false));
  // The pushed chair slides exactly as before: the meshes have no contacts
  // and no mass.
  EXPECT_EQ(file_text(mesh + "/object_poses.txt"), file_text(primitive + "/object_poses.txt"));
  EXPECT_EQ(file_text(mesh + "/groundtruth.txt"), file_text(primitive + "/groundtruth.txt"));
  const Dataset d = read_dataset(mesh);
  const int pushed = d.object("chair_pushed").id;
  EXPECT_GT(translation_between(d.object_poses.back().at(pushed).pose,
                                d.object_poses.front().at(pushed).pose),
            0.3);
  EXPECT_EQ(dataset::read_info(mesh).value().props_style, "mesh");
}

TEST(SimMeshProps, SameSeedGivesByteIdenticalDatasetsAndMeshIsTheDefault) {
  const std::string a = render_small(props_render(8, 160, false, true, 42));
  const std::string b = render_small(props_render(8, 160, false, true, 42));
  EXPECT_EQ(compare_trees(a, b), "");
  // Mesh props are the default, and the style really changes the pictures.
  SmallRender by_default = props_render(8, 160, false, true, 42);
  by_default.set.clear();
  EXPECT_EQ(compare_trees(a, render_small(by_default)), "");
  const std::string p = render_small(props_render(8, 160, false, false, 42));
  EXPECT_NE(compare_trees(a, p), "");
}

// The segmentation pass labels what the colour pass draws: a chair whose
// meshes are hidden as well as its primitives labels no pixel at all.
TEST(SimMeshProps, HiddenGeomsLabelNoPixels) {
  sim::Scenario s =
      sim::load_scenario(scenario_path("depot_walking_xyz"), {{"props_style", "mesh"}});
  sim::scale_camera(s.camera, 160);
  sim::World world(sim::build_scene(s.layout,
                                    sim::ClassTable::load(s.classes_path), s, s.camera));
  sim::Renderer renderer(world.model(), world.camera_id(), s.camera, sim::GlBackend::kOsMesa,
                         world.geom_instances(), world.skin_instances());
  const sim::Instance* chair = nullptr;
  for (const auto& inst : world.instances())
    if (inst.name == "chair_a") chair = &inst;
  ASSERT_NE(chair, nullptr);
  // From behind the chair (it faces -y), above its backrest.
  const Eigen::Vector3d target = chair->pose * Eigen::Vector3d(0, 0, 0.5);
  const Eigen::Vector3d from = target + Eigen::Vector3d(0, 1.1, 0.7);
  world.set_camera_pose(make_pose(sim::look_at_rotation(from, target), from));
  auto chair_pixels = [&] {
    sim::RenderedFrame frame;
    renderer.render(world.data(), frame);
    return cv::countNonZero(frame.instance == chair->id);
  };
  EXPECT_GT(chair_pixels(), 1000) << "the mesh chair fills much of the 160x120 view";
  mjModel* m = const_cast<mjModel*>(world.model());
  const int body = mj_name2id(m, mjOBJ_BODY, "pushable/chair_a");
  int hidden = 0;
  for (int g = 0; g < m->ngeom; ++g)
    if (m->geom_bodyid[g] == body && m->geom_type[g] == mjGEOM_MESH) {
      m->geom_group[g] = 3;
      ++hidden;
    }
  EXPECT_EQ(hidden, 3);
  EXPECT_EQ(chair_pixels(), 0) << "hidden primitive geoms must not label pixels";
}

}  // namespace
}  // namespace depot::test
