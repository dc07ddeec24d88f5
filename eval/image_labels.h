#pragma once
// Hand-labelled ground-truth boxes of real images, read from YAML
// (eval/data/real_labels.yaml):
//
//   classes: [person, dog, horse]     # every class a box may name
//   images:
//     ${DEPOT_SHARED_DATA}/photos/person.jpg:   # relative to this file, or shared data
//       - {class: person, x1: 191, y1: 100, x2: 270, y2: 375}
//
// Boxes are pixels with x2/y2 exclusive, like a dataset's boxes.txt. Hand
// labels have no visible-pixel count: a box counts as fully visible.
#include <string>
#include <vector>

#include "eval/box_matching.h"

namespace depot::eval {

struct LabelledImage {
  std::string path;   // resolved image path
  std::string where;  // "<labels file>:<line>", for errors about the image
  std::vector<TruthObject> boxes;
  std::vector<std::string> box_where;  // each box's "<labels file>:<line>"
};

struct ImageLabels {
  std::string path;  // the labels file
  std::vector<std::string> classes;
  std::vector<LabelledImage> images;
};

// Throws depot::Error "<path>[:line]: <problem>" for an unreadable file, a
// YAML error, an unknown key, a box of a class not in `classes`, or a box
// that is empty or has negative coordinates. The images are not opened:
// check_image_size does that.
ImageLabels read_image_labels(const std::string& path);

// Throws "<labels file>:<line>: box ... is outside the WxH image <path>"
// when a box of `image` does not fit in an image of `size`.
void check_image_size(const LabelledImage& image, int width, int height);

}  // namespace depot::eval
