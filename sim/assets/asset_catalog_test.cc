// The shipped asset catalogue loads, every entry's model loads with its
// clips and colours, and bad entries fail with one line naming the
// catalogue and the entry.
#include "sim/assets/asset_catalog.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/config_path.h"
#include "common/testing/error_of.h"
#include "sim/assets/testing/asset_fixtures.h"

namespace depot::sim {
namespace {

using testing::scratch_file;

const std::string kCatalog = std::string(DEPOT_SOURCE_DIR) + "/assets/catalog.yaml";

const ClassTable& classes() {
  static const ClassTable table =
      ClassTable::load(std::string(DEPOT_SOURCE_DIR) + "/scenes/classes.yaml");
  return table;
}

TEST(AssetCatalog, ShippedCatalogueNamesRealFilesAndClasses) {
  const AssetCatalog c = load_asset_catalog(kCatalog, classes());
  EXPECT_EQ(catalog_assets_of_class(c, "person").size(), 5u);
  for (const char* cls : {"dog", "cat", "pig", "bird", "chair", "desk"})
    EXPECT_FALSE(catalog_assets_of_class(c, cls).empty()) << cls;
  const CatalogAsset& dog = catalog_asset(c, "dog");
  EXPECT_EQ(dog.label_class, "dog");
  EXPECT_THAT(dog.clip_file, ::testing::HasSubstr("fox-animations.glb"));
  EXPECT_DOUBLE_EQ(dog.options.target_height, 0.6);
  EXPECT_EQ(catalog_asset(c, "worker_male").clips.at("walk"), "Walk_procedural");
  EXPECT_EQ(catalog_asset(c, "worker_male").file.rfind(shared_data_dir(), 0), 0u);
  EXPECT_EQ(error_of([&] { catalog_asset(c, "unicorn"); }),
            kCatalog + ": no asset named 'unicorn'");
}

TEST(AssetCatalog, EveryEntryLoadsWithItsClipsAndColours) {
  const AssetCatalog c = load_asset_catalog(kCatalog, classes());
  for (const CatalogAsset& a : c.assets) {
    const AssetModel m = load_catalog_asset(c, a);
    EXPECT_FALSE(m.meshes.empty()) << a.name;
    EXPECT_NEAR(m.bounds.min().z(), 0.0, 1e-4) << a.name;
    if (a.options.target_height > 0) {
      EXPECT_NEAR(m.bounds.max().z(), a.options.target_height, 1e-4) << a.name;
    }
    for (const auto& [role, clip] : a.clips)
      EXPECT_GE(find_clip(m, clip), 0) << a.name << " " << clip;
    if (a.name == "cat") {
      for (const auto& mat : m.materials)
        if (mat.name == "Grey") {
          EXPECT_NEAR(mat.rgba[0], 0.80f, 1e-6f);
        }
    }
  }
}

// A catalogue with one entry, written to the scratch folder.
std::string catalogue(const std::string& name, const std::string& entry) {
  return scratch_file(name + ".yaml", "assets:\n  thing:\n" + entry);
}

const std::string kTable = "    file: ${DEPOT_SHARED_DATA}/assets/props/Table.fbx\n";

std::string load_error(const std::string& path) {
  return error_of([&] { load_asset_catalog(path, classes()); }, "(no error)");
}

TEST(AssetCatalogErrors, UnknownClassMissingFileBadKeys) {
  const std::string unknown = catalogue("unknown_class", kTable + "    class: unicorn\n");
  EXPECT_EQ(load_error(unknown),
            unknown + ": asset 'thing': unknown class 'unicorn' (not in the class table)");

  const std::string label = catalogue("unknown_label", kTable + "    label_class: horse\n");
  EXPECT_EQ(load_error(label),
            label + ": asset 'thing': unknown label_class 'horse' (not in the class table)");

  const std::string missing =
      catalogue("missing_file", "    file: ${DEPOT_SHARED_DATA}/assets/props/Sofa.fbx\n");
  EXPECT_EQ(load_error(missing).rfind(missing + ": asset 'thing': model file not found: " +
                                          shared_data_dir() + "/assets/props/Sofa.fbx",
                                      0),
            0u)
      << load_error(missing);

  const std::string typo = catalogue("typo", kTable + "    target_hieght: 1\n");
  EXPECT_EQ(load_error(typo), typo + ": asset 'thing': unknown key 'target_hieght'");

  const std::string axis = catalogue("axis", kTable + "    up: sideways\n");
  EXPECT_EQ(load_error(axis),
            axis + ": asset 'thing': unknown axis 'sideways' (expected +x, -x, +y, -y, +z or -z)");

  const std::string both = catalogue("both", kTable + "    scale: 0.01\n    target_height: 1\n");
  EXPECT_EQ(load_error(both), both + ": asset 'thing': give 'scale' or 'target_height', not both");

  const std::string none = scratch_file("no_assets.yaml", "things: {}\n");
  EXPECT_EQ(load_error(none), none + ": expected a map 'assets: {name: {...}}'");
}

TEST(AssetCatalogErrors, UnknownClipAndMaterialWhenTheModelLoads) {
  const std::string clip =
      catalogue("unknown_clip",
                "    file: ${DEPOT_SHARED_DATA}/assets/animals/cat/Cat.fbx\n    class: cat\n"
                "    target_height: 0.36\n    clips: {walk: Walking}\n");
  const AssetCatalog c = load_asset_catalog(clip, classes());
  const std::string cat = shared_data_dir() + "/assets/animals/cat/Cat.fbx";
  EXPECT_EQ(error_of([&] { load_catalog_asset(c, c.assets[0]); }),
            clip + ": asset 'thing': " + cat +
                ": no clip named 'Walking' (clips: CatArmature|Idle, CatArmature|Walking)");

  const std::string colour =
      catalogue("unknown_material",
                "    file: ${DEPOT_SHARED_DATA}/assets/animals/cat/Cat.fbx\n    "
                "target_height: 0.36\n    colours: {Orange: [1, 0.5, 0]}\n");
  const AssetCatalog c2 = load_asset_catalog(colour, classes());
  EXPECT_EQ(error_of([&] { load_catalog_asset(c2, c2.assets[0]); }),
            colour + ": asset 'thing': colour for material 'Orange', which " + cat +
                " does not have (materials: White, Grey, Pink)");
}

}  // namespace
}  // namespace depot::sim
