// Eq. 8 box conversion, IoU, class-wise NMS and class-name files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/error.h"
#include "dataset/class_list.h"
#include "slam/detect/detection.h"
#include "slam/detect/detector_config.h"
#include "slam/detect/nms.h"
#include "slam/detect/test_support.h"

namespace depot::slam {
namespace {

Detection det(const std::string& name, int id, float conf, cv::Rect2f box) {
  Detection d;
  d.class_name = name;
  d.class_id = id;
  d.confidence = conf;
  d.box = box;
  return d;
}

TEST(YoloToPixels, HandComputedEq8) {
  // X=0.5, Y=0.25, W=0.2, H=0.1 on 640x480: x1 = 0.4*640 = 256,
  // x2 = 0.6*640 = 384, y1 = 0.2*480 = 96, y2 = 0.3*480 = 144.
  const cv::Rect2f r = yolo_to_pixels(0.5f, 0.25f, 0.2f, 0.1f, 640, 480);
  EXPECT_FLOAT_EQ(r.x, 256.0f);
  EXPECT_FLOAT_EQ(r.y, 96.0f);
  EXPECT_FLOAT_EQ(r.width, 128.0f);
  EXPECT_FLOAT_EQ(r.height, 48.0f);
  // The whole image.
  const cv::Rect2f all = yolo_to_pixels(0.5f, 0.5f, 1.0f, 1.0f, 320, 240);
  EXPECT_FLOAT_EQ(all.x, 0.0f);
  EXPECT_FLOAT_EQ(all.y, 0.0f);
  EXPECT_FLOAT_EQ(all.width, 320.0f);
  EXPECT_FLOAT_EQ(all.height, 240.0f);
  // Top-left has the smaller y (the paper prints the y terms swapped).
  const cv::Rect2f low = yolo_to_pixels(0.25f, 0.75f, 0.5f, 0.5f, 100, 200);
  EXPECT_FLOAT_EQ(low.x, 0.0f);
  EXPECT_FLOAT_EQ(low.y, 100.0f);
  EXPECT_FLOAT_EQ(low.width, 50.0f);
  EXPECT_FLOAT_EQ(low.height, 100.0f);
}

TEST(Iou, HandComputed) {
  // Overlap 5x5 = 25, union 100 + 100 - 25 = 175.
  EXPECT_FLOAT_EQ(iou({0, 0, 10, 10}, {5, 5, 10, 10}), 25.0f / 175.0f);
  EXPECT_FLOAT_EQ(iou({0, 0, 10, 10}, {0, 0, 10, 10}), 1.0f);
  EXPECT_FLOAT_EQ(iou({0, 0, 10, 10}, {2, 2, 4, 4}), 16.0f / 100.0f);
  EXPECT_FLOAT_EQ(iou({0, 0, 10, 10}, {10, 0, 10, 10}), 0.0f);  // touching edge
  EXPECT_FLOAT_EQ(iou({0, 0, 10, 10}, {20, 20, 5, 5}), 0.0f);
  EXPECT_FLOAT_EQ(iou({0, 0, 0, 0}, {0, 0, 0, 0}), 0.0f);  // empty union
  EXPECT_FLOAT_EQ(iou({5, 5, 10, 10}, {0, 0, 10, 10}), iou({0, 0, 10, 10}, {5, 5, 10, 10}));
}

TEST(Nms, SuppressesOverlapsOfOneClassKeepsOtherClasses) {
  std::vector<Detection> in{
      det("person", 0, 0.7f, {0, 0, 100, 200}),
      det("person", 0, 0.9f, {10, 10, 100, 200}),   // IoU with the first ~0.75
      det("chair", 56, 0.6f, {10, 10, 100, 200}),   // same box, other class
      det("person", 0, 0.5f, {400, 0, 100, 200}),   // far away
      det("person", 0, 0.8f, {60, 100, 100, 200}),  // IoU with the best ~0.16
  };
  const std::vector<Detection> out = non_max_suppression(in, 0.45f);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_FLOAT_EQ(out[0].confidence, 0.9f);
  EXPECT_EQ(out[0].class_name, "person");
  EXPECT_FLOAT_EQ(out[1].confidence, 0.8f);
  EXPECT_EQ(out[2].class_name, "chair");
  EXPECT_FLOAT_EQ(out[3].confidence, 0.5f);
  EXPECT_FLOAT_EQ(out[3].box.x, 400.0f);
}

TEST(Nms, ThresholdIsStrictAndEmptyInputIsFine) {
  // IoU exactly 1/3: boxes 10x10 overlapping 5x10 -> 50 / 150.
  const std::vector<Detection> in{det("a", 0, 0.9f, {0, 0, 10, 10}),
                                  det("a", 0, 0.8f, {5, 0, 10, 10})};
  EXPECT_EQ(non_max_suppression(in, 1.0f / 3.0f + 1e-4f).size(), 2u);
  EXPECT_EQ(non_max_suppression(in, 0.3f).size(), 1u);
  EXPECT_TRUE(non_max_suppression({}, 0.45f).empty());
}

TEST(ClassNames, ReadsCocoNamesAndTrims) {
  test::TempDir dir;
  const std::string p = dir.write("a.names", "person\r\n  bicycle \ncar\n\n\n");
  const std::vector<std::string> names = dataset::load_class_names(p);
  ASSERT_EQ(names.size(), 3u);
  EXPECT_EQ(names[0], "person");
  EXPECT_EQ(names[1], "bicycle");
  EXPECT_EQ(names[2], "car");
  if (test::have_shared_data()) {
    const auto coco = dataset::load_class_names(test::yolo_fastest_dir() + "/coco.names");
    ASSERT_EQ(coco.size(), 80u);
    EXPECT_EQ(coco[0], "person");
    EXPECT_EQ(coco[56], "chair");
    EXPECT_EQ(coco[79], "toothbrush");
  }
}

TEST(ClassNames, ErrorsNameTheFile) {
  test::TempDir dir;
  const std::string missing = dir.file("missing.names");
  try {
    dataset::load_class_names(missing);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr(missing)) << e.what();
  }
  const std::string empty = dir.write("empty.names", "\n  \n");
  EXPECT_THROW(
      {
        try {
          dataset::load_class_names(empty);
        } catch (const Error& e) {
          EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr(empty)) << e.what();
          throw;
        }
      },
      Error);
  const std::string gap = dir.write("gap.names", "person\n\ncar\n");
  EXPECT_THROW(dataset::load_class_names(gap), Error);
}

TEST(ClassNames, WantedClasses) {
  const std::vector<std::string> names{"person", "dog", "chair"};
  EXPECT_EQ(wanted_classes(names, {}, "x"), std::vector<bool>({true, true, true}));
  EXPECT_EQ(wanted_classes(names, {"chair", "person"}, "x"),
            std::vector<bool>({true, false, true}));
  try {
    wanted_classes(names, {"pig"}, "my.names");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("my.names")) << e.what();
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("'pig'")) << e.what();
  }
}

}  // namespace
}  // namespace depot::slam
