// The output decoders on synthetic tensors: YOLOv5 [1, N, 85], Darknet region
// rows, FastestDet's grid map. No model needed.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "common/error.h"
#include "slam/detect/darknet_detector.h"
#include "slam/detect/fastestdet_detector.h"
#include "slam/detect/letterbox.h"
#include "slam/detect/nms.h"
#include "slam/detect/yolov5_detector.h"

namespace depot::slam {
namespace {

DecodeParams coco_like(float confidence = 0.3f) {
  DecodeParams p;
  for (int i = 0; i < 80; ++i) p.names.push_back("class" + std::to_string(i));
  p.names[0] = "person";
  p.names[56] = "chair";
  p.confidence = confidence;
  p.model = "m.onnx";
  p.names_path = "coco.names";
  return p;
}

// A [1, rows, 85] YOLOv5 output of zeros.
cv::Mat yolov5_output(int rows) {
  const int sz[] = {1, rows, 85};
  return cv::Mat(3, sz, CV_32F, cv::Scalar(0));
}

void set_row(cv::Mat& out, int r, float cx, float cy, float w, float h, float obj, int cls,
             float score) {
  float* row = out.ptr<float>(0, r);
  row[0] = cx, row[1] = cy, row[2] = w, row[3] = h, row[4] = obj;
  row[5 + cls] = score;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(DecodeYolov5, SyntheticTensorToOriginalPixels) {
  // A 640x480 frame letterboxed into 640x640: scale 1, 80 px of padding on top.
  const LetterboxTransform t =
      letterbox(cv::Mat(480, 640, CV_8UC3, cv::Scalar::all(0)), {640, 640}).transform;
  cv::Mat out = yolov5_output(5);
  set_row(out, 0, 320, 320, 100, 200, 0.9f, 0, 0.8f);    // person 0.72
  set_row(out, 1, 100, 100, 50, 50, 0.9f, 2, 0.2f);      // 0.18: below threshold
  set_row(out, 2, 500, 300, 80, 120, 0.5f, 56, 0.9f);    // chair 0.45
  set_row(out, 3, 20, 200, 60, 80, 0.95f, 0, 0.95f);     // person over the left edge
  set_row(out, 4, 320, 320, 100, 200, 0.25f, 0, 0.99f);  // obj below threshold
  const std::vector<Detection> d = decode_yolov5(out, coco_like(), t);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d[0].class_name, "person");
  EXPECT_EQ(d[0].class_id, 0);
  EXPECT_FLOAT_EQ(d[0].confidence, 0.72f);
  // Input box (270, 220, 100, 200) minus the 80 px top padding.
  EXPECT_EQ(d[0].box, cv::Rect2f(270, 140, 100, 200));
  EXPECT_EQ(d[1].class_name, "chair");
  EXPECT_FLOAT_EQ(d[1].confidence, 0.45f);
  EXPECT_EQ(d[1].box, cv::Rect2f(460, 160, 80, 120));
  // x from -10 clipped to 0.
  EXPECT_EQ(d[2].box, cv::Rect2f(0, 80, 50, 80));
}

TEST(DecodeYolov5, ScaledLetterboxWantedClassesAndNms) {
  // 1280x960 into 640x640: scale 0.5, pad_y 80.
  const LetterboxTransform t =
      letterbox(cv::Mat(960, 1280, CV_8UC3, cv::Scalar::all(0)), {640, 640}).transform;
  cv::Mat out = yolov5_output(3);
  set_row(out, 0, 320, 320, 100, 200, 0.9f, 0, 0.9f);
  set_row(out, 1, 325, 318, 100, 200, 0.8f, 0, 0.9f);  // duplicate of row 0
  set_row(out, 2, 500, 300, 80, 120, 0.9f, 56, 0.9f);
  DecodeParams p = coco_like();
  p.wanted.assign(80, false);
  p.wanted[0] = true;  // persons only
  const std::vector<Detection> d = non_max_suppression(decode_yolov5(out, p, t), 0.45f);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].class_name, "person");
  EXPECT_FLOAT_EQ(d[0].confidence, 0.81f);
  // Input (270, 220, 100, 200) -> ((270 - 0) / 0.5, (220 - 80) / 0.5, 200, 400).
  EXPECT_EQ(d[0].box, cv::Rect2f(540, 280, 200, 400));
  // A 2-D [N, 85] output decodes the same.
  const cv::Mat flat(3, 85, CV_32F, out.ptr<float>());
  EXPECT_EQ(non_max_suppression(decode_yolov5(flat, p, t), 0.45f).size(), 1u);
}

TEST(DecodeYolov5, ClassCountAndShapeErrors) {
  const LetterboxTransform t =
      letterbox(cv::Mat(480, 640, CV_8UC3, cv::Scalar::all(0)), {640, 640}).transform;
  DecodeParams p = coco_like();
  p.names.pop_back();
  EXPECT_EQ(error_of([&] { decode_yolov5(yolov5_output(2), p, t); }),
            "m.onnx: model outputs 80 classes but coco.names lists 79");
  const int sz[] = {1, 3, 4, 85};
  const std::string e =
      error_of([&] { decode_yolov5(cv::Mat(4, sz, CV_32F, cv::Scalar(0)), coco_like(), t); });
  EXPECT_EQ(e.rfind("m.onnx: unexpected output 1x3x4x85", 0), 0u) << e;
}

