// MuJoCo encoding: the .msh layout, a real person through MuJoCo 2.2's VFS
// and compiler (vertex counts, where the vertices end up after MuJoCo
// re-centres them), per-frame vertex writes, and two renders that pin down
// MuJoCo's texture orientation and what its segmentation pass draws.
#include "sim/assets/mujoco_mesh.h"

#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <memory>

#include "common/testing/error_of.h"
#include "sim/assets/skinning.h"
#include "sim/assets/testing/asset_fixtures.h"
#include "sim/assets/testing/cpu_skinning.h"
#include "sim/render/gl_context.h"

namespace depot::sim {
namespace {

using testing::worker;

constexpr double kPi = 3.14159265358979323846;

// A compiled MJCF whose files come from memory, like World does it.
struct Compiled {
  mjModel* model = nullptr;
  mjData* data = nullptr;
  std::string error;
  ~Compiled() {
    if (data) mj_deleteData(data);
    if (model) mj_deleteModel(model);
  }
};

std::unique_ptr<Compiled> compile(const std::string& xml,
                                  const std::vector<std::pair<std::string, std::string>>& files) {
  auto out = std::make_unique<Compiled>();
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  auto add = [&](const std::string& name, const std::string& bytes) {
    EXPECT_EQ(mj_makeEmptyFileVFS(&vfs, name.c_str(), static_cast<int>(bytes.size())), 0) << name;
    std::memcpy(vfs.filedata[mj_findFileVFS(&vfs, name.c_str())], bytes.data(), bytes.size());
  };
  for (const auto& [name, bytes] : files) add(name, bytes);
  add("model.xml", xml);
  char error[1000] = "";
  out->model = mj_loadXML("model.xml", &vfs, error, sizeof(error));
  mj_deleteVFS(&vfs);
  out->error = error;
  if (out->model) {
    out->data = mj_makeData(out->model);
    mj_forward(out->model, out->data);
  }
  return out;
}

// World position of vertex v of mesh geom g: geom_xpos + geom_xmat * mesh_vert.
Eigen::Vector3d world_vertex(const mjModel* m, const mjData* d, int g, int v) {
  const float* p = m->mesh_vert + 3 * (m->mesh_vertadr[m->geom_dataid[g]] + v);
  Eigen::Matrix3d r;
  for (int i = 0; i < 9; ++i) r(i / 3, i % 3) = d->geom_xmat[9 * g + i];
  return Eigen::Vector3d(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]) +
         r * Eigen::Vector3d(p[0], p[1], p[2]);
}

// The actor's body pose in the test scenes.
const Eigen::Isometry3d kBody = [] {
  Eigen::Isometry3d b = Eigen::Isometry3d::Identity();
  b.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  b.translation() = Eigen::Vector3d(1.0, -2.0, 0.0);
  return b;
}();

std::string person_xml(const MujocoAssetSet& set) {
  const Eigen::Quaterniond q(kBody.linear());
  std::ostringstream x;
  x << "<mujoco><compiler angle=\"radian\"/><asset>\n"
    << set.asset_xml << "</asset><worldbody>\n"
    << "<body name=\"actor\" mocap=\"true\" pos=\"" << kBody.translation().transpose()
    << "\" quat=\"" << q.w() << " " << q.x() << " " << q.y() << " " << q.z() << "\">\n"
    << mesh_geoms_xml(set) << "</body></worldbody></mujoco>\n";
  return x.str();
}

TEST(MujocoMesh, MshLayoutIsHeaderThenArrays) {
  const std::vector<Eigen::Vector3f> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<Eigen::Vector3f> n(4, Eigen::Vector3f(0, 0, 1));
  const std::vector<Eigen::Vector2f> uv = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  const std::vector<Eigen::Vector3i> f = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const std::string msh = encode_msh(p, n, uv, f, "tetra");
  ASSERT_EQ(msh.size(), 4 * 4 + 4 * (3 * 4 + 3 * 4 + 2 * 4 + 3 * 4));
  int32_t header[4];
  std::memcpy(header, msh.data(), sizeof(header));
  EXPECT_EQ(header[0], 4);
  EXPECT_EQ(header[1], 4);
  EXPECT_EQ(header[2], 4);
  EXPECT_EQ(header[3], 4);
  float v1[3];
  std::memcpy(v1, msh.data() + 16 + 12, sizeof(v1));  // vertex 1
  EXPECT_EQ(v1[0], 1.0f);
  int32_t last_face[3];
  std::memcpy(last_face, msh.data() + msh.size() - 12, sizeof(last_face));
  EXPECT_EQ(last_face[2], 3);
  // Without normals and UVs the counts say 0 and the arrays are absent.
  EXPECT_EQ(encode_msh(p, {}, {}, f, "tetra").size(), 16u + 4 * (3 * 4 + 3 * 4));
  EXPECT_EQ(error_of([&] {
              encode_msh({p[0], p[1], p[2]}, {}, {}, {{0, 1, 2}}, "tri");
            }),
            "tri: MuJoCo meshes need at least 4 vertices, this one has 3");
  EXPECT_EQ(error_of([&] {
              encode_msh(p, {}, {}, {{0, 1, 4}}, "tetra");
            }),
            "tetra: triangle index out of range");
}

TEST(MujocoMesh, PersonCompilesInMujocoWithEveryVertexWhereItWasPut) {
  const AssetModel& m = worker();
  const MujocoAssetSet set = encode_for_mujoco(m, "worker");
  auto c = compile(person_xml(set), set.files);
  ASSERT_NE(c->model, nullptr) << c->error;
  const mjModel* mm = c->model;
  ASSERT_EQ(mm->nmesh, static_cast<int>(m.meshes.size()));
  ASSERT_EQ(mm->ngeom, static_cast<int>(m.meshes.size()));
  EXPECT_EQ(mm->ntex, 5);
  for (int t = 0; t < mm->ntex; ++t) EXPECT_GE(mm->tex_width[t], 256);
  Eigen::AlignedBox3d box;
  for (int g = 0; g < mm->ngeom; ++g) {
    const AssetMesh& mesh = m.meshes[g];
    const int id = mm->geom_dataid[g];
    ASSERT_EQ(mm->mesh_vertnum[id], static_cast<int>(mesh.positions.size())) << mesh.name;
    EXPECT_EQ(mm->mesh_facenum[id], static_cast<int>(mesh.triangles.size())) << mesh.name;
    EXPECT_GE(mm->mesh_texcoordadr[id], 0) << mesh.name;
    EXPECT_GE(mm->geom_matid[g], 0) << mesh.name;
    // MuJoCo moved the mesh to its centre of mass (geom_pos) ...
    EXPECT_GT(Eigen::Map<const Eigen::Vector3d>(mm->geom_pos + 3 * g).norm(), 0.05);
    // ... but vertex i still lands where the model put it, with its normal
    // (turned into the geom frame) and its UV.
    const Eigen::Matrix3d geom_rotation = geom_in_body(mm, g).linear();
    for (size_t v = 0; v < mesh.positions.size(); v += 7) {
      const Eigen::Vector3d expected = kBody * mesh.positions[v].cast<double>();
      ASSERT_LT((world_vertex(mm, c->data, g, static_cast<int>(v)) - expected).norm(), 1e-5)
          << mesh.name << " vertex " << v;
      const float* n = mm->mesh_normal + 3 * (mm->mesh_vertadr[id] + v);
      ASSERT_LT((geom_rotation * Eigen::Vector3d(n[0], n[1], n[2]) - mesh.normals[v].cast<double>())
                    .norm(),
                1e-4)
          << mesh.name << " normal " << v;
      const float* uv = mm->mesh_texcoord + 2 * (mm->mesh_texcoordadr[id] + v);
      ASSERT_EQ(Eigen::Vector2f(uv[0], uv[1]), mesh.uvs[v]) << mesh.name << " uv " << v;
    }
    for (size_t v = 0; v < mesh.positions.size(); ++v)
      box.extend(world_vertex(mm, c->data, g, static_cast<int>(v)));
  }
  EXPECT_NEAR(box.min().z(), 0.0, 1e-5);
  EXPECT_NEAR(box.max().z(), m.bounds.max().z(), 1e-5);
  EXPECT_NEAR(box.sizes().head<2>().norm(),
              (kBody.linear().cast<float>() * m.bounds.sizes()).head<2>().norm(), 0.3);
}

TEST(MujocoMesh, WrittenVerticesFollowTheGeomFrame) {
  const AssetModel& m = worker();
  const MujocoAssetSet set = encode_for_mujoco(m, "worker");
  auto c = compile(person_xml(set), set.files);
  ASSERT_NE(c->model, nullptr) << c->error;
  SkeletonPose pose = rest_pose(m.skeleton);
  turn_bone(m.skeleton, pose, find_bone(m.skeleton, "thigh_l"),
            Eigen::Quaterniond(Eigen::AngleAxisd(-kPi / 3, Eigen::Vector3d::UnitY())));
  std::vector<Eigen::Affine3d> globals, matrices;
  bone_globals(m.skeleton, pose, globals);
  testing::skinning_matrices(m.skeleton, globals, matrices);
  std::vector<Eigen::Vector3f> p, n;
  for (int g = 0; g < c->model->ngeom; ++g) {
    testing::skin_mesh(m.meshes[g], matrices, p, n);
    write_mesh_vertices(c->model, g, p, n);
    for (size_t v = 0; v < p.size(); v += 5)
      ASSERT_LT(
          (world_vertex(c->model, c->data, g, static_cast<int>(v)) - kBody * p[v].cast<double>())
              .norm(),
          1e-5);
    // Normals turn with the geom frame too.
    const float* nv = c->model->mesh_normal + 3 * c->model->mesh_vertadr[c->model->geom_dataid[g]];
    const Eigen::Vector3d n0 =
        geom_in_body(c->model, g).linear() * Eigen::Vector3d(nv[0], nv[1], nv[2]);
    EXPECT_LT((n0 - n[0].cast<double>()).norm(), 1e-5);
  }
  p.pop_back();
  n.pop_back();
  EXPECT_NE(error_of([&] { write_mesh_vertices(c->model, 0, p, n); }).find("vertices, got"),
            std::string::npos);
}

// --- renders (OSMesa): what MuJoCo 2.2.2 does with textures and skins.

struct Shot {
  std::vector<unsigned char> rgb, seg;  // bottom-up rows
  int width = 0, height = 0;
  std::vector<mjvGeom> geoms;
  cv::Vec3b colour(int x, int y_from_top) const {
    const size_t i = 3 * (static_cast<size_t>(height - 1 - y_from_top) * width + x);
    return cv::Vec3b(rgb[i], rgb[i + 1], rgb[i + 2]);  // R, G, B
  }
  // The scene geom drawn at a pixel, or nullptr.
  const mjvGeom* geom_at(int x, int y_from_top) const {
    const size_t i = 3 * (static_cast<size_t>(height - 1 - y_from_top) * width + x);
    const int id = seg[i] | (seg[i + 1] << 8) | (seg[i + 2] << 16);
    return id > 0 && id <= static_cast<int>(geoms.size()) ? &geoms[id - 1] : nullptr;
  }
};

Shot render(const mjModel* m, mjData* d, int size) {
  static std::unique_ptr<GlContext> gl = GlContext::create(GlBackend::kOsMesa, 128, 128);
  gl->make_current();
  mjvScene scn;
  mjvCamera cam;
  mjvOption opt;
  mjrContext con;
  mjv_defaultScene(&scn);
  mjv_defaultCamera(&cam);
  mjv_defaultOption(&opt);
  mjr_defaultContext(&con);
  mjv_makeScene(m, &scn, 100);
  mjr_makeContext(m, &con, mjFONTSCALE_50);
  mjr_setBuffer(mjFB_OFFSCREEN, &con);
  cam.type = mjCAMERA_FIXED;
  cam.fixedcamid = 0;
  mjv_updateScene(m, d, &opt, nullptr, &cam, mjCAT_ALL, &scn);
  const mjrRect viewport{0, 0, size, size};
  Shot shot;
  shot.width = shot.height = size;
  shot.rgb.resize(3 * size * size);
  shot.seg.resize(3 * size * size);
  mjr_render(viewport, &scn, &con);
  mjr_readPixels(shot.rgb.data(), nullptr, viewport, &con);
  scn.flags[mjRND_SEGMENT] = scn.flags[mjRND_IDCOLOR] = 1;
  mjr_render(viewport, &scn, &con);
  mjr_readPixels(shot.seg.data(), nullptr, viewport, &con);
  shot.geoms.assign(scn.geoms, scn.geoms + scn.ngeom);
  mjr_freeContext(&con);
  mjv_freeScene(&scn);
  return shot;
}

// An explicit extent: MuJoCo derives the far clipping plane from it, and a
// model whose only visible thing is a skin (which the extent ignores) would
// otherwise be clipped away.
const char* kCamera =
    "<visual><global offwidth=\"128\" offheight=\"128\"/>"
    "<headlight ambient=\"1 1 1\" diffuse=\"0 0 0\" specular=\"0 0 0\"/></visual>"
    "<statistic extent=\"2\" center=\"0 0 0.5\"/>";

TEST(MujocoRender, TexturesAreSampledFromTheImageTopAtVZero) {
  // A thin box facing the camera (+x), its front face mapped with the
  // loader's convention: v = 0 at the top edge. The texture is red above,
  // blue below.
  AssetModel model;
  model.source = "quad";
  AssetMaterial mat;
  mat.name = "paint";
  mat.texture = cv::Mat(64, 64, CV_8UC3, cv::Scalar(0, 0, 255));
  mat.texture(cv::Rect(0, 32, 64, 32)) = cv::Scalar(255, 0, 0);
  model.materials.push_back(mat);
  AssetMesh mesh;
  mesh.material = 0;
  for (float x : {0.01f, -0.01f})
    for (const auto& [y, z] : {std::pair{-0.5f, 0.f}, {0.5f, 0.f}, {0.5f, 1.f}, {-0.5f, 1.f}}) {
      mesh.positions.emplace_back(x, y, z);
      mesh.normals.emplace_back(x > 0 ? 1.f : -1.f, 0.f, 0.f);
      mesh.uvs.emplace_back(0.5f + y, 1.0f - z);
    }
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 7, 6}, {0, 5, 1}, {0, 4, 5},
                    {3, 2, 6}, {3, 6, 7}, {0, 3, 7}, {0, 7, 4}, {1, 5, 6}, {1, 6, 2}};
  model.meshes.push_back(mesh);
  const MujocoAssetSet set = encode_for_mujoco(model, "quad");
  const std::string xml = std::string("<mujoco>") + kCamera + "<asset>" + set.asset_xml +
                          "</asset><worldbody><camera pos=\"2.5 0 0.5\" xyaxes=\"0 1 0 0 0 1\" "
                          "fovy=\"45\"/><body mocap=\"true\">" +
                          mesh_geoms_xml(set) + "</body></worldbody></mujoco>";
  auto c = compile(xml, set.files);
  ASSERT_NE(c->model, nullptr) << c->error;
  const Shot shot = render(c->model, c->data, 128);
  const cv::Vec3b top = shot.colour(64, 40), bottom = shot.colour(64, 85);
  EXPECT_GT(top[0], 200) << "top is not red";
  EXPECT_LT(top[2], 50);
  EXPECT_GT(bottom[2], 200) << "bottom is not blue";
  EXPECT_LT(bottom[0], 50);
  ASSERT_NE(shot.geom_at(64, 64), nullptr);
  EXPECT_EQ(shot.geom_at(64, 64)->objtype, mjOBJ_GEOM);
}

