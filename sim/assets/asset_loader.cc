#include "sim/assets/asset_loader.h"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>

#include "common/error.h"
#include "sim/assets/alpha_cutout.h"
#include "sim/assets/asset_materials.h"
#include "sim/assets/skinning.h"

namespace fs = std::filesystem;

namespace depot::sim {
namespace {

Eigen::Affine3d to_eigen(const aiMatrix4x4& m) {
  Eigen::Affine3d a;
  a.matrix() << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2,
      m.d3, m.d4;
  return a;
}

// assimp's messages may span lines; ours are one line.
std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void check_model_file(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(path, "model file not found");
  if (!fs::is_regular_file(path, ec)) fail(path, "not a model file (a folder?)");
  const std::string ext = lower_extension(path);
  const auto& ok = supported_model_extensions();
  if (std::find(ok.begin(), ok.end(), ext) == ok.end())
    fail(path, "unsupported model format '" + ext + "' (expected .glb, .gltf, .fbx or .obj)");
  if (fs::file_size(path, ec) == 0) fail(path, "model file is empty");
}

// Reads the file, then post-processes it with `flags`. Faces are counted in
// between: assimp's own checks would reject a model without faces with
// messages like "No meshes remaining".
const aiScene* read_scene(Assimp::Importer& importer, const std::string& path, unsigned int flags) {
  // Pivot helper nodes ($AssimpFbx$) would sit between bones and the nodes
  // that clips animate; folding them keeps one node per FBX bone.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  importer.SetPropertyInteger(AI_CONFIG_PP_LBW_MAX_WEIGHTS, 4);
  const aiScene* scene = importer.ReadFile(path, 0);
  if (!scene) fail(path, "cannot read the model: " + one_line(importer.GetErrorString()));
  if (!scene->mRootNode) fail(path, "cannot read the model: no scene graph");
  size_t surfaces = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m)
    for (unsigned f = 0; f < scene->mMeshes[m]->mNumFaces; ++f)
      surfaces += scene->mMeshes[m]->mFaces[f].mNumIndices >= 3;
  if (surfaces == 0 && scene->mNumAnimations == 0) fail(path, "the model has no triangles");
  scene = importer.ApplyPostProcessing(flags | aiProcess_ValidateDataStructure);
  if (!scene) fail(path, "cannot read the model: " + one_line(importer.GetErrorString()));
  return scene;
}

// The scene graph, parents before children.
struct Node {
  const aiNode* ai = nullptr;
  int parent = -1;
  Eigen::Affine3d local = Eigen::Affine3d::Identity();
  Eigen::Affine3d global = Eigen::Affine3d::Identity();
};

std::vector<Node> flatten(const aiScene& scene) {
  std::vector<Node> nodes;
  std::vector<std::pair<const aiNode*, int>> stack = {{scene.mRootNode, -1}};
  while (!stack.empty()) {
    auto [ai, parent] = stack.back();
    stack.pop_back();
    Node n;
    n.ai = ai;
    n.parent = parent;
    n.local = to_eigen(ai->mTransformation);
    n.global = parent >= 0 ? nodes[parent].global * n.local : n.local;
    const int index = static_cast<int>(nodes.size());
    nodes.push_back(n);
    for (int c = static_cast<int>(ai->mNumChildren) - 1; c >= 0; --c)
      stack.push_back({ai->mChildren[c], index});
  }
  return nodes;
}

void decompose(const Eigen::Affine3d& a, Eigen::Vector3d& t, Eigen::Quaterniond& r,
               Eigen::Vector3d& s) {
  Eigen::Matrix3d rotation, scaling;
  a.computeRotationScaling(&rotation, &scaling);
  t = a.translation();
  r = Eigen::Quaterniond(rotation).normalized();
  s = scaling.diagonal();
}

double ticks_per_second(const aiAnimation& anim) {
  // assimp's convention for files that do not say.
  return anim.mTicksPerSecond > 0 ? anim.mTicksPerSecond : 25.0;
}

std::string clip_list(const aiScene& scene) {
  std::string names;
  for (unsigned i = 0; i < scene.mNumAnimations; ++i)
    names += (i ? ", " : "") + std::string(scene.mAnimations[i]->mName.C_Str());
  return names.empty() ? "none" : names;
}

const aiAnimation* find_animation(const aiScene& scene, const std::string& name) {
  for (unsigned i = 0; i < scene.mNumAnimations; ++i)
    if (name == scene.mAnimations[i]->mName.C_Str()) return scene.mAnimations[i];
  return nullptr;
}

// Keys of one assimp channel; translations multiplied by `scale`.
BoneChannel read_channel(const aiNodeAnim& ch, double tps, double scale) {
  BoneChannel out;
  out.bone_name = ch.mNodeName.C_Str();
  for (unsigned k = 0; k < ch.mNumPositionKeys; ++k) {
    const auto& key = ch.mPositionKeys[k];
    out.translations.push_back(
        {key.mTime / tps, Eigen::Vector3d(key.mValue.x, key.mValue.y, key.mValue.z) * scale});
  }
  for (unsigned k = 0; k < ch.mNumRotationKeys; ++k) {
    const auto& key = ch.mRotationKeys[k];
    out.rotations.push_back(
        {key.mTime / tps,
         Eigen::Quaterniond(key.mValue.w, key.mValue.x, key.mValue.y, key.mValue.z).normalized()});
  }
  for (unsigned k = 0; k < ch.mNumScalingKeys; ++k) {
    const auto& key = ch.mScalingKeys[k];
    out.scales.push_back(
        {key.mTime / tps, Eigen::Vector3d(key.mValue.x, key.mValue.y, key.mValue.z)});
  }
  return out;
}

// A mesh in the file's space before axes and units change: positions at the
// bind pose and, for skinned vertices, the scene nodes they follow.
struct SourceMesh {
  AssetMesh mesh;
  std::vector<std::array<std::pair<int, float>, 4>> node_weights;  // node index, weight
};

class SceneReader {
 public:
  SceneReader(const aiScene& scene, const std::string& path, const AssetLoadOptions& options)
      : scene_(scene), path_(path), options_(options), nodes_(flatten(scene)) {
    for (size_t i = 0; i < nodes_.size(); ++i) index_[nodes_[i].ai] = static_cast<int>(i);
  }

