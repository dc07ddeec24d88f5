#include "eval/image_labels.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>

#include "common/config_path.h"
#include "common/error.h"
#include "common/yaml_file.h"

namespace depot::eval {
namespace {

int coordinate(const std::string& path, const YAML::Node& box, const char* key) {
  const YAML::Node n = box[key];
  if (!n) fail(yaml_where(path, box), std::string("box has no '") + key + "'");
  try {
    return n.as<int>();
  } catch (const YAML::Exception&) {
    fail(yaml_where(path, n), std::string("'") + key + "' must be a whole number of pixels");
  }
}

}  // namespace

ImageLabels read_image_labels(const std::string& path) {
  const YAML::Node root = load_yaml_file(path, "image labels");
  if (!root.IsMap()) fail(path, "image labels must be a YAML map (keys: classes, images)");
  check_known_keys(root, {"classes", "images"}, path);
  ImageLabels labels;
  labels.path = path;
  const YAML::Node classes = root["classes"];
  if (!classes || !classes.IsSequence() || classes.size() == 0)
    fail(path, "'classes' must list the classes the boxes name");
  for (const YAML::Node& c : classes) {
    if (!c.IsScalar() || c.Scalar().empty()) fail(yaml_where(path, c), "a class must be a name");
    labels.classes.push_back(c.Scalar());
  }
  const YAML::Node images = root["images"];
  if (!images || !images.IsMap() || images.size() == 0)
    fail(path, "'images' must map image files to their boxes");
  const std::string folder = std::filesystem::path(path).parent_path().string();
  for (const auto& kv : images) {
    LabelledImage image;
    image.where = yaml_where(path, kv.first);
    image.path = resolve_config_path(kv.first.Scalar(), folder.empty() ? "." : folder);
    if (!kv.second.IsSequence() && !kv.second.IsNull())
      fail(yaml_where(path, kv.second), "an image's boxes must be a list (empty for no object)");
    for (const YAML::Node& b : kv.second) {
      if (!b.IsMap()) fail(yaml_where(path, b), "a box must be {class, x1, y1, x2, y2}");
      check_known_keys(b, {"class", "x1", "y1", "x2", "y2"}, path);
      const YAML::Node cls = b["class"];
      if (!cls || !cls.IsScalar()) fail(yaml_where(path, b), "box has no 'class'");
      if (std::find(labels.classes.begin(), labels.classes.end(), cls.Scalar()) ==
          labels.classes.end())
        fail(yaml_where(path, cls), "class '" + cls.Scalar() + "' is not in 'classes'");
      const int x1 = coordinate(path, b, "x1"), y1 = coordinate(path, b, "y1");
      const int x2 = coordinate(path, b, "x2"), y2 = coordinate(path, b, "y2");
      if (x1 < 0 || y1 < 0 || x2 <= x1 || y2 <= y1)
        fail(yaml_where(path, b), "box " + std::to_string(x1) + " " + std::to_string(y1) + " " +
                                      std::to_string(x2) + " " + std::to_string(y2) +
                                      " is empty or has negative coordinates");
      TruthObject box;
      box.class_name = cls.Scalar();
      box.box = cv::Rect2f(static_cast<float>(x1), static_cast<float>(y1),
                           static_cast<float>(x2 - x1), static_cast<float>(y2 - y1));
      box.visible_pixels = box.box.area();
      image.boxes.push_back(box);
      image.box_where.push_back(yaml_where(path, b));
    }
    labels.images.push_back(std::move(image));
  }
  return labels;
}

void check_image_size(const LabelledImage& image, int width, int height) {
  for (size_t i = 0; i < image.boxes.size(); ++i) {
    const cv::Rect2f& b = image.boxes[i].box;
    if (b.x + b.width <= width && b.y + b.height <= height) continue;
    fail(image.box_where[i], "box " + std::to_string(static_cast<int>(b.x)) + " " +
                                 std::to_string(static_cast<int>(b.y)) + " " +
                                 std::to_string(static_cast<int>(b.x + b.width)) + " " +
                                 std::to_string(static_cast<int>(b.y + b.height)) +
                                 " is outside the " + std::to_string(width) + "x" +
                                 std::to_string(height) + " image " + image.path);
  }
}

}  // namespace depot::eval
