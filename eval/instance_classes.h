#pragma once
// Which class each instance of a simulated dataset belongs to (objects.json),
// and the mask of a class's pixels in a label image (labels/, 16-bit ids).
#include <map>
#include <set>
#include <string>

#include <opencv2/core.hpp>

namespace depot::eval {

// What objects.json says of an instance.
struct InstanceInfo {
  std::string class_name;
  std::string model;  // catalogue asset it is drawn from ("asset"), or ""
};

// Instance id -> its class and model, from `dataset`/objects.json. Throws
// depot::Error naming the file when it is missing or malformed.
std::map<int, InstanceInfo> read_instances(const std::string& dataset);

// Instance id -> class (read_instances, classes only).
std::map<int, std::string> read_instance_classes(const std::string& dataset);

// The ids of the instances of `class_name`.
std::set<int> instances_of(const std::map<int, std::string>& classes,
                           const std::string& class_name);

// CV_8U, 255 where the label (CV_16U) is one of `ids`, else 0.
cv::Mat instances_mask(const cv::Mat& labels, const std::set<int>& ids);

}  // namespace depot::eval
