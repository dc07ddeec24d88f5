// The asset loader on the real shared models: units and axes, textures,
// alpha cut-out, colours, external clips, and every bad input.
#include "sim/assets/asset_loader.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "common/testing/error_of.h"
#include "sim/assets/alpha_cutout.h"
#include "sim/assets/skinning.h"
#include "sim/assets/testing/asset_fixtures.h"

namespace depot::sim {
namespace {

using testing::person_options;
using testing::scratch_file;
using testing::shared_asset;
using testing::worker;

const AssetMesh& mesh_with_material(const AssetModel& m, const std::string& material) {
  for (const auto& mesh : m.meshes)
    if (mesh.material >= 0 && m.materials[mesh.material].name == material) return mesh;
  throw std::runtime_error("no mesh with material " + material);
}

Eigen::Vector3f centroid(const AssetMesh& mesh) {
  Eigen::Vector3f c = Eigen::Vector3f::Zero();
  for (const auto& p : mesh.positions) c += p;
  return c / static_cast<float>(mesh.positions.size());
}

Eigen::Vector3d joint(const AssetModel& m, const std::string& bone) {
  const int b = find_bone(m.skeleton, bone);
  EXPECT_GE(b, 0) << bone;
  return rest_joint_position(m.skeleton, b);
}

TEST(AssetLoader, PersonStandsOnTheFloorInMetresFacingX) {
  const AssetModel& m = worker();
  // MakeHuman worker: 1.79 m to the top of the hair, feet on the floor.
  EXPECT_NEAR(m.bounds.min().z(), 0.0, 1e-5);
  EXPECT_GT(m.bounds.max().z(), 1.6);
  EXPECT_LT(m.bounds.max().z(), 1.9);
  EXPECT_DOUBLE_EQ(m.scale, 1.0);
  // Facing +x: the eyes are in front of the head joint; its left (+y) side
  // carries the left leg.
  const Eigen::Vector3f eyes = centroid(mesh_with_material(m, "high-poly"));
  const Eigen::Vector3d head = joint(m, "head");
  EXPECT_GT(eyes.x() - head.x(), 0.05);
  EXPECT_NEAR(eyes.y(), head.y(), 0.01);
  EXPECT_GT(joint(m, "thigh_l").y(), 0.05);
  EXPECT_LT(joint(m, "thigh_r").y(), -0.05);
  EXPECT_GT(joint(m, "head").z(), joint(m, "pelvis").z() + 0.5);
  // The file's origin stays under the body (not the bounding box centre,
  // which the A-pose arms and the feet pull away).
  EXPECT_NEAR(joint(m, "pelvis").x(), 0.0, 0.05);
  EXPECT_NEAR(joint(m, "pelvis").y(), 0.0, 0.01);
}

TEST(AssetLoader, PersonHasTheFiftyThreeJointSkinAndItsClip) {
  const AssetModel& m = worker();
  for (const char* bone : {"Root", "pelvis", "spine_01", "spine_03", "neck_01", "head", "thigh_l",
                           "calf_l", "foot_l", "ball_l", "upperarm_r", "hand_r", "index_03_l"})
    EXPECT_GE(find_bone(m.skeleton, bone), 0) << bone;
  int deforming = 0;
  for (const auto& b : m.skeleton.bones) deforming += b.deforms;
  EXPECT_GE(deforming, 50);
  for (const auto& mesh : m.meshes) {
    ASSERT_EQ(mesh.bones.size(), mesh.positions.size()) << mesh.name;
    for (const auto& vb : mesh.bones) {
      float sum = 0;
      for (int k = 0; k < 4; ++k) {
        EXPECT_LT(vb.bone[k], static_cast<int>(m.skeleton.bones.size()));
        if (vb.bone[k] >= 0) sum += vb.weight[k];
      }
      ASSERT_NEAR(sum, 1.0f, 1e-5f);
    }
  }
  ASSERT_EQ(m.clips.size(), 1u);
  EXPECT_EQ(m.clips[0].name, "Walk_procedural");
  EXPECT_NEAR(m.clips[0].duration, 1.1, 1e-9);
}

TEST(AssetLoader, PersonMeshesAreBoundToTheirDecodedTextures) {
  const AssetModel& m = worker();
  ASSERT_EQ(m.meshes.size(), 5u);  // body, suit, shoes, hair, eyes
  for (const auto& mesh : m.meshes) {
    ASSERT_GE(mesh.material, 0);
    EXPECT_EQ(mesh.uvs.size(), mesh.positions.size()) << mesh.name;
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size()) << mesh.name;
    EXPECT_FALSE(m.materials[mesh.material].texture.empty()) << mesh.name;
  }
  const AssetMaterial& skin = m.materials[mesh_with_material(m, "body").material];
  EXPECT_EQ(skin.texture.cols, 1024);
  EXPECT_EQ(skin.texture.rows, 1024);
  EXPECT_EQ(skin.texture.type(), CV_8UC3);  // JPEG
  EXPECT_FALSE(skin.alpha_mask);
  const AssetMaterial& hair = m.materials[mesh_with_material(m, "short02").material];
  EXPECT_EQ(hair.texture.type(), CV_8UC4);  // PNG with an alpha mask
  EXPECT_TRUE(hair.texture_has_alpha);
  EXPECT_TRUE(hair.alpha_mask);
  // Skin texels are skin-coloured (red above blue), not a grey default.
  const cv::Scalar mean = cv::mean(skin.texture);
  EXPECT_GT(mean[2], mean[0] + 20);
}

TEST(AssetLoader, UvsHaveTheirOriginAtTheImageTop) {
  // The eye mesh is an eyeball plus a transparent cornea whose UVs land on
  // the only transparent island of the eye texture: with UVs read the right
  // way up, the cornea samples alpha 0; flipped, every triangle samples an
  // opaque texel.
  AssetLoadOptions o = person_options();
  o.cut_alpha = false;
  const AssetModel m = load_asset(shared_asset("people/mh_worker_male.glb"), o);
  const AssetMesh& eyes = mesh_with_material(m, "high-poly");
  const AssetMaterial& mat = m.materials[eyes.material];
  AssetMesh flipped = eyes;
  for (auto& uv : flipped.uvs) uv.y() = 1.0f - uv.y();
  int transparent = 0, transparent_flipped = 0;
  for (size_t t = 0; t < eyes.triangles.size(); ++t) {
    transparent += triangle_alpha(eyes, mat, static_cast<int>(t)) < 0.01f;
    transparent_flipped += triangle_alpha(flipped, mat, static_cast<int>(t)) < 0.01f;
  }
  EXPECT_EQ(transparent, 980);
  EXPECT_EQ(transparent_flipped, 0);
}

TEST(AssetLoader, AlphaMaskedTrianglesAreCut) {
  AssetLoadOptions o = person_options();
  o.cut_alpha = false;
  const AssetModel uncut = load_asset(shared_asset("people/mh_worker_male.glb"), o);
  const AssetModel& cut = worker();
  const AssetMesh& eyes = mesh_with_material(cut, "high-poly");
  EXPECT_EQ(mesh_with_material(uncut, "high-poly").triangles.size() - eyes.triangles.size(), 980u);
  const AssetMesh& hair = mesh_with_material(cut, "short02");
  const AssetMaterial& hair_mat = cut.materials[hair.material];
  EXPECT_LT(hair.triangles.size(), mesh_with_material(uncut, "short02").triangles.size());
  for (size_t t = 0; t < hair.triangles.size(); ++t)
    ASSERT_GE(triangle_alpha(hair, hair_mat, static_cast<int>(t)), hair_mat.alpha_cutoff);
  // Unused vertices went with their triangles; opaque meshes are untouched.
  std::vector<bool> used(hair.positions.size(), false);
  for (const auto& t : hair.triangles)
    for (int k = 0; k < 3; ++k) used[t[k]] = true;
  EXPECT_EQ(std::count(used.begin(), used.end(), false), 0);
  EXPECT_EQ(mesh_with_material(cut, "body").triangles.size(),
            mesh_with_material(uncut, "body").triangles.size());
  // Transparent texels now carry hair colour, not the exporter's black.
  cv::Mat alpha;
  cv::extractChannel(hair_mat.texture, alpha, 3);
  const cv::Scalar clear = cv::mean(hair_mat.texture, alpha < 10);
  EXPECT_GT(clear[0] + clear[1] + clear[2], 60);
}

TEST(AssetLoader, ArbitraryUnitsScaleToTheTargetHeight) {
  AssetLoadOptions o;
  o.up = Axis::kPosY;
  o.forward = Axis::kPosZ;
  o.target_height = 1.55;
  const AssetModel cow = load_asset(shared_asset("animals/farm/Cow.fbx"), o);
  EXPECT_NEAR(cow.bounds.max().z() - cow.bounds.min().z(), 1.55, 1e-4);
  EXPECT_NEAR(cow.bounds.min().z(), 0.0, 1e-5);
  EXPECT_NEAR(1.55 / cow.scale, 514.8, 1.0);  // the file's cow is ~515 units tall
  // Long along x, head forward.
  EXPECT_GT(cow.bounds.sizes().x(), 1.5 * cow.bounds.sizes().y());
  EXPECT_GT(joint(cow, "Head").x(), 0.5);
  EXPECT_LT(joint(cow, "Tail1").x(), -0.5);
  // Clip translations are in metres too: no key further than the cow is big.
  const AnimationClip& walk = cow.clips[find_clip(cow, "Armature|Walk")];
  for (const auto& ch : walk.channels)
    for (const auto& k : ch.translations) ASSERT_LT(k.value.norm(), 3.0) << ch.bone_name;
  // Blender's linear material colours, sRGB-encoded: 0.64 -> 0.82.
  for (const auto& mat : cow.materials)
    if (mat.name == "White") {
      EXPECT_NEAR(mat.rgba[0], 0.82, 0.01);
    }
}

TEST(AssetLoader, ScaleFactorAndAxes) {
  AssetLoadOptions o;
  o.up = Axis::kPosY;
  o.forward = Axis::kPosZ;
  o.scale = 0.01;  // centimetres
  const AssetModel chair = load_asset(shared_asset("props/OfficeChair.fbx"), o);
  EXPECT_NEAR(chair.bounds.max().z(), 1.1276, 1e-3);
  EXPECT_TRUE(chair.skeleton.bones.empty());
  for (const auto& mesh : chair.meshes) EXPECT_TRUE(mesh.bones.empty());
  // The backrest is behind the seat: the chair faces +x.
  double x = 0, n = 0;
  for (const auto& mesh : chair.meshes)
    for (const auto& p : mesh.positions)
      if (p.z() > 0.9) x += p.x(), n += 1;
  EXPECT_LT(x / n, -0.2);
  // Turning the forward axis turns the model: forward = -z faces it back.
  o.forward = Axis::kNegZ;
  const AssetModel back = load_asset(shared_asset("props/OfficeChair.fbx"), o);
  EXPECT_NEAR(back.meshes[0].positions[0].x(), -chair.meshes[0].positions[0].x(), 1e-5);
  EXPECT_NEAR(back.meshes[0].positions[0].y(), -chair.meshes[0].positions[0].y(), 1e-5);
  EXPECT_NEAR(back.meshes[0].positions[0].z(), chair.meshes[0].positions[0].z(), 1e-5);
}

TEST(AssetLoader, ClipsComeFromAnotherFileByBoneName) {
  AssetLoadOptions o;
  o.target_height = 0.6;
  AssetModel dog = load_asset(shared_asset("animals/dog/fox-dog.glb"), o);
  EXPECT_TRUE(dog.clips.empty());
  load_clips_into(dog, shared_asset("animals/dog/fox-animations.glb"), {"Walk", "Idle"}, true);
  ASSERT_EQ(dog.clips.size(), 2u);
  const AnimationClip& walk = dog.clips[find_clip(dog, "Walk")];
  EXPECT_NEAR(walk.duration, 1.0, 1e-6);
  EXPECT_GT(walk.channels.size(), 40u);
  for (const auto& ch : walk.channels) {
    EXPECT_EQ(dog.skeleton.bones[ch.bone].name, ch.bone_name);
    EXPECT_TRUE(ch.translations.empty());
    EXPECT_FALSE(ch.rotations.empty());
  }
  EXPECT_NE(error_of([&] {
              load_clips_into(dog, shared_asset("animals/dog/fox-animations.glb"), {"Fly"}, true);
            }).find("fox-animations.glb: no clip named 'Fly' (clips: Bark, Bite"),
            std::string::npos);
}

// --- bad input: one line naming the file and the problem.

std::string load_error(const std::string& path, const AssetLoadOptions& o = {}) {
  return error_of([&] { load_asset(path, o); }, "(no error)");
}

TEST(AssetLoaderErrors, MissingEmptyCorruptAndUnsupportedFiles) {
  const std::string missing = (testing::scratch_dir() / "nobody.glb").string();
  EXPECT_EQ(load_error(missing), missing + ": model file not found");

  const std::string empty = scratch_file("empty.glb", "");
  EXPECT_EQ(load_error(empty), empty + ": model file is empty");

  const std::string glb = scratch_file("corrupt.glb", std::string("glTF\x02\0\0\0", 8) + "garbage");
  EXPECT_EQ(load_error(glb).rfind(glb + ": cannot read the model: ", 0), 0u) << load_error(glb);

  const std::string fbx =
      scratch_file("corrupt.fbx", std::string("Kaydara FBX Binary  \0", 21) + "\x1a\0 garbage");
  EXPECT_EQ(load_error(fbx).rfind(fbx + ": cannot read the model: ", 0), 0u) << load_error(fbx);

  const std::string stl = scratch_file("model.stl", "solid x\nendsolid x\n");
  EXPECT_EQ(load_error(stl),
            stl + ": unsupported model format '.stl' (expected .glb, .gltf, .fbx or .obj)");

  for (const std::string& e : {load_error(missing), load_error(glb), load_error(fbx)})
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST(AssetLoaderErrors, ModelWithoutFaces) {
  const std::string points = scratch_file("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n");
  EXPECT_EQ(load_error(points), points + ": the model has no triangles");
  const std::string lines = scratch_file("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n");
  EXPECT_EQ(load_error(lines), lines + ": the model has no triangles");
}

const char* kQuadObj =
    "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "usemtl painted\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";

TEST(AssetLoaderErrors, MissingTextureFile) {
  scratch_file("missing_tex/quad.mtl", "newmtl painted\nKd 1 1 1\nmap_Kd paint.png\n");
  const std::string obj = scratch_file("missing_tex/quad.obj", kQuadObj);
  const std::string e = load_error(obj);
  EXPECT_EQ(e.rfind(obj + ": texture 'paint.png' of material 'painted' not found", 0), 0u) << e;
}

TEST(AssetLoader, ExternalTextureBesideTheModel) {
  cv::Mat img(4, 8, CV_8UC3, cv::Scalar(10, 20, 200));
  std::vector<uchar> png;
  cv::imencode(".png", img, png);
  scratch_file("tex/paint.png", std::string(png.begin(), png.end()));
  scratch_file("tex/quad.mtl", "newmtl painted\nKd 1 1 1\nmap_Kd paint.png\n");
  const std::string obj = scratch_file("tex/quad.obj", kQuadObj);
  AssetLoadOptions o;
  o.up = Axis::kPosZ;
  o.forward = Axis::kPosX;
  const AssetModel m = load_asset(obj, o);
  ASSERT_EQ(m.meshes.size(), 1u);
  const AssetMaterial& mat = m.materials[m.meshes[0].material];
  EXPECT_EQ(mat.texture.cols, 8);
  EXPECT_EQ(mat.texture.rows, 4);
  EXPECT_EQ(mat.texture.at<cv::Vec3b>(0, 0), cv::Vec3b(10, 20, 200));
  ASSERT_EQ(m.meshes[0].uvs.size(), 4u);
  // OBJ's vt 0 0 is the image's bottom-left: v = 1 at the top-left origin.
  for (size_t i = 0; i < 4; ++i)
    if (m.meshes[0].positions[i].norm() < 1e-6) {
      EXPECT_NEAR(m.meshes[0].uvs[i].y(), 1.0f, 1e-6);
    }
}

TEST(AssetLoaderErrors, ClipThatDoesNotExist) {
  AssetLoadOptions o = person_options();
  o.clips = {"Walk_procedural", "Run"};
  EXPECT_EQ(
      load_error(shared_asset("people/mh_worker_male.glb"), o),
      shared_asset("people/mh_worker_male.glb") + ": no clip named 'Run' (clips: Walk_procedural)");
}

TEST(AssetLoaderErrors, AxesThatAreNotPerpendicular) {
  AssetLoadOptions o;
  o.up = Axis::kPosY;
  o.forward = Axis::kNegY;
  EXPECT_EQ(
      load_error(shared_asset("props/Table.fbx"), o),
      shared_asset("props/Table.fbx") + ": up axis +y and forward axis -y must be perpendicular");
}

}  // namespace
}  // namespace depot::sim
