#pragma once
// Furniture drawn as catalogue meshes (scenario key props_style: mesh): the
// office chair for pushables of type chair, and the desk (or table) for
// scene objects of type desk (assets/catalog.yaml, classes chair and desk).
//
// A prop keeps its primitive geoms for physics (made invisible: group 3,
// alpha 0, so neither the colour nor the segmentation pass draws them) and
// gets visual mesh geoms in the same body: no contacts, density 0 (no mass,
// so a chair slides exactly as before), labelled with the body's instance.
//
// Each catalogue model is loaded and encoded once per scene; its MuJoCo
// <mesh> elements are shared by every instance drawn at the same scale (one
// set for all chairs, one per desk size), all reading the same .msh files.
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "sim/assets/asset_catalog.h"
#include "sim/assets/mujoco_mesh.h"
#include "sim/scenario/scene_layout.h"

namespace depot::sim {

// Mesh geoms of one prop instance, in its body's frame.
struct PropGeoms {
  std::string xml;             // <geom type="mesh" .../> elements for the body
  Eigen::AlignedBox3d bounds;  // the placed, scaled meshes' bounds
  std::string asset;           // the catalogue entry drawn
};

// The height of a chair model's seat: the highest vertex within 0.15 m of
// the model's vertical axis (the column of an office chair, its origin),
// where the seat cushion's top is.
double chair_seat_height(const AssetModel& model);

// Bounds of every mesh vertex of a model (model frame).
Eigen::AlignedBox3d model_bounds(const AssetModel& model);

class MeshProps {
 public:
  // The catalogue is read when the first prop is asked for.
  explicit MeshProps(LazyAssetCatalog& catalog) : catalog_(catalog) {}

  // Whether the catalogue has a model of `class_name` (a class without one
  // stays primitive, like an actor's).
  bool has_model(const std::string& class_name);

  // A chair's visual meshes: the first catalogue asset of class chair,
  // facing +x with its column on the body's origin, scaled uniformly so its
  // seat's top is at kChairSeatHeight (sim/scene/depot_objects.h).
  PropGeoms chair();
  // Uniform scale chair() applies (for tests and reports).
  double chair_scale();

  // A desk's visual meshes: the catalogue asset `object.model` (a desk-class
  // entry) or else the first asset of class desk, its front (+x in the
  // model: where one sits) turned to the desk's -x, where the primitive desk
  // is used from, its footprint centred and scaled to the primitive desk's
  // top: kDeskDepth along x, `object.length` along y, kDeskTopHeight tall (so
  // the monitor stands on it as before). `where` names the layout object in
  // errors.
  PropGeoms desk(const SceneObject& object, const std::string& where);

  // <texture>/<material>/<mesh> elements of every model used so far (for an
  // <asset> section), and their VFS files appended to `files`.
  std::string asset_xml() const;
  void append_files(std::vector<std::pair<std::string, std::string>>& files) const;
  bool empty() const { return models_.empty(); }
  // How many catalogue models were loaded and encoded (each once).
  size_t models_loaded() const { return models_.size(); }

 private:
  struct Model {
    std::string name;    // catalogue entry
    std::string prefix;  // unique asset name prefix, "prop_<entry>"
    AssetModel model;
    MujocoAssetSet set;                 // materials, textures, .msh files (meshes at scale 1)
    Eigen::AlignedBox3d bounds;         // model frame, scale 1
    std::map<std::string, int> scales;  // "sx sy sz" -> index of its <mesh> set
    std::string mesh_xml;               // <mesh> elements of every scale used
  };
  const AssetCatalog& catalog() { return catalog_.get(); }
  Model& model(const CatalogAsset& asset);
  // Mesh geoms of `m` scaled by `scale` (model axes) then placed by `pose`.
  PropGeoms place(Model& m, const Eigen::Vector3d& scale, const Eigen::Isometry3d& pose);

  LazyAssetCatalog& catalog_;
  std::vector<std::unique_ptr<Model>> models_;  // in order of first use
  std::map<std::string, Model*> by_name_;
};

}  // namespace depot::sim
