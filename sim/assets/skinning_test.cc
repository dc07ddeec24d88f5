// Skinning and clip sampling on the MakeHuman worker: the bind pose
// reproduces the mesh, a known bone turn moves known vertices, clip keys come
// back at their times.
#include "sim/assets/skinning.h"
#include "sim/assets/testing/cpu_skinning.h"

#include <gtest/gtest.h>

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <functional>
#include <map>

#include "common/testing/error_of.h"
#include "sim/assets/testing/asset_fixtures.h"

namespace depot::sim {
namespace {

using testing::shared_asset;
using testing::worker;

constexpr double kPi = 3.14159265358979323846;

// Bones below `root` in the skeleton (root included).
std::vector<bool> subtree(const Skeleton& sk, int root) {
  std::vector<bool> in(sk.bones.size(), false);
  in[root] = true;
  for (size_t i = 0; i < sk.bones.size(); ++i)
    if (sk.bones[i].parent >= 0 && in[sk.bones[i].parent]) in[i] = true;
  return in;
}

// Vertices weighted only to bones in `set`.
bool only_on(const VertexBones& vb, const std::vector<bool>& set) {
  for (int k = 0; k < 4; ++k)
    if (vb.bone[k] >= 0 && vb.weight[k] > 0 && !set[vb.bone[k]]) return false;
  return vb.bone[0] >= 0;
}

bool touches(const VertexBones& vb, int bone) {
  for (int k = 0; k < 4; ++k)
    if (vb.bone[k] == bone && vb.weight[k] > 0) return true;
  return false;
}

struct Posed {
  std::vector<std::vector<Eigen::Vector3f>> positions, normals;
};

Posed skin_all(const AssetModel& m, const SkeletonPose& pose) {
  std::vector<Eigen::Affine3d> globals, matrices;
  bone_globals(m.skeleton, pose, globals);
  testing::skinning_matrices(m.skeleton, globals, matrices);
  Posed out;
  out.positions.resize(m.meshes.size());
  out.normals.resize(m.meshes.size());
  for (size_t i = 0; i < m.meshes.size(); ++i)
    testing::skin_mesh(m.meshes[i], matrices, out.positions[i], out.normals[i]);
  return out;
}

void expect_rest_pose_reproduces_bind_mesh(const AssetModel& m) {
  const Posed posed = skin_all(m, rest_pose(m.skeleton));
  const float tolerance = 1e-5f * std::max(1.0f, m.bounds.sizes().maxCoeff());
  for (size_t i = 0; i < m.meshes.size(); ++i) {
    ASSERT_EQ(posed.positions[i].size(), m.meshes[i].positions.size());
    for (size_t v = 0; v < m.meshes[i].positions.size(); ++v) {
      ASSERT_LT((posed.positions[i][v] - m.meshes[i].positions[v]).norm(), tolerance)
          << m.source << " mesh " << i << " vertex " << v;
      ASSERT_LT((posed.normals[i][v] - m.meshes[i].normals[v]).norm(), 1e-4f);
    }
  }
}

TEST(Skinning, RestPoseReproducesTheBindMesh) {
  expect_rest_pose_reproduces_bind_mesh(worker());
  // The FBX animals' scene graphs hold another pose than the one their meshes
  // were bound in (the cat's is mid-stride): the rest pose must be the bind
  // pose, not the scene graph's.
  AssetLoadOptions o;
  o.target_height = 0.36;
  o.forward = Axis::kPosX;
  expect_rest_pose_reproduces_bind_mesh(load_asset(shared_asset("animals/cat/Cat.fbx"), o));
  o.target_height = 1.55;
  o.forward = Axis::kPosZ;
  expect_rest_pose_reproduces_bind_mesh(load_asset(shared_asset("animals/farm/Cow.fbx"), o));
}

TEST(Skinning, TurningTheLeftThighSwingsTheLeftFootAndNothingAboveTheHips) {
  const AssetModel& m = worker();
  const Skeleton& sk = m.skeleton;
  const std::vector<int> b = find_bones(sk, {"thigh_l", "foot_l", "head"}, "test");
  const int thigh = b[0], foot = b[1], head = b[2];
  const Eigen::Vector3d hip = rest_joint_position(sk, thigh);
  // Swing the thigh 90 degrees forward about the model's y axis.
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(-kPi / 2, Eigen::Vector3d::UnitY()));
  SkeletonPose pose = rest_pose(sk);
  turn_bone(sk, pose, thigh, turn);
  const Posed posed = skin_all(m, pose);

