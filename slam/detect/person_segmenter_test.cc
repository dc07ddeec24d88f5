// The person segmenter: its YAML, the real MediaPipe selfie model through
// OpenCV dnn (NHWC input), the mapping back to the image, and bad models.
#include "slam/detect/person_segmenter.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "common/testing/error_of.h"
#include "slam/detect/test_support.h"

namespace depot::slam {
namespace {

std::string shipped() {
  return test::source_dir() + "/scenes/segmenters/selfie.yaml";
}

TEST(SegmenterConfig, ShippedSelfieModel) {
  const SegmenterConfig c = load_segmenter_config(shipped());
  EXPECT_EQ(c.model, test::shared_data() + "/models/selfie-segmentation/selfie_segmentation.onnx");
  EXPECT_EQ(c.input_width, 256);
  EXPECT_TRUE(c.nhwc);
  EXPECT_TRUE(c.rgb);
  EXPECT_FALSE(c.letterbox);
  EXPECT_FALSE(c.logit);
  EXPECT_FLOAT_EQ(c.input_hi, 1.0f);
  EXPECT_FLOAT_EQ(c.threshold, 0.5f);
}

TEST(SegmenterConfig, BadFilesNameFileAndLine) {
  test::TempDir dir;
  const struct {
    const char* yaml;
    const char* problem;
  } cases[] = {
      {"input_width: 256\n", ": missing 'model' (path of the ONNX model file)"},
      {"model: m.onnx\nlayout: nwhc\n", ":2: 'layout' must be nhwc or nchw, not 'nwhc'"},
      {"model: m.onnx\ninput_range: [1, 0]\n", ":2: 'input_range' must have lo < hi"},
      {"model: m.onnx\ninput_range: 1\n", ":2: 'input_range' must be two numbers [lo, hi]"},
      {"model: m.onnx\nthreshold: 2\n", ":2: 'threshold' = 2 is out of range [0, 1]"},
      {"model: m.onnx\nsize: 3\n", ":2: unknown key 'size'"},
  };
  int i = 0;
  for (const auto& c : cases) {
    const std::string path = dir.write("s" + std::to_string(i++) + ".yaml", c.yaml);
    const std::string error = error_of([&] { load_segmenter_config(path); });
    EXPECT_EQ(error.rfind(path + c.problem, 0), 0u) << error;
  }
  EXPECT_EQ(load_segmenter_config(dir.write("rel.yaml", "model: m.onnx\n")).model,
            dir.file("m.onnx"));
}

TEST(PersonSegmenter, MasksThePeopleOfTheRealFrameAtImageSize) {
  DEPOT_REQUIRE_SHARED_DATA();
  const cv::Mat bgr = cv::imread(test::tum_frame());
  for (bool letterbox : {false, true}) {
    SegmenterConfig c = load_segmenter_config(shipped());
    c.letterbox = letterbox;
    PersonSegmenter segmenter(c);
    const cv::Mat p = segmenter.probability(bgr);
    ASSERT_EQ(p.size(), bgr.size());
    ASSERT_EQ(p.type(), CV_32F);
    double lo, hi;
    cv::minMaxLoc(p, &lo, &hi);
    EXPECT_GE(lo, 0.0);
    EXPECT_LE(hi, 1.0);
    // The standing man fills the right edge; the wall above the desks
    // (hand-labelled boxes, eval/data/real_labels.yaml) holds nobody.
    const cv::Mat mask = segmenter.mask(bgr);
    EXPECT_GT(cv::mean(mask(cv::Rect(540, 150, 90, 300)))[0] / 255, 0.8) << letterbox;
    EXPECT_LT(cv::mean(mask(cv::Rect(300, 100, 120, 60)))[0] / 255, 0.1) << letterbox;
  }
}

TEST(PersonSegmenter, BadModelsAreOneError) {
  DEPOT_REQUIRE_SHARED_DATA();
  test::TempDir dir;
  SegmenterConfig c;
  c.model = dir.file("missing.onnx");
  EXPECT_EQ(error_of([&] { PersonSegmenter{c}; }), c.model + ": model file not found");
  c.model = dir.write_random("garbage.onnx", 4096);
  EXPECT_EQ(error_of([&] { PersonSegmenter{c}; }).rfind(c.model + ": cannot load model", 0), 0u);
  // A detector is not a segmenter: its output is no probability map.
  c.model = test::fastestdet_dir() + "/FastestDet.onnx";
  c.input_width = c.input_height = 352;
  c.nhwc = false;
  EXPECT_EQ(error_of([&] { PersonSegmenter{c}; }).rfind(c.model + ": output ", 0), 0u)
      << error_of([&] { PersonSegmenter{c}; });
}

}  // namespace
}  // namespace depot::slam
