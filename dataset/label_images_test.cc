#include "dataset/label_images.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "common/testing/error_of.h"
#include "dataset/test_folder.h"

namespace depot::dataset {
namespace {

TEST(LabelImages, ListAndImagesRoundTrip) {
  const std::string dir = testing::new_test_folder();
  std::filesystem::create_directory(std::filesystem::path(dir) / "labels");
  const std::vector<double> stamps = {1.0, 1.033333};
  cv::Mat labels(4, 6, CV_16UC1, cv::Scalar(0));
  labels.at<uint16_t>(1, 2) = 7;
  labels.at<uint16_t>(3, 5) = 65535;
  for (double t : stamps) write_label_image(dir, t, labels, 1);
  write_label_list(dir, "walk", stamps);
  EXPECT_EQ(testing::read_text(dir, "labels.txt"),
            "# instance label images (16-bit instance ids, 0 = none)\n"
            "# file: 'walk' (depot-slam simulator)\n# timestamp filename\n"
            "1.000000 labels/1.000000.png\n1.033333 labels/1.033333.png\n");
  ASSERT_TRUE(has_label_list(dir));
  const std::vector<StampedFile> list = read_label_list(dir);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[1].path, "labels/1.033333.png");
  EXPECT_DOUBLE_EQ(list[1].timestamp, 1.033333);
  const cv::Mat read = read_label_image(dir, list[1].path);
  ASSERT_EQ(read.type(), CV_16UC1);
  EXPECT_EQ(cv::countNonZero(read != labels), 0);
}

TEST(LabelImages, MissingListAndWrongImagesAreErrorsNamingTheFile) {
  const std::string dir = testing::new_test_folder();
  EXPECT_FALSE(has_label_list(dir));
  EXPECT_EQ(error_of([&] { read_label_list(dir); }),
            dir +
                "/labels.txt: cannot open file (the instance label images; not a simulated "
                "dataset?)");
  testing::write_text(dir, "labels.txt", "# x\n1.0 labels/1.png\nbad labels/2.png\n");
  EXPECT_EQ(error_of([&] { read_label_list(dir); }).rfind(dir + "/labels.txt:3: ", 0), 0u);
  cv::imwrite(dir + "/colour.png", cv::Mat(2, 2, CV_8UC3, cv::Scalar(1, 2, 3)));
  EXPECT_EQ(error_of([&] { read_label_image(dir, "colour.png"); }),
            dir + "/colour.png: label image is not 16-bit single-channel");
}

}  // namespace
}  // namespace depot::dataset