TEST(MujocoRender, SkinsAreDrawnInTheSegmentationPassAsSkinObjects) {
  // MuJoCo 2.2's <skin> (an asset in 2.x) bound to one mocap body: it shows
  // in the segmentation pass with its own segid, but as object type
  // mjOBJ_SKIN with the skin's id, not as a geom, so a label lookup that
  // only knows geoms (sim/render/renderer.cc today) would read it as
  // background.
  const std::string xml = std::string("<mujoco>") + kCamera +
                          "<asset><skin name=\"sk\" rgba=\"0 1 0 1\" "
                          "vertex=\"0 -0.3 0.2  0 0.3 0.2  0 0.3 0.8  0 -0.3 0.8  -0.1 0 0.5\" "
                          "face=\"0 1 2  0 2 3  0 4 1  1 4 2  2 4 3  3 4 0\">"
                          "<bone body=\"b\" bindpos=\"0 0 0\" bindquat=\"1 0 0 0\" "
                          "vertid=\"0 1 2 3 4\" vertweight=\"1 1 1 1 1\"/></skin></asset>"
                          "<worldbody><camera pos=\"2.5 0 0.5\" xyaxes=\"0 1 0 0 0 1\" "
                          "fovy=\"45\"/><body name=\"b\" mocap=\"true\"><geom type=\"sphere\" "
                          "size=\"0.01\" rgba=\"0 0 0 0\"/></body></worldbody></mujoco>";
  auto c = compile(xml, {});
  ASSERT_NE(c->model, nullptr) << c->error;
  ASSERT_EQ(c->model->nskin, 1);
  const Shot shot = render(c->model, c->data, 128);
  EXPECT_GT(shot.colour(64, 64)[1], 200);  // drawn green in the colour pass
  const mjvGeom* g = shot.geom_at(64, 64);
  ASSERT_NE(g, nullptr) << "skin missing from the segmentation pass";
  EXPECT_EQ(g->type, mjGEOM_SKIN);
  EXPECT_EQ(g->objtype, mjOBJ_SKIN);
  EXPECT_EQ(g->objid, 0);
}

}  // namespace
}  // namespace depot::sim
