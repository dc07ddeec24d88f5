#include "slam/detect/detector_config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>

#include "common/config_path.h"
#include "common/error.h"
#include "common/yaml_fields.h"
#include "common/yaml_file.h"

namespace depot::slam {

const std::vector<std::string>& dnn_detector_types() {
  static const std::vector<std::string> types{"yolov5", "darknet", "fastestdet"};
  return types;
}

DetectorConfig load_detector_config(const std::string& yaml_path) {
  YAML::Node root = load_yaml_file(yaml_path, "detector config");
  if (!root.IsMap()) fail(yaml_path, "detector config must be a YAML map");

  static const std::vector<std::string> known{"type",       "model",       "config",
                                              "names",      "input_width", "input_height",
                                              "confidence", "nms",         "classes"};
  check_known_keys(root, known, yaml_path);

  const YamlFields fields(root, yaml_path, "detector config");
  DetectorConfig c;
  c.type = fields.str("type");
  const auto& types = dnn_detector_types();
  if (c.type.empty()) fail(yaml_path, "missing 'type' (yolov5, darknet or fastestdet)");
  if (std::find(types.begin(), types.end(), c.type) == types.end())
    fail(yaml_where(yaml_path, root["type"]), "unknown detector type '" + printable(c.type) +
                                                  "' (expected yolov5, darknet or fastestdet)");

  const std::string folder = std::filesystem::path(yaml_path).parent_path().string();
  c.model = resolve_config_path(fields.str("model"), folder);
  c.config = resolve_config_path(fields.str("config"), folder);
  c.names = resolve_config_path(fields.str("names"), folder);
  if (c.model.empty()) fail(yaml_path, "missing 'model' (path of the model file)");
  if (c.names.empty()) fail(yaml_path, "missing 'names' (path of the class names file)");
  if (c.type == "darknet" && c.config.empty())
    fail(yaml_path, "missing 'config' (path of the Darknet .cfg file)");
  if (c.type != "darknet" && !c.config.empty())
    fail(yaml_where(yaml_path, root["config"]), "'config' is for type darknet only");

  c.input_width = fields.number<int>("input_width", 0, 0, 4096);
  c.input_height = fields.number<int>("input_height", 0, 0, 4096);
  if ((c.input_width == 0) != (c.input_height == 0))
    fail(yaml_path, "give both 'input_width' and 'input_height' or neither");
  c.confidence = fields.number<float>("confidence", c.confidence, 0.0, 1.0);
  c.nms = fields.number<float>("nms", c.nms, 0.0, 1.0);

  if (const YAML::Node cls = root["classes"]) {
    if (!cls.IsSequence() && !cls.IsNull())
      fail(yaml_where(yaml_path, cls), "'classes' must be a list of class names");
    for (const YAML::Node& n : cls) {
      if (!n.IsScalar() || n.as<std::string>().empty())
        fail(yaml_where(yaml_path, n), "'classes' entries must be class names");
      c.classes.push_back(n.as<std::string>());
    }
  }
  return c;
}

std::vector<bool> wanted_classes(const std::vector<std::string>& names,
                                 const std::vector<std::string>& wanted,
                                 const std::string& names_path) {
  if (wanted.empty()) return std::vector<bool>(names.size(), true);
  std::vector<bool> keep(names.size(), false);
  for (const std::string& w : wanted) {
    const auto it = std::find(names.begin(), names.end(), w);
    if (it == names.end())
      fail(names_path, "wanted class '" + w + "' is not one of the model's " +
                           std::to_string(names.size()) + " classes");
    keep[static_cast<size_t>(it - names.begin())] = true;
  }
  return keep;
}

}  // namespace depot::slam