  const std::vector<bool> leg = subtree(sk, thigh);
  const std::vector<bool> head_only = [&] {
    std::vector<bool> s(sk.bones.size(), false);
    s[head] = true;
    return s;
  }();
  int foot_vertices = 0, head_vertices = 0;
  double foot_forward = 0;
  for (size_t i = 0; i < m.meshes.size(); ++i) {
    const AssetMesh& mesh = m.meshes[i];
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      const Eigen::Vector3d rest = mesh.positions[v].cast<double>();
      const Eigen::Vector3d now = posed.positions[i][v].cast<double>();
      if (only_on(mesh.bones[v], leg) && touches(mesh.bones[v], foot)) {
        // Rigidly carried about the hip joint.
        const Eigen::Vector3d expected = hip + turn * (rest - hip);
        ASSERT_LT((now - expected).norm(), 1e-4) << mesh.name << " vertex " << v;
        foot_forward += now.x() - hip.x();
        ++foot_vertices;
      } else if (only_on(mesh.bones[v], head_only)) {
        ASSERT_LT((now - rest).norm(), 1e-6) << mesh.name << " vertex " << v;
        ++head_vertices;
      }
    }
  }
  EXPECT_GT(foot_vertices, 500);
  EXPECT_GT(head_vertices, 500);
  // The foot now sits in front of the hip by about the leg's length.
  EXPECT_NEAR(foot_forward / foot_vertices, 0.86, 0.1);
  // The joint itself stays put, its children move.
  std::vector<Eigen::Affine3d> globals;
  bone_globals(sk, pose, globals);
  EXPECT_LT((globals[thigh].translation() - hip).norm(), 1e-9);
  const Eigen::Vector3d ankle = globals[foot].translation();
  EXPECT_NEAR(ankle.z(), hip.z(), 0.1);
  EXPECT_GT(ankle.x() - hip.x(), 0.7);
}

TEST(Skinning, SetBoneRotationAndMissingBones) {
  const AssetModel& m = worker();
  SkeletonPose pose = rest_pose(m.skeleton);
  const int neck = find_bones(m.skeleton, {"neck_01"}, "test")[0];
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  set_bone_rotation(pose, neck, q);
  EXPECT_TRUE(pose.rotation[neck].isApprox(q));
  EXPECT_EQ(error_of([&] {
              find_bones(m.skeleton, {"head", "tail"}, "gait");
            }),
            "gait: the skeleton has no bone named 'tail'");
}

// The raw keys of one channel, read with assimp directly (not through the
// loader).
const aiNodeAnim* raw_channel(const aiScene& scene, const std::string& clip,
                              const std::string& bone) {
  for (unsigned a = 0; a < scene.mNumAnimations; ++a) {
    const aiAnimation& anim = *scene.mAnimations[a];
    if (clip != anim.mName.C_Str()) continue;
    for (unsigned c = 0; c < anim.mNumChannels; ++c)
      if (bone == anim.mChannels[c]->mNodeName.C_Str()) return anim.mChannels[c];
  }
  return nullptr;
}

