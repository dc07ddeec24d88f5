#pragma once
// The asset catalogue (assets/catalog.yaml): which shared model file plays
// which simulator class, how its axes and units become the model frame, its
// clips by role, the class its pixels are labelled with, and colours for
// materials the file leaves grey. Loading it checks everything that needs no
// model file read (classes, files, axes, keys); clip and material names are
// checked when an entry's model is loaded. Every error is one line naming the
// catalogue file and the entry.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "sim/assets/asset_loader.h"
#include "sim/scenario/class_table.h"

namespace depot::sim {

struct CatalogAsset {
  std::string name;          // the entry's key
  std::string file;          // resolved model path
  std::string class_name;    // simulator class it plays; "" = described, not used yet
  std::string label_class;   // class written to labels and boxes (default class_name)
  AssetLoadOptions options;  // axes, scale or target height; clips filled from `clips`
  std::map<std::string, std::string> clips;  // role (walk, idle...) -> clip name
  std::string clip_file;  // resolved file holding the clips (bones matched by name), or ""
  std::map<std::string, Eigen::Vector4f> colours;  // material name -> sRGB rgba
  // Metres of ground one cycle of the walk clip covers (0: not given).
  double stride = 0;
  // Legs swung procedurally when the file has no walk clip: per leg the bone
  // at the hip and, optionally, a foot bone that is not its descendant (IK
  // rigs) and is carried along; front left, front right, back left, back
  // right.
  std::vector<std::vector<std::string>> legs;
};

struct AssetCatalog {
  std::string path;
  std::vector<CatalogAsset> assets;
};

// Reads and validates the catalogue at `path` against the simulator's
// classes. Paths in it are relative to its folder or start with
// ${DEPOT_SHARED_DATA} (common/config_path.h).
AssetCatalog load_asset_catalog(const std::string& path, const ClassTable& classes);

// The catalogue at `path`, read at the first get(): a scene drawn from
// primitives never reads it, and the mesh props and mesh actors of one scene
// share one read.
class LazyAssetCatalog {
 public:
  LazyAssetCatalog(const ClassTable& classes, std::string path)
      : classes_(classes), path_(std::move(path)) {}
  const AssetCatalog& get() {
    if (!catalog_) catalog_ = std::make_unique<AssetCatalog>(load_asset_catalog(path_, classes_));
    return *catalog_;
  }

 private:
  const ClassTable& classes_;
  std::string path_;
  std::unique_ptr<AssetCatalog> catalog_;
};

// The entry named `name`; fails naming the catalogue.
const CatalogAsset& catalog_asset(const AssetCatalog& catalog, const std::string& name);

// Entries that play `class_name`, in catalogue order.
std::vector<const CatalogAsset*> catalog_assets_of_class(const AssetCatalog& catalog,
                                                         const std::string& class_name);

// Loads an entry's model with its options, adds clips from clip_file and
// applies its colours. Fails with "<catalogue>: asset '<name>': <problem>"
// (the problem names the model file when it is the model's), e.g. for a clip
// or material name the file does not have.
AssetModel load_catalog_asset(const AssetCatalog& catalog, const CatalogAsset& asset);

}  // namespace depot::sim
