#include "sim/scene/skinned_actor_xml.h"

#include <fmt/format.h>

#include <iterator>
#include <sstream>

#include "sim/actors/bone_poses.h"
#include "sim/assets/mujoco_mesh.h"
#include "sim/assets/skinning.h"

namespace depot::sim {
namespace {

// Compact numbers: a person's skins are ~18k vertices, written as text.
void put(std::string& out, double v) {
  fmt::format_to(std::back_inserter(out), "{:.6g} ", std::abs(v) < 1e-12 ? 0.0 : v);
}

std::string trimmed(std::string s) {
  if (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace

SkinMaterials encode_skin_materials(const AssetModel& model, const std::string& prefix) {
  MujocoAssetSet set = encode_for_mujoco(model, prefix);
  SkinMaterials out;
  out.material_names = set.material_names;
  // Skins carry their own vertices: leave the bind meshes out, MuJoCo would
  // otherwise compile each of them (~0.28 s per person variant).
  for (auto& [name, bytes] : set.files)
    if (name.size() < 4 || name.compare(name.size() - 4, 4, ".msh") != 0)
      out.files.emplace_back(name, std::move(bytes));
  std::istringstream lines(set.asset_xml);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("<mesh ", 0) != 0) out.asset_xml += line + "\n";
  return out;
}

std::string bone_bodies_xml(const AssetModel& model, const std::vector<int>& body_bones,
                            const std::vector<Pose>& poses, const std::string& prefix,
                            std::vector<std::string>& bodies) {
  std::string x;
  const Skeleton& sk = model.skeleton;
  for (size_t i = 0; i < body_bones.size(); ++i) {
    const std::string name = prefix + "/" + sk.bones[body_bones[i]].name;
    bodies.push_back(name);
    const Eigen::Quaterniond q(poses[i].linear());
    std::string pos, quat;
    for (int k = 0; k < 3; ++k) put(pos, poses[i].translation()[k]);
    for (double v : {q.w(), q.x(), q.y(), q.z()}) put(quat, v);
    x += "<body name=\"" + name + "\" mocap=\"true\" pos=\"" + trimmed(pos) + "\" quat=\"" +
         trimmed(quat) + "\"/>\n";
  }
  return x;
}

std::string skins_xml(const AssetModel& model, const std::vector<int>& body_bones, double scale,
                      const std::vector<std::string>& material_names,
                      const std::vector<std::string>& bodies, const std::string& prefix,
                      std::vector<std::string>& skins) {
  const Skeleton& sk = model.skeleton;
  // The skin's bind pose is the bones' rest globals: there the skinning
  // matrices are identity and the vertices are the file's bind mesh.
  std::vector<Eigen::Affine3d> rest;
  bone_globals(sk, rest_pose(sk), rest);
  std::vector<int> body_of_bone(sk.bones.size(), -1);
  for (size_t i = 0; i < body_bones.size(); ++i) body_of_bone[body_bones[i]] = static_cast<int>(i);

  std::string x;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const AssetMesh& mesh = model.meshes[m];
    if (mesh.triangles.empty() || mesh.bones.size() != mesh.positions.size()) continue;
    const std::string name = prefix + "/skin" + std::to_string(m);
    skins.push_back(name);
    std::string vertex, texcoord, face;
    for (const auto& v : mesh.positions)
      for (int k = 0; k < 3; ++k) put(vertex, scale * v[k]);
    for (const auto& uv : mesh.uvs)
      for (int k = 0; k < 2; ++k) put(texcoord, uv[k]);
    for (const auto& t : mesh.triangles)
      for (int k = 0; k < 3; ++k) face += std::to_string(t[k]) + " ";
    x += "<skin name=\"" + name + "\"";
    if (!material_names[m].empty()) x += " material=\"" + material_names[m] + "\"";
    x += " vertex=\"" + trimmed(vertex) + "\"";
    if (!mesh.uvs.empty()) x += " texcoord=\"" + trimmed(texcoord) + "\"";
    x += " face=\"" + trimmed(face) + "\">\n";
    // Per bone: the vertices it moves and their weights.
    std::vector<std::string> ids(body_bones.size()), weights(body_bones.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      const VertexBones& vb = mesh.bones[v];
      for (int k = 0; k < 4; ++k) {
        if (vb.bone[k] < 0 || vb.weight[k] <= 0.0f) continue;
        const int body = body_of_bone[vb.bone[k]];
        if (body < 0) continue;
        ids[body] += std::to_string(v) + " ";
        put(weights[body], vb.weight[k]);
      }
    }
    for (size_t b = 0; b < ids.size(); ++b) {
      if (ids[b].empty()) continue;  // MuJoCo wants vertices on every bone of a skin
      const Pose bind = rigid_bone_pose(rest[body_bones[b]]);
      const Eigen::Quaterniond q(bind.linear());
      std::string pos, quat;
      for (int k = 0; k < 3; ++k) put(pos, scale * bind.translation()[k]);
      for (double v : {q.w(), q.x(), q.y(), q.z()}) put(quat, v);
      x += "<bone body=\"" + bodies[b] + "\" bindpos=\"" + trimmed(pos) + "\" bindquat=\"" +
           trimmed(quat) + "\" vertid=\"" + trimmed(ids[b]) + "\" vertweight=\"" +
           trimmed(weights[b]) + "\"/>\n";
    }
    x += "</skin>\n";
  }
  return x;
}

}  // namespace depot::sim