TEST(ClipSampling, KeysComeBackAtTheirTimesAndSlerpBetween) {
  const AssetModel& m = worker();
  const AnimationClip& walk = m.clips[find_clip(m, "Walk_procedural")];
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(shared_asset("people/mh_worker_male.glb"), 0);
  ASSERT_NE(scene, nullptr);
  const aiNodeAnim* raw = raw_channel(*scene, "Walk_procedural", "thigh_l");
  ASSERT_NE(raw, nullptr);
  ASSERT_GT(raw->mNumRotationKeys, 5u);
  const double tps = scene->mAnimations[0]->mTicksPerSecond;
  const int thigh = find_bone(m.skeleton, "thigh_l");

  auto key = [&](unsigned k) {
    const aiQuaternion& q = raw->mRotationKeys[k].mValue;
    return Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized();
  };
  const unsigned k = 2;  // keys 2 and 3 differ (5 and 6 are the same peak)
  const double t5 = raw->mRotationKeys[k].mTime / tps, t6 = raw->mRotationKeys[k + 1].mTime / tps;
  SkeletonPose pose = rest_pose(m.skeleton);
  sample_clip(walk, t5, false, pose);
  EXPECT_NEAR(pose.rotation[thigh].angularDistance(key(k)), 0.0, 1e-9);
  // Halfway between two keys: the slerp midpoint.
  sample_clip(walk, 0.5 * (t5 + t6), false, pose);
  EXPECT_NEAR(pose.rotation[thigh].angularDistance(key(k).slerp(0.5, key(k + 1))), 0.0, 1e-9);
  // Looping wraps time by the duration; clamping holds the last key.
  SkeletonPose wrapped = rest_pose(m.skeleton);
  sample_clip(walk, t5 + 3 * walk.duration, true, wrapped);
  EXPECT_NEAR(wrapped.rotation[thigh].angularDistance(key(k)), 0.0, 1e-9);
  sample_clip(walk, 100.0, false, pose);
  EXPECT_NEAR(pose.rotation[thigh].angularDistance(key(raw->mNumRotationKeys - 1)), 0.0, 1e-9);
  // The clip really moves the leg: the key differs from the rest pose.
  EXPECT_GT(key(k).angularDistance(m.skeleton.bones[thigh].rest_rotation), 0.05);
}

TEST(ClipSampling, TranslationKeysAreInMetres) {
  // The cow's clips move its root in file units (~535 per cow); sampled
  // translations come back scaled to the model.
  AssetLoadOptions o;
  o.target_height = 1.55;
  o.clips = {"Armature|Walk"};
  const AssetModel cow = load_asset(shared_asset("animals/farm/Cow.fbx"), o);
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(shared_asset("animals/farm/Cow.fbx"), 0);
  ASSERT_NE(scene, nullptr);
  const AnimationClip& walk = cow.clips[0];
  for (const BoneChannel& ch : walk.channels) {
    if (ch.translations.empty()) continue;
    const aiNodeAnim* raw = raw_channel(*scene, "Armature|Walk", ch.bone_name);
    ASSERT_NE(raw, nullptr) << ch.bone_name;
    const aiVector3D& r = raw->mPositionKeys[0].mValue;
    SkeletonPose pose = rest_pose(cow.skeleton);
    sample_clip(walk, ch.translations[0].time, false, pose);
    EXPECT_LT((pose.translation[ch.bone] - cow.scale * Eigen::Vector3d(r.x, r.y, r.z)).norm(),
              1e-9);
  }
}

Eigen::Affine3d to_eigen(const aiMatrix4x4& m) {
  Eigen::Affine3d a;
  a.matrix() << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2,
      m.d3, m.d4;
  return a;
}

