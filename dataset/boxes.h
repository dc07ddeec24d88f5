#pragma once
// boxes.txt: the ground-truth boxes of the visible detectable instances, one
// line per instance and frame:
//
//   timestamp id class x1 y1 x2 y2 visible_pixels moving
//
// in pixels with x2/y2 exclusive; visible_pixels counts the instance's
// pixels in the label image (<= the box's area).
#include <string>
#include <vector>

namespace depot::dataset {

struct BoxRecord {
  double timestamp = 0;  // the frame's rgb timestamp
  int id = 0;            // instance id (objects.json, labels/)
  std::string class_name;
  int x1 = 0, y1 = 0, x2 = 0, y2 = 0;
  int visible_pixels = 0;
  bool moving = false;
  // Its line in the file (0 when not read from one), for the errors of
  // checks against other files (a frame of rgb.txt, a class of classes.txt,
  // the image size of calibration.yaml).
  int line = 0;

  int area() const { return (x2 - x1) * (y2 - y1); }
};

// The comment lines that open the file.
std::string boxes_header(const std::string& scenario_name);
// One line, with its newline.
std::string format_box(const BoxRecord& box);
// Writes `dataset_dir`/boxes.txt atomically: the header, then the boxes in
// the given order (frame by frame).
void write_boxes(const std::string& dataset_dir, const std::string& scenario_name,
                 const std::vector<BoxRecord>& boxes);

// Whether the folder has boxes.txt (a simulated dataset).
bool has_boxes(const std::string& dataset_dir);
// Reads `dataset_dir`/boxes.txt after checking the dataset's format version;
// boxes in file order. Throws depot::Error "<path>:<line>: ..." for a
// malformed line: field count, numbers, a flag that is not 0/1, an empty box
// or one with a negative corner, visible_pixels not in [1, area].
std::vector<BoxRecord> read_boxes(const std::string& dataset_dir);
// `dataset_dir`/boxes.txt:<line>, for the callers' checks (BoxRecord::line).
std::string box_location(const std::string& dataset_dir, const BoxRecord& box);

}  // namespace depot::dataset
