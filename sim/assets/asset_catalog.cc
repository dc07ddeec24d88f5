#include "sim/assets/asset_catalog.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <set>

#include "common/config_path.h"
#include "common/error.h"
#include "common/yaml_file.h"

namespace fs = std::filesystem;

namespace depot::sim {
namespace {

const std::set<std::string> kKeys = {
    "file",  "class",     "label_class", "up",     "forward", "scale", "target_height",
    "clips", "clip_file", "colours",     "center", "stride",  "legs"};

std::string resolve_file(const YAML::Node& value, const std::string& catalog_dir,
                         const std::string& where, const std::string& key) {
  if (!value.IsScalar() || value.as<std::string>().empty())
    fail(where, "'" + key + "' must be a file path");
  const std::string resolved = resolve_config_path(value.as<std::string>(), catalog_dir);
  if (!fs::is_regular_file(resolved)) {
    std::string hint;
    if (names_shared_data(value.as<std::string>()))
      hint = " (the shared data folder is " + shared_data_dir() + "; set " + kSharedDataVariable +
             " to move it)";
    fail(where, key + " not found: " + resolved + hint);
  }
  std::string ext = fs::path(resolved).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  const auto& ok = supported_model_extensions();
  if (std::find(ok.begin(), ok.end(), ext) == ok.end())
    fail(where, key + " " + resolved + " has an unsupported format '" + ext + "'");
  return resolved;
}

double positive(const YAML::Node& value, const std::string& where, const std::string& key) {
  double v = 0;
  try {
    v = value.as<double>();
  } catch (const YAML::Exception&) {
    fail(where, "'" + key + "' must be a number");
  }
  if (!(v > 0)) fail(where, "'" + key + "' must be positive");
  return v;
}

Eigen::Vector4f colour(const YAML::Node& value, const std::string& where) {
  if (!value.IsSequence() || (value.size() != 3 && value.size() != 4))
    fail(where, "a colour is [r, g, b] or [r, g, b, a] with values 0..1");
  Eigen::Vector4f c(1, 1, 1, 1);
  for (size_t i = 0; i < value.size(); ++i) {
    try {
      c[i] = value[i].as<float>();
    } catch (const YAML::Exception&) {
      fail(where, "a colour is [r, g, b] or [r, g, b, a] with values 0..1");
    }
    if (c[i] < 0 || c[i] > 1) fail(where, "colour values must lie in 0..1");
  }
  return c;
}

CatalogAsset read_entry(const std::string& name, const YAML::Node& node,
                        const std::string& catalog_path, const ClassTable& classes) {
  const std::string where = catalog_path + ": asset '" + name + "'";
  if (!node.IsMap()) fail(where, "expected a map of settings");
  for (const auto& kv : node) {
    const std::string key = kv.first.as<std::string>();
    if (!kKeys.count(key)) fail(where, "unknown key '" + key + "'");
  }
  const std::string dir = fs::path(catalog_path).parent_path().string();
  CatalogAsset a;
  a.name = name;
  if (!node["file"]) fail(where, "missing 'file'");
  a.file = resolve_file(node["file"], dir, where, "model file");
  if (node["clip_file"]) a.clip_file = resolve_file(node["clip_file"], dir, where, "clip file");

  auto known_class = [&](const std::string& key) {
    const std::string c = node[key].as<std::string>();
    if (!classes.contains(c))
      fail(where, "unknown " + key + " '" + c + "' (not in the class table)");
    return c;
  };
  if (node["class"]) a.class_name = known_class("class");
  a.label_class = node["label_class"] ? known_class("label_class") : a.class_name;

  if (node["up"]) a.options.up = parse_axis(node["up"].as<std::string>(), where);
  if (node["forward"]) a.options.forward = parse_axis(node["forward"].as<std::string>(), where);
  model_rotation(a.options.up, a.options.forward, where);  // perpendicular?
  if (node["scale"] && node["target_height"])
    fail(where, "give 'scale' or 'target_height', not both");
  if (node["scale"]) a.options.scale = positive(node["scale"], where, "scale");
  if (node["target_height"])
    a.options.target_height = positive(node["target_height"], where, "target_height");

  if (node["center"]) a.options.center_xy = node["center"].as<bool>();

  if (const YAML::Node clips = node["clips"]) {
    if (!clips.IsMap()) fail(where, "'clips' must map roles to clip names (walk: Walk)");
    for (const auto& kv : clips) a.clips[kv.first.as<std::string>()] = kv.second.as<std::string>();
  }
  if (!a.clip_file.empty() && a.clips.empty()) fail(where, "'clip_file' without 'clips'");
  if (a.clip_file.empty())
    for (const auto& [role, clip] : a.clips) a.options.clips.push_back(clip);

  if (node["stride"]) a.stride = positive(node["stride"], where, "stride");
  if (const YAML::Node legs = node["legs"]) {
    const std::string form =
        "'legs' lists four legs (front left, front right, back left, back right), each "
        "[hip bone] or [hip bone, foot bone]";
    if (!legs.IsSequence() || legs.size() != 4) fail(where, form);
    for (const auto& leg : legs) {
      if (!leg.IsSequence() || leg.size() < 1 || leg.size() > 2) fail(where, form);
      std::vector<std::string> bones;
      for (const auto& b : leg) bones.push_back(b.as<std::string>());
      a.legs.push_back(bones);
    }
  }

  if (const YAML::Node colours = node["colours"]) {
    if (!colours.IsMap()) fail(where, "'colours' must map material names to colours");
    for (const auto& kv : colours) {
      const std::string material = kv.first.as<std::string>();
      a.colours[material] = colour(kv.second, where + ": colour of '" + material + "'");
    }
  }
  return a;
}

}  // namespace

AssetCatalog load_asset_catalog(const std::string& path, const ClassTable& classes) {
  const YAML::Node root = load_yaml_file(path, "asset catalogue");
  const YAML::Node assets = root["assets"];
  if (!assets || !assets.IsMap()) fail(path, "expected a map 'assets: {name: {...}}'");
  AssetCatalog catalog;
  catalog.path = path;
  try {
    for (const auto& kv : assets)
      catalog.assets.push_back(read_entry(kv.first.as<std::string>(), kv.second, path, classes));
  } catch (const YAML::Exception& e) {
    fail(path + ":" + std::to_string(e.mark.line + 1), "invalid entry: " + e.msg);
  }
  return catalog;
}

const CatalogAsset& catalog_asset(const AssetCatalog& catalog, const std::string& name) {
  for (const auto& a : catalog.assets)
    if (a.name == name) return a;
  fail(catalog.path, "no asset named '" + name + "'");
}

std::vector<const CatalogAsset*> catalog_assets_of_class(const AssetCatalog& catalog,
                                                         const std::string& class_name) {
  std::vector<const CatalogAsset*> out;
  for (const auto& a : catalog.assets)
    if (a.class_name == class_name) out.push_back(&a);
  return out;
}

AssetModel load_catalog_asset(const AssetCatalog& catalog, const CatalogAsset& asset) {
  const std::string where = catalog.path + ": asset '" + asset.name + "'";
  AssetModel model;
  try {
    model = load_asset(asset.file, asset.options);
    if (!asset.clip_file.empty()) {
      std::vector<std::string> names;
      for (const auto& [role, clip] : asset.clips) names.push_back(clip);
      load_clips_into(model, asset.clip_file, names, /*rotations_only=*/true);
    }
  } catch (const Error& e) {
    fail(where, e.what());
  }
  for (const auto& [material, rgba] : asset.colours) {
    bool found = false;
    for (auto& m : model.materials) {
      if (m.name != material) continue;
      m.rgba = rgba;
      found = true;
    }
    if (!found) {
      std::string names;
      for (const auto& m : model.materials) names += (names.empty() ? "" : ", ") + m.name;
      fail(where, "colour for material '" + material + "', which " + asset.file +
                      " does not have (materials: " + names + ")");
    }
  }
  return model;
}

}  // namespace depot::sim
