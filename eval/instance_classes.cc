#include "eval/instance_classes.h"

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/error.h"

namespace depot::eval {

std::map<int, InstanceInfo> read_instances(const std::string& dataset) {
  const std::string path = (std::filesystem::path(dataset) / "objects.json").string();
  std::ifstream in(path);
  if (!in) fail(path, "cannot open file (the dataset's objects; not a simulated dataset?)");
  std::map<int, InstanceInfo> instances;
  try {
    const nlohmann::json doc = nlohmann::json::parse(in);
    for (const nlohmann::json& o : doc.at("instances"))
      instances[o.at("id").get<int>()] = {o.at("class").get<std::string>(),
                                          o.value("asset", std::string())};
  } catch (const nlohmann::json::exception& e) {
    fail(path, std::string("not a dataset's objects file: ") + e.what());
  }
  return instances;
}

std::map<int, std::string> read_instance_classes(const std::string& dataset) {
  std::map<int, std::string> classes;
  for (const auto& [id, info] : read_instances(dataset)) classes[id] = info.class_name;
  return classes;
}

std::set<int> instances_of(const std::map<int, std::string>& classes,
                           const std::string& class_name) {
  std::set<int> ids;
  for (const auto& [id, c] : classes)
    if (c == class_name) ids.insert(id);
  return ids;
}

cv::Mat instances_mask(const cv::Mat& labels, const std::set<int>& ids) {
  if (labels.type() != CV_16UC1) fail("instances mask", "labels must be a 16-bit image");
  cv::Mat mask(labels.size(), CV_8UC1);
  for (int y = 0; y < labels.rows; ++y) {
    const uint16_t* l = labels.ptr<uint16_t>(y);
    uint8_t* m = mask.ptr<uint8_t>(y);
    for (int x = 0; x < labels.cols; ++x) m[x] = ids.count(l[x]) ? 255 : 0;
  }
  return mask;
}

}  // namespace depot::eval