  AssetModel read() {
    mark_skeleton_nodes();
    compute_rest_globals();
    read_meshes();
    AssetModel model;
    model.source = path_;
    normalise(model);
    build_skeleton(model);
    read_clips(model);
    model.materials = read_materials(scene_, path_, options_.linear_colours);
    for (auto& m : model.meshes)
      if (m.material >= static_cast<int>(model.materials.size())) m.material = -1;
    if (options_.cut_alpha) cut_alpha_triangles(model);
    model.meshes.erase(std::remove_if(model.meshes.begin(), model.meshes.end(),
                                      [](const AssetMesh& m) { return m.triangles.empty(); }),
                       model.meshes.end());
    return model;
  }

 private:
  int node_named(const aiString& name) const {
    const aiNode* n = scene_.mRootNode->FindNode(name);
    if (!n) return -1;
    return index_.at(n);
  }

  // Bones (nodes that vertices follow), animated nodes, the nodes of rigid
  // meshes that an animation moves, and all their ancestors.
  void mark_skeleton_nodes() {
    in_skeleton_.assign(nodes_.size(), false);
    animated_.assign(nodes_.size(), false);
    bind_.assign(nodes_.size(), std::nullopt);
    for (unsigned a = 0; a < scene_.mNumAnimations; ++a) {
      const aiAnimation& anim = *scene_.mAnimations[a];
      for (unsigned c = 0; c < anim.mNumChannels; ++c) {
        const int n = node_named(anim.mChannels[c]->mNodeName);
        if (n >= 0) animated_[n] = true;
      }
    }
    for (size_t n = 0; n < nodes_.size(); ++n) {
      const aiNode* ai = nodes_[n].ai;
      for (unsigned k = 0; k < ai->mNumMeshes; ++k) {
        const aiMesh& mesh = *scene_.mMeshes[ai->mMeshes[k]];
        for (unsigned b = 0; b < mesh.mNumBones; ++b) {
          const aiBone& bone = *mesh.mBones[b];
          const int bn = node_named(bone.mName);
          if (bn < 0)
            fail(path_, "bone '" + std::string(bone.mName.C_Str()) + "' of mesh '" +
                            mesh.mName.C_Str() + "' has no node in the scene");
          // The bone's global transform when the mesh was bound: the offset
          // matrix maps the mesh (at its node's global transform) into the
          // bone's space. The first mesh decides; the files bind all meshes
          // at once.
          if (!bind_[bn]) bind_[bn] = nodes_[n].global * to_eigen(bone.mOffsetMatrix).inverse();
          in_skeleton_[bn] = true;
        }
        if (mesh.mNumBones == 0 && moved_by_animation(static_cast<int>(n))) in_skeleton_[n] = true;
      }
      if (animated_[n]) in_skeleton_[n] = true;
    }
    for (int n = static_cast<int>(nodes_.size()) - 1; n >= 0; --n)
      if (in_skeleton_[n] && nodes_[n].parent >= 0) in_skeleton_[nodes_[n].parent] = true;
  }

