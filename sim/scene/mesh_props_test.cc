// Mesh props (props_style: mesh): the catalogue's office chair, desk and
// table scaled and placed over the primitive furniture, each model loaded and
// encoded once per scene, and visual only: the compiled bodies keep their
// mass, inertia and contacts.
#include "sim/scene/mesh_props.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/config_path.h"
#include "common/error.h"
#include "common/testing/error_of.h"
#include "sim/scenario/scenario_loader.h"
#include "sim/scene/depot_objects.h"
#include "sim/scene/scene_model.h"
#include "sim/world/world.h"

namespace depot::sim {
namespace {

const std::string kWalking = std::string(DEPOT_SOURCE_DIR) + "/scenarios/depot_walking_xyz.yaml";

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

struct Props {
  ClassTable classes = ClassTable::load(project_file("scenes/classes.yaml"));
  LazyAssetCatalog catalog{classes, project_file("assets/catalog.yaml")};
  MeshProps props{catalog};
};

SceneModel scene_of(const Scenario& s) {
  return build_scene(s.layout, ClassTable::load(s.classes_path), s,
                     s.camera);
}

const Instance& instance(const SceneModel& scene, const std::string& name) {
  for (const Instance& inst : scene.instances)
    if (inst.name == name) return inst;
  ADD_FAILURE() << "no instance " << name;
  return scene.instances.front();
}

TEST(MeshProps, ChairSeatIsAtThePrimitiveSeatHeight) {
  Props p;
  // The Quaternius office chair at the catalogue's 0.01 m per unit: its
  // cushion's top is 0.495 m above the floor, the primitive seat 0.46 m.
  const double s = p.props.chair_scale();
  EXPECT_NEAR(kChairSeatHeight / s, 0.495, 0.002);
  EXPECT_NEAR(s, 0.929, 0.002);
  const PropGeoms chair = p.props.chair();
  EXPECT_NEAR(chair.bounds.min().z(), 0.0, 1e-9);
  EXPECT_NEAR(chair.bounds.max().z(), 1.128 * s, 0.002);
  // It faces +x like the primitive chair: the backrest and its tilt are behind.
  EXPECT_LT(chair.bounds.min().x(), -0.38);
  EXPECT_GT(chair.bounds.max().x(), 0.3);
  EXPECT_EQ(count(chair.xml, "<geom type=\"mesh\""), 3u);
  EXPECT_EQ(count(chair.xml, "contype=\"0\" conaffinity=\"0\" density=\"0\""), 3u);
  EXPECT_EQ(p.props.models_loaded(), 1u);
}

TEST(MeshProps, DesksFitThePrimitiveTopAndShareTheirMeshes) {
  Props p;
  SceneObject desk;
  desk.type = "desk";
  desk.name = "d";
  desk.length = 1.6;
  for (const std::string model : {"", "table"}) {
    desk.model = model;
    const PropGeoms g = p.props.desk(desk, "test");
    EXPECT_NEAR(g.bounds.min().x(), -kDeskDepth / 2, 1e-6) << model;
    EXPECT_NEAR(g.bounds.max().x(), kDeskDepth / 2, 1e-6) << model;
    EXPECT_NEAR(g.bounds.min().y(), -0.8, 1e-6) << model;
    EXPECT_NEAR(g.bounds.max().y(), 0.8, 1e-6) << model;
    EXPECT_NEAR(g.bounds.min().z(), 0.0, 1e-6) << model;
    EXPECT_NEAR(g.bounds.max().z(), kDeskTopHeight, 1e-6) << model;
    // Turned half round: its front (the desk's drawers) faces -x.
    EXPECT_THAT(g.xml, ::testing::HasSubstr("quat=\"0 0 0 1\"")) << model;
  }
  EXPECT_EQ(p.props.models_loaded(), 2u);
  // Another desk of the same size shares its meshes; another length adds
  // scaled <mesh> elements reading the same files.
  desk.model = "";
  const std::string same = p.props.desk(desk, "test").xml;
  desk.length = 1.8;
  const std::string longer = p.props.desk(desk, "test").xml;
  EXPECT_NE(same, longer);
  EXPECT_EQ(p.props.models_loaded(), 2u);
  std::vector<std::pair<std::string, std::string>> files;
  p.props.append_files(files);
  EXPECT_EQ(files.size(), 10u + 2u) << "desk: 10 meshes, table: 2, each encoded once";
  EXPECT_EQ(count(p.props.asset_xml(), "<mesh "), 2 * 10u + 2u);
  EXPECT_EQ(count(p.props.asset_xml(), "<material "), 2u + 2u);
}

TEST(MeshProps, DeskModelMustBeACatalogueDesk) {
  Props p;
  SceneObject desk;
  desk.type = "desk";
  desk.name = "d";
  desk.model = "office_chair";
  std::string error = error_of([&] { p.props.desk(desk, "depot.yaml: object 'd'"); });
  EXPECT_NE(error.find("depot.yaml: object 'd': model 'office_chair' plays class 'chair'"),
            std::string::npos)
      << error;
  desk.model = "sofa";
  error = error_of([&] { p.props.desk(desk, "depot.yaml: object 'd'"); });
  EXPECT_THAT(error, ::testing::HasSubstr("model 'sofa' is not in the asset catalogue")) << error;
}

TEST(MeshProps, SceneLoadsEachModelOnceAndKeepsThePhysics) {
  const SceneModel primitive = scene_of(load_scenario(kWalking, {{"props_style", "primitive"}}));
  SceneModel mesh = scene_of(load_scenario(kWalking, {{"props_style", "mesh"}}));
  EXPECT_EQ(count(primitive.xml, "type=\"mesh\""), 0u);
  EXPECT_EQ(count(primitive.xml, "prop_"), 0u);
  // Three chairs of 3 meshes, desk_office (the desk, 10) and desk_stage (the
  // table, 2, as scenes/depot.yaml names it).
  EXPECT_EQ(count(mesh.xml, "<geom type=\"mesh\""), 3u * 3u + 10u + 2u);
  EXPECT_EQ(count(mesh.xml, "<mesh "), 3u + 10u + 2u);
  EXPECT_EQ(count(mesh.xml, "mesh=\"prop_office_chair_s0_mesh0\""), 3u);
  size_t msh = 0;
  for (const auto& [name, bytes] : mesh.assets)
    msh += name.size() > 4 && name.substr(name.size() - 4) == ".msh";
  EXPECT_EQ(msh, 3u + 10u + 2u);

  // Extents cover the meshes (and still the primitives).
  for (const std::string name : {"chair_a", "chair_pushed", "desk_office", "desk_stage"}) {
    const Instance& a = instance(primitive, name);
    const Instance& b = instance(mesh, name);
    EXPECT_TRUE(b.extent.contains(a.extent)) << name;
  }
  EXPECT_NEAR(instance(mesh, "chair_a").extent.max().z(), 1.048, 0.003);
  EXPECT_EQ(instance(mesh, "chair_a").asset, "office_chair");
  EXPECT_EQ(instance(mesh, "desk_stage").asset, "table");
  EXPECT_EQ(instance(mesh, "desk_office").asset, "desk");
  EXPECT_EQ(instance(mesh, "desk_stage_monitor").asset, "");
  EXPECT_EQ(instance(primitive, "chair_a").asset, "");
  EXPECT_NEAR(instance(mesh, "desk_stage").extent.max().z(), 0.78, 1e-6) << "the papers on top";

  // Compiled: the same masses and inertias, the primitives hidden but
  // colliding, the meshes without contacts.
  World a(scene_of(load_scenario(kWalking)));
  World b(std::move(mesh));
  const mjModel* ma = a.model();
  const mjModel* mb = b.model();
  EXPECT_EQ(ma->nbody, mb->nbody);
  for (const std::string name : {"chair_a", "chair_pushed", "desk_stage"}) {
    const std::string body =
        std::string(name.rfind("chair", 0) == 0 ? "pushable/" : "static/") + name;
    const int ba = mj_name2id(ma, mjOBJ_BODY, body.c_str());
    const int bb = mj_name2id(mb, mjOBJ_BODY, body.c_str());
    ASSERT_GE(ba, 0);
    ASSERT_GE(bb, 0);
    EXPECT_EQ(ma->body_mass[ba], mb->body_mass[bb]) << name;
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(ma->body_inertia[3 * ba + k], mb->body_inertia[3 * bb + k]) << name;
      EXPECT_EQ(ma->body_ipos[3 * ba + k], mb->body_ipos[3 * bb + k]) << name;
    }
    int colliding_a = 0, colliding_b = 0, meshes = 0, shown_primitives = 0;
    for (int g = 0; g < ma->ngeom; ++g)
      if (ma->geom_bodyid[g] == ba) colliding_a += ma->geom_contype[g] || ma->geom_conaffinity[g];
    for (int g = 0; g < mb->ngeom; ++g) {
      if (mb->geom_bodyid[g] != bb) continue;
      if (mb->geom_type[g] == mjGEOM_MESH) {
        ++meshes;
        EXPECT_EQ(mb->geom_contype[g], 0);
        EXPECT_EQ(mb->geom_conaffinity[g], 0);
        EXPECT_EQ(mb->geom_group[g], 0);
        continue;
      }
      colliding_b += mb->geom_contype[g] || mb->geom_conaffinity[g];
      // Hidden: a group the renderer leaves out (mjv_defaultOption shows 0-2).
      if (mb->geom_group[g] != 3 || mb->geom_rgba[4 * g + 3] != 0.0f) ++shown_primitives;
    }
    EXPECT_EQ(colliding_a, colliding_b) << name;
    EXPECT_GT(meshes, 0) << name;
    // A desk keeps its papers; a chair shows no primitive at all.
    EXPECT_EQ(shown_primitives, name == "desk_stage" ? 1 : 0) << name;
  }
}

}  // namespace
}  // namespace depot::sim
