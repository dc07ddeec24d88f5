#include "sim/assets/mujoco_mesh.h"

#include <cstdint>
#include <cstring>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "common/error.h"
#include "common/number_text.h"
#include "common/png_codec.h"

namespace depot::sim {
namespace {

static_assert(sizeof(float) == 4 && sizeof(int32_t) == 4, "MSH stores 32-bit values");

template <typename T>
void append(std::string& out, const T* data, size_t count) {
  out.append(reinterpret_cast<const char*>(data), count * sizeof(T));
}

}  // namespace

std::string encode_msh(const std::vector<Eigen::Vector3f>& positions,
                       const std::vector<Eigen::Vector3f>& normals,
                       const std::vector<Eigen::Vector2f>& uvs,
                       const std::vector<Eigen::Vector3i>& triangles, const std::string& where) {
  const size_t nv = positions.size();
  if (nv < 4)
    fail(where, "MuJoCo meshes need at least 4 vertices, this one has " + std::to_string(nv));
  if (!normals.empty() && normals.size() != nv)
    fail(where, "normal count differs from vertex count");
  if (!uvs.empty() && uvs.size() != nv) fail(where, "UV count differs from vertex count");
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || static_cast<size_t>(t[k]) >= nv) fail(where, "triangle index out of range");
  const int32_t header[4] = {static_cast<int32_t>(nv), static_cast<int32_t>(normals.size()),
                             static_cast<int32_t>(uvs.size()),
                             static_cast<int32_t>(triangles.size())};
  std::string out;
  out.reserve(16 + nv * 32 + triangles.size() * 12);
  append(out, header, 4);
  // Eigen's fixed vectors are plain arrays of floats/ints.
  append(out, positions.data()->data(), 3 * nv);
  if (!normals.empty()) append(out, normals.data()->data(), 3 * nv);
  if (!uvs.empty()) append(out, uvs.data()->data(), 2 * nv);
  if (!triangles.empty()) append(out, triangles.data()->data(), 3 * triangles.size());
  return out;
}

std::string encode_msh(const AssetMesh& mesh, const std::string& where) {
  return encode_msh(mesh.positions, mesh.normals, mesh.uvs, mesh.triangles, where);
}

std::string encode_texture_png(const cv::Mat& image) {
  cv::Mat bgr = image;
  if (image.channels() == 4) cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
  if (image.channels() == 1) cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  // Level 0 (stored): the bytes only travel through memory to MuJoCo, which
  // decodes them at once; deflating ~4 MB of texels per person costs more
  // than it saves.
  const std::vector<unsigned char> buf = encode_png(bgr, PngKind::kColor, 0);
  return std::string(buf.begin(), buf.end());
}

MujocoAssetSet encode_for_mujoco(const AssetModel& model, const std::string& prefix) {
  MujocoAssetSet set;
  std::ostringstream textures, materials, meshes;
  // Materials (and their textures) that some mesh uses.
  std::map<int, std::string> material_name;
  for (const AssetMesh& mesh : model.meshes) {
    const int mi = mesh.material;
    if (mi < 0 || material_name.count(mi)) continue;
    const AssetMaterial& mat = model.materials[mi];
    const std::string name = prefix + "_mat" + std::to_string(mi);
    material_name[mi] = name;
    materials << "<material name=\"" << name << "\"";
    if (!mat.texture.empty()) {
      const std::string tex = prefix + "_tex" + std::to_string(mi);
      set.files.emplace_back(tex + ".png", encode_texture_png(mat.texture));
      textures << "<texture name=\"" << tex << "\" type=\"2d\" file=\"" << tex << ".png\"/>\n";
      materials << " texture=\"" << tex << "\"";
    }
    materials << " rgba=\"" << shortest_number(mat.rgba[0]) << " " << shortest_number(mat.rgba[1])
              << " " << shortest_number(mat.rgba[2]) << " " << shortest_number(mat.rgba[3])
              << "\" specular=\"0\" shininess=\"0\" reflectance=\"0\"/>\n";
  }
  for (size_t i = 0; i < model.meshes.size(); ++i) {
    const AssetMesh& mesh = model.meshes[i];
    const std::string name = prefix + "_mesh" + std::to_string(i);
    const std::string file = name + ".msh";
    set.files.emplace_back(file, encode_msh(mesh, model.source + ": mesh '" + mesh.name + "'"));
    meshes << "<mesh name=\"" << name << "\" file=\"" << file << "\"/>\n";
    set.mesh_names.push_back(name);
    set.material_names.push_back(mesh.material >= 0 ? material_name[mesh.material] : "");
  }
  set.asset_xml = textures.str() + materials.str() + meshes.str();
  return set;
}

std::string mesh_geoms_xml(const MujocoAssetSet& set, const std::string& extra) {
  std::string out;
  for (size_t i = 0; i < set.mesh_names.size(); ++i) {
    out += "<geom type=\"mesh\" mesh=\"" + set.mesh_names[i] + "\"";
    if (!set.material_names[i].empty()) out += " material=\"" + set.material_names[i] + "\"";
    out += " contype=\"0\" conaffinity=\"0\"";
    if (!extra.empty()) out += " " + extra;
    out += "/>\n";
  }
  return out;
}

Eigen::Isometry3d geom_in_body(const mjModel* m, int geom) {
  const mjtNum* p = m->geom_pos + 3 * geom;
  const mjtNum* q = m->geom_quat + 4 * geom;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  return pose;
}

void write_mesh_vertices(mjModel* m, int geom, const std::vector<Eigen::Vector3f>& positions,
                         const std::vector<Eigen::Vector3f>& normals) {
  if (geom < 0 || geom >= m->ngeom || m->geom_type[geom] != mjGEOM_MESH)
    fail("write_mesh_vertices", "geom " + std::to_string(geom) + " is not a mesh geom");
  const int mesh = m->geom_dataid[geom];
  const int n = m->mesh_vertnum[mesh];
  if (static_cast<int>(positions.size()) != n || static_cast<int>(normals.size()) != n)
    fail("write_mesh_vertices", "mesh " + std::to_string(mesh) + " has " + std::to_string(n) +
                                    " vertices, got " + std::to_string(positions.size()));
  const Eigen::Isometry3d body_from_geom = geom_in_body(m, geom);
  const Eigen::Matrix3f r_t = body_from_geom.linear().transpose().cast<float>();
  const Eigen::Vector3f p = body_from_geom.translation().cast<float>();
  float* vert = m->mesh_vert + 3 * m->mesh_vertadr[mesh];
  float* normal = m->mesh_normal + 3 * m->mesh_vertadr[mesh];
  for (int i = 0; i < n; ++i) {
    Eigen::Map<Eigen::Vector3f>(vert + 3 * i) = r_t * (positions[i] - p);
    Eigen::Map<Eigen::Vector3f>(normal + 3 * i) = r_t * normals[i];
  }
}

}  // namespace depot::sim
