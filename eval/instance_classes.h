#pragma once
// Which class each instance of a simulated dataset belongs to (its
// objects.json, read by dataset/objects.h), and the mask of a class's pixels
// in a label image (labels/, 16-bit ids).
#include <map>
#include <set>
#include <string>

#include <opencv2/core.hpp>

#include "dataset/objects.h"

namespace depot::eval {

// Instance id -> its class.
std::map<int, std::string> instance_classes(const dataset::ObjectsFile& objects);
// Instance id -> the catalogue asset it is drawn from ("" for primitives).
std::map<int, std::string> instance_assets(const dataset::ObjectsFile& objects);

// The ids of the instances of `class_name`.
std::set<int> instances_of(const std::map<int, std::string>& classes,
                           const std::string& class_name);

// CV_8U, 255 where the label (CV_16U) is one of `ids`, else 0.
cv::Mat instances_mask(const cv::Mat& labels, const std::set<int>& ids);

}  // namespace depot::eval