  bool moved_by_animation(int n) const {
    for (; n >= 0; n = nodes_[n].parent)
      if (animated_[n]) return true;
    return false;
  }

  // The pose the vertices were bound in: bones at their bind transforms,
  // other nodes following their parents. (The FBX animals' scene graphs hold
  // another pose, e.g. the cat's mid-stride; the bind pose is the one the
  // mesh was modelled in.)
  void compute_rest_globals() {
    rest_global_.resize(nodes_.size());
    for (size_t n = 0; n < nodes_.size(); ++n) {
      const int p = nodes_[n].parent;
      rest_global_[n] =
          bind_[n] ? *bind_[n]
                   : (p >= 0 ? rest_global_[p] : Eigen::Affine3d::Identity()) * nodes_[n].local;
    }
  }

  void read_meshes() {
    for (size_t n = 0; n < nodes_.size(); ++n) {
      const aiNode* ai = nodes_[n].ai;
      for (unsigned k = 0; k < ai->mNumMeshes; ++k)
        read_mesh(*scene_.mMeshes[ai->mMeshes[k]], static_cast<int>(n));
    }
    size_t triangles = 0;
    for (const auto& m : meshes_) triangles += m.mesh.triangles.size();
    if (triangles == 0) fail(path_, "the model has no triangles");
  }

