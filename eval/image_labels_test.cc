// Hand-labelled image boxes: the shipped labels of the real images, and bad
// files named with their line.
#include "eval/image_labels.h"

#include <gtest/gtest.h>

#include "common/config_path.h"
#include "common/testing/error_of.h"
#include "eval/test_files.h"

namespace depot::eval {
namespace {

using testing::write_test_file;

TEST(ImageLabels, ShippedRealLabelsAreValid) {
  const ImageLabels labels =
      read_image_labels(std::string(DEPOT_SOURCE_DIR) + "/eval/data/real_labels.yaml");
  ASSERT_EQ(labels.images.size(), 7u);
  const LabelledImage& tum = labels.images.back();
  EXPECT_EQ(tum.path, shared_data_dir() + "/tum/fr3_walking_xyz_frame/rgb/1341846313.592026.png");
  int people = 0;
  for (const TruthObject& b : tum.boxes) people += b.class_name == "person";
  EXPECT_EQ(people, 2);
  EXPECT_NO_THROW(check_image_size(tum, 640, 480));
  // Hand labels count as fully visible.
  EXPECT_DOUBLE_EQ(tum.boxes[0].visible_pixels, tum.boxes[0].box.area());
}

TEST(ImageLabels, ReadsBoxesRelativeToTheFile) {
  const std::string path = write_test_file(
      "labels.yaml",
      "classes: [person, dog]\nimages:\n  a.png:\n    - {class: dog, x1: 1, y1: 2, x2: 11, y2: "
      "22}\n  b.png: []\n");
  const ImageLabels labels = read_image_labels(path);
  ASSERT_EQ(labels.images.size(), 2u);
  EXPECT_EQ(labels.images[0].path, std::filesystem::path(path).parent_path() / "a.png");
  EXPECT_EQ(labels.images[0].boxes[0].box, cv::Rect2f(1, 2, 10, 20));
  EXPECT_TRUE(labels.images[1].boxes.empty());
  EXPECT_EQ(error_of([&] { check_image_size(labels.images[0], 10, 30); }),
            path + ":4: box 1 2 11 22 is outside the 10x30 image " + labels.images[0].path);
}

TEST(ImageLabels, BadFilesNameFileAndLine) {
  const struct {
    const char* yaml;
    const char* problem;
  } cases[] = {
      {"classes: [person]\nimages:\n  a.png:\n    - {class: dgo, x1: 0, y1: 0, x2: 5, y2: 5}\n",
       ":4: class 'dgo' is not in 'classes'"},
      {"classes: [person]\nimages:\n  a.png:\n    - {class: person, x1: 5, y1: 0, x2: 5, y2: 5}\n",
       ":4: box 5 0 5 5 is empty or has negative coordinates"},
      {"classes: [person]\nimages:\n  a.png:\n    - {class: person, x1: a, y1: 0, x2: 5, y2: 5}\n",
       ":4: 'x1' must be a whole number of pixels"},
      {"classes: [person]\nimages:\n  a.png:\n    - {class: person, x1: 0, y1: 0, x2: 5}\n",
       ":4: box has no 'y2'"},
      {"classes: [person]\nimages:\n  a.png:\n    - {class: person, x: 0}\n",
       ":4: unknown key 'x' (expected class, x1, y1, x2, y2)"},
      {"classes: [person]\npictures: {}\n",
       ":2: unknown key 'pictures' (expected classes, images)"},
      {"images:\n  a.png: []\n", ": 'classes' must list the classes the boxes name"},
      {"classes: [person]\nimages:\n  a.png: [\n", ":4: YAML syntax error"},
  };
  int i = 0;
  for (const auto& c : cases) {
    const std::string path = write_test_file("bad" + std::to_string(i++) + ".yaml", c.yaml);
    const std::string error = error_of([&] { read_image_labels(path); });
    EXPECT_EQ(error.rfind(path + c.problem, 0), 0u) << error;
  }
}

}  // namespace
}  // namespace depot::eval