// Skinning the way assimp's data defines it, independently of the loader:
// vertex = sum of w * (global(bone) * offset) * v / sum of w, with every
// animated node at its first key, in the file's own units and axes.
std::vector<std::vector<Eigen::Vector3d>> assimp_reference(const std::string& path,
                                                           const std::string& clip) {
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_LimitBoneWeights);
  EXPECT_NE(scene, nullptr);
  std::map<std::string, Eigen::Affine3d> keyed;
  for (unsigned a = 0; a < scene->mNumAnimations; ++a) {
    if (clip != scene->mAnimations[a]->mName.C_Str()) continue;
    for (unsigned c = 0; c < scene->mAnimations[a]->mNumChannels; ++c) {
      const aiNodeAnim& ch = *scene->mAnimations[a]->mChannels[c];
      const aiVector3D t = ch.mPositionKeys[0].mValue, s = ch.mScalingKeys[0].mValue;
      const aiQuaternion q = ch.mRotationKeys[0].mValue;
      Eigen::Affine3d local = Eigen::Affine3d::Identity();
      local.linear() = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix() *
                       Eigen::Vector3d(s.x, s.y, s.z).asDiagonal();
      local.translation() = Eigen::Vector3d(t.x, t.y, t.z);
      keyed[ch.mNodeName.C_Str()] = local;
    }
  }
  std::function<Eigen::Affine3d(const aiNode*)> global = [&](const aiNode* n) {
    auto it = keyed.find(n->mName.C_Str());
    const Eigen::Affine3d local = it != keyed.end() ? it->second : to_eigen(n->mTransformation);
    return n->mParent ? Eigen::Affine3d(global(n->mParent) * local) : local;
  };
  std::vector<std::vector<Eigen::Vector3d>> out;
  std::function<void(const aiNode*)> walk = [&](const aiNode* n) {
    for (unsigned k = 0; k < n->mNumMeshes; ++k) {
      const aiMesh& mesh = *scene->mMeshes[n->mMeshes[k]];
      std::vector<Eigen::Vector3d> p(mesh.mNumVertices, Eigen::Vector3d::Zero());
      std::vector<double> total(mesh.mNumVertices, 0.0);
      for (unsigned b = 0; b < mesh.mNumBones; ++b) {
        const aiBone& bone = *mesh.mBones[b];
        const Eigen::Affine3d m =
            global(scene->mRootNode->FindNode(bone.mName)) * to_eigen(bone.mOffsetMatrix);
        for (unsigned w = 0; w < bone.mNumWeights; ++w) {
          const aiVector3D& v = mesh.mVertices[bone.mWeights[w].mVertexId];
          p[bone.mWeights[w].mVertexId] +=
              bone.mWeights[w].mWeight * (m * Eigen::Vector3d(v.x, v.y, v.z));
          total[bone.mWeights[w].mVertexId] += bone.mWeights[w].mWeight;
        }
      }
      // The cat's weights sum to 0.92..1.03 per vertex: normalised, as the
      // loader does (unnormalised they would pull vertices to the origin).
      for (size_t v = 0; v < p.size(); ++v) p[v] /= total[v];
      out.push_back(p);
    }
    for (unsigned c = 0; c < n->mNumChildren; ++c) walk(n->mChildren[c]);
  };
  walk(scene->mRootNode);
  return out;
}

TEST(ClipSampling, PosedMeshMatchesAssimpsOwnSkinning) {
  // The cat's clip at its first keys, through loader + sample_clip +
  // skinning, against the reference above mapped into the model frame
  // (root * scale): catches a wrong bind pose or a wrong unit change.
  AssetLoadOptions o;
  o.forward = Axis::kPosX;
  o.target_height = 0.36;
  const std::string path = shared_asset("animals/cat/Cat.fbx");
  const AssetModel cat = load_asset(path, o);
  SkeletonPose pose = rest_pose(cat.skeleton);
  sample_clip(cat.clips[find_clip(cat, "CatArmature|Walking")], 0.0, false, pose);
  const Posed posed = skin_all(cat, pose);
  const auto reference = assimp_reference(path, "CatArmature|Walking");
  ASSERT_EQ(reference.size(), cat.meshes.size());
  double moved = 0;
  for (size_t i = 0; i < cat.meshes.size(); ++i) {
    ASSERT_EQ(reference[i].size(), posed.positions[i].size());
    for (size_t v = 0; v < reference[i].size(); ++v) {
      const Eigen::Vector3d expected = cat.skeleton.root * (cat.scale * reference[i][v]);
      ASSERT_LT((posed.positions[i][v].cast<double>() - expected).norm(), 1e-4) << i << " " << v;
      moved = std::max<double>(moved, (posed.positions[i][v] - cat.meshes[i].positions[v]).norm());
    }
  }
  EXPECT_GT(moved, 0.02);  // the clip's first frame is not the bind pose
}

TEST(ClipSampling, AClipPosesTheMeshAwayFromRest) {
  const AssetModel& m = worker();
  SkeletonPose pose = rest_pose(m.skeleton);
  sample_clip(m.clips[0], 0.3, true, pose);
  const Posed posed = skin_all(m, pose);
  double max_move = 0;
  for (size_t i = 0; i < m.meshes.size(); ++i)
    for (size_t v = 0; v < m.meshes[i].positions.size(); ++v)
      max_move =
          std::max<double>(max_move, (posed.positions[i][v] - m.meshes[i].positions[v]).norm());
  EXPECT_GT(max_move, 0.1);  // a foot or hand moved by more than 10 cm
  EXPECT_LT(max_move, 1.0);
}

}  // namespace
}  // namespace depot::sim