TEST(DecodeDarknet, RegionRowsByEq8) {
  cv::Mat a(3, 85, CV_32F, cv::Scalar(0)), b(2, 85, CV_32F, cv::Scalar(0));
  // cx, cy, w, h normalised; objectness; class scores already x objectness.
  float* r = a.ptr<float>(0);
  r[0] = 0.5f, r[1] = 0.25f, r[2] = 0.2f, r[3] = 0.1f, r[4] = 0.95f, r[5 + 0] = 0.9f;
  r = a.ptr<float>(1);
  r[0] = 0.5f, r[1] = 0.5f, r[2] = 0.2f, r[3] = 0.2f, r[4] = 0.9f, r[5 + 3] = 0.25f;  // too low
  r = b.ptr<float>(1);
  r[0] = 0.95f, r[1] = 0.5f, r[2] = 0.2f, r[3] = 0.5f, r[4] = 0.8f, r[5 + 56] = 0.7f;
  const std::vector<Detection> d = decode_darknet({a, b}, coco_like(), {640, 480});
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].class_name, "person");
  EXPECT_FLOAT_EQ(d[0].confidence, 0.9f);
  EXPECT_EQ(d[0].box, cv::Rect2f(256, 96, 128, 48));  // Eq. 8 by hand
  EXPECT_EQ(d[1].class_name, "chair");
  // x from 0.85*640 = 544 to 1.05*640, clipped at 640; y 0.25*480 .. 0.75*480.
  EXPECT_EQ(d[1].box, cv::Rect2f(544, 120, 96, 240));
  DecodeParams p = coco_like();
  p.names.resize(20);
  p.model = "y.weights";
  EXPECT_EQ(error_of([&] {
              decode_darknet({a}, p, {640, 480});
            }),
            "y.weights: model outputs 80 classes but coco.names lists 20");
}

TEST(DecodeFastestDet, GridCellAsTheReferenceExample) {
  // [1, 85, H=2, W=3]; one confident cell at row 1, column 2.
  const int H = 2, W = 3;
  const int sz[] = {1, 85, H, W};
  cv::Mat out(4, sz, CV_32F, cv::Scalar(0));
  auto at = [&](int c, int h, int w) -> float& { return out.ptr<float>(0, c)[h * W + w]; };
  at(0, 1, 2) = 0.81f;      // objectness (sigmoid already applied)
  at(1, 1, 2) = 0.5f;       // tx -> tanh
  at(2, 1, 2) = -0.25f;     // ty
  at(3, 1, 2) = 0.0f;       // tw -> sigmoid(0) = 0.5
  at(4, 1, 2) = 1.0f;       // th -> sigmoid(1)
  at(5 + 0, 1, 2) = 0.9f;   // person (softmax already applied)
  at(5 + 56, 1, 2) = 0.1f;  // chair
  at(0, 0, 0) = 0.2f;       // a weak cell: 0.2^0.6 * 1^0.4 = 0.38 < 0.5
  at(5 + 3, 0, 0) = 1.0f;
  const std::vector<Detection> d = decode_fastestdet(out, coco_like(0.5f), {640, 480});
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].class_name, "person");
  EXPECT_NEAR(d[0].confidence, std::pow(0.81, 0.6) * std::pow(0.9, 0.4), 1e-6);
  const double cx = (2 + std::tanh(0.5)) / 3, cy = (1 + std::tanh(-0.25)) / 2;
  const double bw = 0.5, bh = 1 / (1 + std::exp(-1.0));
  const double x1 = (cx - bw / 2) * 640, y1 = (cy - bh / 2) * 480;
  const double x2 = std::min((cx + bw / 2) * 640, 640.0), y2 = (cy + bh / 2) * 480;
  EXPECT_NEAR(d[0].box.x, x1, 1e-3);
  EXPECT_NEAR(d[0].box.y, y1, 1e-3);
  EXPECT_NEAR(d[0].box.width, x2 - x1, 1e-3);
  EXPECT_NEAR(d[0].box.height, y2 - y1, 1e-3);

  // The same map channels-last [1, H, W, 85] decodes identically.
  const int szt[] = {1, H, W, 85};
  cv::Mat last(4, szt, CV_32F);
  for (int c = 0; c < 85; ++c)
    for (int h = 0; h < H; ++h)
      for (int w = 0; w < W; ++w) last.ptr<float>(0, h, w)[c] = at(c, h, w);
  const std::vector<Detection> d2 = decode_fastestdet(last, coco_like(0.5f), {640, 480});
  ASSERT_EQ(d2.size(), 1u);
  EXPECT_EQ(d2[0].box, d[0].box);
  EXPECT_FLOAT_EQ(d2[0].confidence, d[0].confidence);

  DecodeParams p = coco_like();
  p.names.resize(79);
  EXPECT_EQ(error_of([&] {
              decode_fastestdet(out, p, {640, 480});
            }),
            "m.onnx: model outputs 80 classes but coco.names lists 79");
}

}  // namespace
}  // namespace depot::slam
