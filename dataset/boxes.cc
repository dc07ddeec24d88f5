#include "dataset/boxes.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "common/image_size.h"
#include "common/text_records.h"
#include "common/tum_io.h"
#include "dataset/dataset_files.h"
#include "dataset/format_version.h"
#include "dataset/text_fields.h"

namespace depot::dataset {
namespace {

BoxRecord parse_box(const std::vector<std::string>& f, const std::string& where) {
  if (f.size() != 9)
    fail(where, "expected 9 fields (timestamp id class x1 y1 x2 y2 visible_pixels moving), found " +
                    std::to_string(f.size()));
  BoxRecord b;
  b.timestamp = parse_number_field(f[0], "timestamp", where);
  b.id = static_cast<int>(parse_integer_field(f[1], "id", where));
  b.class_name = f[2];
  // Corners beyond the largest image are refused before the int casts
  // (and the box's area stays an int).
  long corner[4];
  static const char* const names[] = {"x1", "y1", "x2", "y2"};
  for (int i = 0; i < 4; ++i) corner[i] = parse_integer_field(f[3 + i], names[i], where);
  const bool inside =
      std::all_of(corner, corner + 4, [](long c) { return c >= 0 && c <= kMaxImageSide; });
  b.x1 = static_cast<int>(corner[0]);
  b.y1 = static_cast<int>(corner[1]);
  b.x2 = static_cast<int>(corner[2]);
  b.y2 = static_cast<int>(corner[3]);
  const long visible = parse_integer_field(f[7], "visible_pixels", where);
  b.visible_pixels = static_cast<int>(std::clamp(visible, -1L, 1L + kMaxImageSide * kMaxImageSide));
  b.moving = parse_flag_field(f[8], "moving", where);
  if (!inside || b.x2 <= b.x1 || b.y2 <= b.y1)
    fail(where,
         "box " + f[3] + " " + f[4] + " " + f[5] + " " + f[6] + " is empty or outside the image");
  if (b.visible_pixels < 1 || b.visible_pixels > b.area())
    fail(where,
         "visible_pixels " + f[7] + " is not in [1, box area " + std::to_string(b.area()) + "]");
  return b;
}

}  // namespace

std::string boxes_header(const std::string& scenario_name) {
  return "# ground-truth boxes of visible detectable instances, pixels, x2/y2 exclusive\n" +
         file_header_line(scenario_name) +
         "# timestamp id class x1 y1 x2 y2 visible_pixels moving\n";
}

std::string format_box(const BoxRecord& b) {
  return fmt::format("{} {} {} {} {} {} {} {} {}\n", format_timestamp(b.timestamp), b.id,
                     b.class_name, b.x1, b.y1, b.x2, b.y2, b.visible_pixels, b.moving ? 1 : 0);
}

void write_boxes(const std::string& dataset_dir, const std::string& scenario_name,
                 const std::vector<BoxRecord>& boxes) {
  std::string text = boxes_header(scenario_name);
  for (const BoxRecord& b : boxes) text += format_box(b);
  write_text_file_atomic(dataset_file(dataset_dir, kBoxesFile), text);
}

bool has_boxes(const std::string& dataset_dir) {
  return std::filesystem::is_regular_file(dataset_file(dataset_dir, kBoxesFile));
}

std::vector<BoxRecord> read_boxes(const std::string& dataset_dir) {
  check_format_version(dataset_dir);
  const std::string path = dataset_file(dataset_dir, kBoxesFile);
  std::ifstream in(path);
  if (!in) fail(path, "cannot open file (the ground-truth boxes)");
  std::vector<BoxRecord> boxes;
  for_each_numbered_record(
      in, path, [&](int line, const std::string& where, const std::vector<std::string>& f) {
        BoxRecord b = parse_box(f, where);
        b.line = line;
        boxes.push_back(std::move(b));
      });
  if (in.bad()) fail(path, "read error");
  return boxes;
}

std::string box_location(const std::string& dataset_dir, const BoxRecord& box) {
  return dataset_file(dataset_dir, kBoxesFile) + ":" + std::to_string(box.line);
}

}  // namespace depot::dataset
