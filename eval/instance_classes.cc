#include "eval/instance_classes.h"

#include "common/error.h"

namespace depot::eval {

std::map<int, std::string> instance_classes(const dataset::ObjectsFile& objects) {
  std::map<int, std::string> classes;
  for (const dataset::ObjectRecord& o : objects.objects) classes[o.id] = o.class_name;
  return classes;
}

std::map<int, std::string> instance_assets(const dataset::ObjectsFile& objects) {
  std::map<int, std::string> assets;
  for (const dataset::ObjectRecord& o : objects.objects) assets[o.id] = o.asset;
  return assets;
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
