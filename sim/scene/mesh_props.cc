#include "sim/scene/mesh_props.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/error.h"
#include "sim/scene/depot_objects.h"
#include "sim/scene/mjcf_text.h"

namespace depot::sim {
namespace {

// The file a mesh of an encoded set reads (encode_for_mujoco names it after
// the mesh).
const std::string& msh_file(const MujocoAssetSet& set, size_t mesh) {
  const std::string file = set.mesh_names[mesh] + ".msh";
  for (const auto& [name, bytes] : set.files)
    if (name == file) return name;
  fail(set.mesh_names[mesh], "encoded mesh file missing");
}

}  // namespace

double chair_seat_height(const AssetModel& model) {
  constexpr double kAxis = 0.15;  // m around the vertical axis
  double top = -1.0;
  for (const AssetMesh& mesh : model.meshes)
    for (const Eigen::Vector3f& p : mesh.positions)
      if (std::abs(p.x()) <= kAxis && std::abs(p.y()) <= kAxis) top = std::max(top, double(p.z()));
  if (top <= 0.0) fail(model.source, "no seat above the model's origin (an office chair's column)");
  return top;
}

Eigen::AlignedBox3d model_bounds(const AssetModel& model) {
  Eigen::AlignedBox3d b;
  for (const AssetMesh& mesh : model.meshes)
    for (const Eigen::Vector3f& p : mesh.positions) b.extend(p.cast<double>());
  return b;
}

MeshProps::Model& MeshProps::model(const CatalogAsset& asset) {
  auto it = by_name_.find(asset.name);
  if (it != by_name_.end()) return *it->second;
  auto m = std::make_unique<Model>();
  m->name = asset.name;
  m->prefix = "prop_" + asset.name;
  m->model = load_catalog_asset(catalog(), asset);
  m->set = encode_for_mujoco(m->model, m->prefix);
  m->bounds = model_bounds(m->model);
  Model& out = *m;
  models_.push_back(std::move(m));
  by_name_[asset.name] = &out;
  return out;
}

PropGeoms MeshProps::place(Model& m, const Eigen::Vector3d& scale, const Eigen::Isometry3d& pose) {
  const std::string key = vec(scale);
  auto it = m.scales.find(key);
  if (it == m.scales.end()) {
    const int k = static_cast<int>(m.scales.size());
    it = m.scales.emplace(key, k).first;
    for (size_t i = 0; i < m.set.mesh_names.size(); ++i) {
      m.mesh_xml += "<mesh name=\"" + m.prefix + "_s" + std::to_string(k) + "_mesh" +
                    std::to_string(i) + "\" file=\"" + msh_file(m.set, i) + "\"";
      if (scale != Eigen::Vector3d::Ones()) m.mesh_xml += " scale=\"" + key + "\"";
      m.mesh_xml += "/>\n";
    }
  }
  PropGeoms out;
  out.asset = m.name;
  const std::string placement =
      " pos=\"" + vec(pose.translation()) + "\" quat=\"" + quat(pose.linear()) + "\"";
  for (size_t i = 0; i < m.set.mesh_names.size(); ++i) {
    out.xml += "<geom type=\"mesh\" mesh=\"" + m.prefix + "_s" + std::to_string(it->second) +
               "_mesh" + std::to_string(i) + "\"";
    if (!m.set.material_names[i].empty())
      out.xml += " material=\"" + m.set.material_names[i] + "\"";
    // Visual only: no contacts and no mass, so the body moves as before.
    out.xml += placement + " contype=\"0\" conaffinity=\"0\" density=\"0\"/>\n";
  }
  for (int c = 0; c < 8; ++c)
    out.bounds.extend(
        pose *
        m.bounds.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)).cwiseProduct(scale));
  return out;
}

bool MeshProps::has_model(const std::string& class_name) {
  return !catalog_assets_of_class(catalog(), class_name).empty();
}

double MeshProps::chair_scale() {
  const auto chairs = catalog_assets_of_class(catalog(), "chair");
  if (chairs.empty()) fail(catalog().path, "no asset plays class 'chair'");
  return kChairSeatHeight / chair_seat_height(model(*chairs.front()).model);
}

PropGeoms MeshProps::chair() {
  const double s = chair_scale();
  Model& m = model(*catalog_assets_of_class(catalog(), "chair").front());
  return place(m, Eigen::Vector3d::Constant(s), Eigen::Isometry3d::Identity());
}

PropGeoms MeshProps::desk(const SceneObject& object, const std::string& where) {
  const CatalogAsset* asset = nullptr;
  if (!object.model.empty()) {
    for (const auto& a : catalog().assets)
      if (a.name == object.model) asset = &a;
    if (!asset)
      fail(where, "model '" + object.model + "' is not in the asset catalogue " + catalog().path);
    if (asset->class_name != "desk")
      fail(where, "model '" + object.model + "' plays class '" + asset->class_name +
                      "' in the asset catalogue, not desk");
  } else {
    const auto desks = catalog_assets_of_class(catalog(), "desk");
    if (desks.empty()) fail(catalog().path, "no asset plays class 'desk'");
    asset = desks.front();
  }
  Model& m = model(*asset);
  const Eigen::Vector3d size = m.bounds.sizes();
  if (!(size.minCoeff() > 1e-6) || !(m.bounds.max().z() > 1e-6))
    fail(where, "model '" + asset->name + "' is flat");
  const Eigen::Vector3d scale(kDeskDepth / size.x(), object.length / size.y(),
                              kDeskTopHeight / m.bounds.max().z());
  // Turned half round (its front to -x), footprint centre on the origin.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d centre = m.bounds.center().cwiseProduct(scale);
  pose.translation() = -(pose.linear() * Eigen::Vector3d(centre.x(), centre.y(), 0.0));
  return place(m, scale, pose);
}

std::string MeshProps::asset_xml() const {
  std::string x;
  for (const auto& m : models_) {
    // Textures and materials of the set; its own unscaled <mesh> elements are
    // replaced by the scaled ones place() wrote.
    std::istringstream lines(m->set.asset_xml);
    for (std::string line; std::getline(lines, line);)
      if (line.rfind("<mesh ", 0) != 0) x += line + "\n";
    x += m->mesh_xml;
  }
  return x;
}

void MeshProps::append_files(std::vector<std::pair<std::string, std::string>>& files) const {
  for (const auto& m : models_)
    for (const auto& f : m->set.files) files.push_back(f);
}

}  // namespace depot::sim
