#include "dataset/boxes.h"

#include <gtest/gtest.h>

#include "common/testing/error_of.h"
#include "dataset/test_folder.h"

namespace depot::dataset {
namespace {

TEST(Boxes, RoundTripWithLineNumbers) {
  const std::string dir = testing::new_test_folder();
  BoxRecord a{1.0, 3, "person", 10, 20, 30, 60, 500, true};
  BoxRecord b{1.033333, 5, "chair", 0, 0, 4, 4, 16, false};
  write_boxes(dir, "walk", {a, b});
  EXPECT_EQ(testing::read_text(dir, "boxes.txt"),
            "# ground-truth boxes of visible detectable instances, pixels, x2/y2 exclusive\n"
            "# file: 'walk' (depot-slam simulator)\n"
            "# timestamp id class x1 y1 x2 y2 visible_pixels moving\n"
            "1.000000 3 person 10 20 30 60 500 1\n1.033333 5 chair 0 0 4 4 16 0\n");
  const std::vector<BoxRecord> read = read_boxes(dir);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[0].line, 4);
  EXPECT_EQ(read[1].line, 5);
  EXPECT_EQ(box_location(dir, read[1]), dir + "/boxes.txt:5");
  EXPECT_EQ(format_box(read[0]), format_box(a));
  EXPECT_EQ(format_box(read[1]), format_box(b));
  EXPECT_EQ(read[0].area(), 800);
}

TEST(Boxes, MalformedLinesNameTheFileAndLine) {
  const std::string dir = testing::new_test_folder();
  EXPECT_EQ(error_of([&] { read_boxes(dir); }),
            dir + "/boxes.txt: cannot open file (the ground-truth boxes)");
  const struct {
    std::string line, problem;
  } cases[] = {
      {"1.0 22 desk 1 2 3 4 5",
       "expected 9 fields (timestamp id class x1 y1 x2 y2 visible_pixels moving), found 8"},
      {"nan 22 desk 1 2 3 4 2 0", "timestamp 'nan' is not a number"},
      {"1.0 x desk 1 2 3 4 2 0", "id 'x' is not an integer"},
      {"1.0 22 desk 1 2 3.5 4 2 0", "x2 '3.5' is not an integer"},
      {"1.0 22 desk 10 2 3 40 5 0", "box 10 2 3 40 is empty or outside the image"},
      {"1.0 22 desk -1 2 3 40 5 0", "box -1 2 3 40 is empty or outside the image"},
      // Found by fuzzing (tests/fuzz/fuzz_dataset_boxes): the area of a box
      // this large overflowed an int.
      {"1.0 22 desk 0 0 222222258 20 5 0", "box 0 0 222222258 20 is empty or outside the image"},
      {"1.0 22 desk 0 0 4097 20 5 0", "box 0 0 4097 20 is empty or outside the image"},
      {"1.0 22 desk 0 0 4 4 99999999999 0",
       "visible_pixels 99999999999 is not in [1, box area 16]"},
      {"1.0 22 desk 1 2 3 4 5 0", "visible_pixels 5 is not in [1, box area 4]"},
      {"1.0 22 desk 1 2 3 4 0 0", "visible_pixels 0 is not in [1, box area 4]"},
      {"1.0 22 desk 1 2 3 4 2 7", "moving '7' is not 0 or 1"},
  };
  for (const auto& c : cases) {
    testing::write_text(dir, "boxes.txt", "# a\n# b\n  \n" + c.line + "\r\n");
    EXPECT_EQ(error_of([&] { read_boxes(dir); }), dir + "/boxes.txt:4: " + c.problem) << c.line;
  }
}

}  // namespace
}  // namespace depot::dataset