  void read_mesh(const aiMesh& in, int node) {
    SourceMesh sm;
    AssetMesh& m = sm.mesh;
    m.name = in.mName.C_Str();
    m.material = static_cast<int>(in.mMaterialIndex);
    for (unsigned f = 0; f < in.mNumFaces; ++f) {
      const aiFace& face = in.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines are not surfaces
      m.triangles.emplace_back(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
    }
    if (m.triangles.empty()) return;

    // Skinned vertices are bound at the mesh node's global transform (what
    // the offset matrices assume); rigid ones sit at their node's rest pose.
    const bool skinned = in.mNumBones > 0;
    const Eigen::Affine3d to_source = skinned ? nodes_[node].global : rest_global_[node];
    const Eigen::Matrix3d normal_matrix = to_source.linear().inverse().transpose();
    m.positions.resize(in.mNumVertices);
    m.normals.resize(in.mNumVertices, Eigen::Vector3f::UnitZ());
    for (unsigned v = 0; v < in.mNumVertices; ++v) {
      const aiVector3D& p = in.mVertices[v];
      m.positions[v] = (to_source * Eigen::Vector3d(p.x, p.y, p.z)).cast<float>();
      if (in.mNormals) {
        const aiVector3D& q = in.mNormals[v];
        Eigen::Vector3d nrm = normal_matrix * Eigen::Vector3d(q.x, q.y, q.z);
        if (nrm.norm() > 1e-12) m.normals[v] = nrm.normalized().cast<float>();
      }
    }
    if (in.HasTextureCoords(0)) {
      m.uvs.resize(in.mNumVertices);
      for (unsigned v = 0; v < in.mNumVertices; ++v)
        m.uvs[v] = Eigen::Vector2f(in.mTextureCoords[0][v].x, in.mTextureCoords[0][v].y);
    }

    if (skinned) {
      sm.node_weights.assign(in.mNumVertices, {});
      std::vector<int> count(in.mNumVertices, 0);
      for (unsigned b = 0; b < in.mNumBones; ++b) {
        const aiBone& bone = *in.mBones[b];
        const int bn = node_named(bone.mName);
        for (unsigned w = 0; w < bone.mNumWeights; ++w) {
          const aiVertexWeight& vw = bone.mWeights[w];
          if (vw.mVertexId >= in.mNumVertices || vw.mWeight <= 0) continue;
          auto& slots = sm.node_weights[vw.mVertexId];
          int& c = count[vw.mVertexId];
          if (c < 4) {
            slots[c++] = {bn, vw.mWeight};
          } else {
            // More than four (LimitBoneWeights normally prevents it): keep
            // the heaviest.
            auto lightest = std::min_element(slots.begin(), slots.end(),
                                             [](auto& a, auto& b) { return a.second < b.second; });
            if (lightest->second < vw.mWeight) *lightest = {bn, vw.mWeight};
          }
        }
      }
    } else if (in_skeleton_[node]) {
      sm.node_weights.assign(in.mNumVertices, {});
      for (auto& slots : sm.node_weights) slots[0] = {node, 1.0f};
    }
    meshes_.push_back(std::move(sm));
  }

  // Axes to z-up/x-forward, units to metres, feet on z = 0.
  void normalise(AssetModel& model) {
    rotation_ = model_rotation(options_.up, options_.forward, path_);
    Eigen::AlignedBox3d box;
    for (const auto& sm : meshes_)
      for (const auto& p : sm.mesh.positions) box.extend(rotation_ * p.cast<double>());
    const double height = box.sizes().z();
    if (options_.target_height > 0) {
      if (height < 1e-12) fail(path_, "the model has no height along its up axis");
      scale_ = options_.target_height / height;
    } else {
      if (!(options_.scale > 0)) fail(path_, "scale must be positive");
      scale_ = options_.scale;
    }
    const Eigen::Vector3d c = box.center();
    offset_ = Eigen::Vector3d(options_.center_xy ? -scale_ * c.x() : 0.0,
                              options_.center_xy ? -scale_ * c.y() : 0.0, -scale_ * box.min().z());
    model.scale = scale_;
    model.bounds.setEmpty();
    const Eigen::Matrix3f r = rotation_.cast<float>();
    const Eigen::Matrix3f sr = (scale_ * rotation_).cast<float>();
    const Eigen::Vector3f t = offset_.cast<float>();
    for (auto& sm : meshes_) {
      for (auto& p : sm.mesh.positions) {
        p = sr * p + t;
        model.bounds.extend(p);
      }
      for (auto& n : sm.mesh.normals) n = (r * n).normalized();
    }
  }

  // Bones in metres: local translations scaled, the axis change and the
  // offset above the roots (Skeleton::root), so globals stay rigid-looking
  // and the gait can set rotations directly.
  void build_skeleton(AssetModel& model) {
    Skeleton& sk = model.skeleton;
    sk.root = Eigen::Translation3d(offset_) * Eigen::Affine3d(rotation_);
    std::vector<int> bone_of(nodes_.size(), -1);
    for (size_t n = 0; n < nodes_.size(); ++n) {
      if (!in_skeleton_[n]) continue;
      Bone b;
      b.name = nodes_[n].ai->mName.C_Str();
      const int p = nodes_[n].parent;
      b.parent = p >= 0 ? bone_of[p] : -1;
      const Eigen::Affine3d local =
          p >= 0 ? Eigen::Affine3d(rest_global_[p].inverse() * rest_global_[n]) : rest_global_[n];
      decompose(local, b.rest_translation, b.rest_rotation, b.rest_scale);
      b.rest_translation *= scale_;
      bone_of[n] = static_cast<int>(sk.bones.size());
      sk.bones.push_back(b);
    }
    // Inverse binds from the same composition skinning uses, so the rest
    // pose reproduces the bind pose to rounding.
    std::vector<Eigen::Affine3d> globals;
    bone_globals(sk, rest_pose(sk), globals);
    for (size_t i = 0; i < sk.bones.size(); ++i) sk.bones[i].inverse_bind = globals[i].inverse();

    for (auto& sm : meshes_) {
      if (!sm.node_weights.empty()) {
        sm.mesh.bones.resize(sm.node_weights.size());
        for (size_t v = 0; v < sm.node_weights.size(); ++v) {
          VertexBones& vb = sm.mesh.bones[v];
          float total = 0;
          for (int k = 0; k < 4; ++k) total += sm.node_weights[v][k].second;
          if (total <= 0) continue;  // unweighted: stays where the bind pose put it
          for (int k = 0; k < 4; ++k) {
            const auto [node, w] = sm.node_weights[v][k];
            if (w <= 0) continue;
            vb.bone[k] = bone_of[node];
            vb.weight[k] = w / total;
            sk.bones[bone_of[node]].deforms = true;
          }
        }
      }
      model.meshes.push_back(std::move(sm.mesh));
    }
    meshes_.clear();
  }

  void read_clips(AssetModel& model) {
    std::vector<const aiAnimation*> wanted;
    if (options_.clips.empty()) {
      for (unsigned a = 0; a < scene_.mNumAnimations; ++a) wanted.push_back(scene_.mAnimations[a]);
    } else {
      for (const auto& name : options_.clips) {
        const aiAnimation* anim = find_animation(scene_, name);
        if (!anim) fail(path_, "no clip named '" + name + "' (clips: " + clip_list(scene_) + ")");
        wanted.push_back(anim);
      }
    }
    for (const aiAnimation* anim : wanted) {
      AnimationClip clip;
      clip.name = anim->mName.C_Str();
      const double tps = ticks_per_second(*anim);
      clip.duration = anim->mDuration / tps;
      for (unsigned c = 0; c < anim->mNumChannels; ++c) {
        BoneChannel ch = read_channel(*anim->mChannels[c], tps, scale_);
        ch.bone = find_bone(model.skeleton, ch.bone_name);
        if (ch.bone >= 0) clip.channels.push_back(std::move(ch));
      }
      model.clips.push_back(std::move(clip));
    }
  }

  const aiScene& scene_;
  const std::string& path_;
  const AssetLoadOptions& options_;
  std::vector<Node> nodes_;
  std::map<const aiNode*, int> index_;
  std::vector<bool> in_skeleton_, animated_;
  std::vector<std::optional<Eigen::Affine3d>> bind_;
  std::vector<Eigen::Affine3d> rest_global_;
  std::vector<SourceMesh> meshes_;
  Eigen::Matrix3d rotation_ = Eigen::Matrix3d::Identity();
  double scale_ = 1.0;
  Eigen::Vector3d offset_ = Eigen::Vector3d::Zero();
};

}  // namespace

const std::vector<std::string>& supported_model_extensions() {
  static const std::vector<std::string> ext = {".glb", ".gltf", ".fbx", ".obj"};
  return ext;
}

AssetModel load_asset(const std::string& path, const AssetLoadOptions& options) {
  check_model_file(path);
  Assimp::Importer importer;
  const aiScene* scene = read_scene(importer, path,
                                    aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                        aiProcess_LimitBoneWeights | aiProcess_GenSmoothNormals |
                                        aiProcess_SortByPType | aiProcess_FlipUVs);
  return SceneReader(*scene, path, options).read();
}

void load_clips_into(AssetModel& model, const std::string& path,
                     const std::vector<std::string>& names, bool rotations_only) {
  check_model_file(path);
  Assimp::Importer importer;
  const aiScene* scene = read_scene(importer, path, 0);
  for (const auto& name : names) {
    const aiAnimation* anim = find_animation(*scene, name);
    if (!anim) fail(path, "no clip named '" + name + "' (clips: " + clip_list(*scene) + ")");
    AnimationClip clip;
    clip.name = name;
    const double tps = ticks_per_second(*anim);
    clip.duration = anim->mDuration / tps;
    for (unsigned c = 0; c < anim->mNumChannels; ++c) {
      BoneChannel ch = read_channel(*anim->mChannels[c], tps, model.scale);
      ch.bone = find_bone(model.skeleton, ch.bone_name);
      if (ch.bone < 0) continue;
      if (rotations_only) {
        ch.translations.clear();
        ch.scales.clear();
      }
      clip.channels.push_back(std::move(ch));
    }
    if (clip.channels.empty())
      fail(path, "clip '" + name + "' animates no bone of " + model.source);
    const int existing = find_clip(model, name);
    if (existing >= 0)
      model.clips[existing] = std::move(clip);
    else
      model.clips.push_back(std::move(clip));
  }
}

}  // namespace depot::sim
