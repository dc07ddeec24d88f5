#pragma once
// A 3D model loaded from a file (glTF/GLB, FBX, OBJ), as plain data in the
// simulator's frame: z up, x forward (the way the model faces), y left,
// metres; the bind pose stands on z = 0. Nothing here refers to assimp or
// MuJoCo: asset_loader.h fills it, skinning.h poses it, mujoco_mesh.h encodes
// it for MuJoCo.
//
// Conventions shared by every function of sim/assets:
// - "model frame": the frame above, the one the actor's root pose places in
//   the world.
// - UVs have their origin at the top-left of the texture image, v grows
//   downwards (glTF's convention, and what MuJoCo 2.2 samples: v = 0 is the
//   first row of the PNG).
// - Colours are sRGB-encoded 0..1, as MuJoCo's rgba expects.
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

namespace depot::sim {

struct AssetMaterial {
  std::string name;
  Eigen::Vector4f rgba{1, 1, 1, 1};  // base colour; multiplies the texture
  cv::Mat texture;                   // CV_8UC3 (BGR) or CV_8UC4 (BGRA); empty: none
  std::string texture_name;          // embedded name or file, for messages and VFS names
  bool texture_has_alpha = false;    // some texel has alpha < 255
  // The file asks for alpha testing or blending (glTF alphaMode MASK or
  // BLEND): hair cards and eyes. MuJoCo 2.2 ignores texture alpha, so such
  // materials need alpha_cutout.h before they are encoded.
  bool alpha_mask = false;
  float alpha_cutoff = 0.5f;  // glTF alphaCutoff (MASK); 0.5 otherwise
};

// Up to four bones per vertex (aiProcess_LimitBoneWeights); unused slots have
// bone -1 and weight 0; the weights of a skinned vertex sum to 1.
struct VertexBones {
  Eigen::Vector4i bone{-1, -1, -1, -1};
  Eigen::Vector4f weight{0, 0, 0, 0};
};

// One triangle mesh with one material, in the model frame at the bind pose.
struct AssetMesh {
  std::string name;
  int material = -1;  // index into AssetModel::materials
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;  // unit, one per position
  std::vector<Eigen::Vector2f> uvs;      // one per position, or empty
  std::vector<Eigen::Vector3i> triangles;
  std::vector<VertexBones> bones;  // one per position, or empty (a rigid mesh)
};

// A node of the skeleton. Local transforms are translation (metres),
// rotation and scale relative to the parent bone (or to Skeleton::root for a
// bone without parent); bones come parents first.
struct Bone {
  std::string name;
  int parent = -1;
  Eigen::Vector3d rest_translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rest_rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d rest_scale = Eigen::Vector3d::Ones();
  // Model frame -> this bone's frame at the bind pose: the skinning matrix of
  // the bone is global(bone) * inverse_bind. At the rest pose it is identity
  // for every bone that deforms vertices.
  Eigen::Affine3d inverse_bind = Eigen::Affine3d::Identity();
  bool deforms = false;  // some vertex is weighted to it
};

struct Skeleton {
  std::vector<Bone> bones;
  // Model frame <- the skeleton's root space (the axis and unit change of
  // the file); applied above every bone without parent.
  Eigen::Affine3d root = Eigen::Affine3d::Identity();
};

template <typename T>
struct Key {
  double time = 0;  // seconds from the clip's start
  T value;
};

// Keys of one bone; an empty list leaves that part of the bone at rest.
struct BoneChannel {
  std::string bone_name;
  int bone = -1;                                   // index into Skeleton::bones
  std::vector<Key<Eigen::Vector3d>> translations;  // metres, model scale
  std::vector<Key<Eigen::Quaterniond>> rotations;
  std::vector<Key<Eigen::Vector3d>> scales;
};

struct AnimationClip {
  std::string name;
  double duration = 0;  // seconds
  std::vector<BoneChannel> channels;
};

struct AssetModel {
  std::string source;  // the file it was loaded from
  std::vector<AssetMesh> meshes;
  std::vector<AssetMaterial> materials;
  Skeleton skeleton;
  std::vector<AnimationClip> clips;
  // Metres per source unit (what the loader multiplied lengths by).
  double scale = 1.0;
  // Bounds of every vertex at the bind pose (before any alpha cut-out).
  Eigen::AlignedBox3f bounds;
};

// Index of the bone/clip named `name`, or -1.
int find_bone(const Skeleton& skeleton, const std::string& name);
int find_clip(const AssetModel& model, const std::string& name);

}  // namespace depot::sim
