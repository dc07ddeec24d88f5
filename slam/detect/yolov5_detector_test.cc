// Yolov5Detector end to end (load, warm-up check, letterbox, forward, decode,
// NMS, back to original pixels) on a tiny ONNX model the test writes itself:
// GlobalAveragePool -> 1x1 Conv with zero weights whose bias holds a chosen
// YOLOv5 output -> Reshape to [1, N, 85]. The model's output is therefore
// known exactly, whatever the frame.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "common/error.h"
#include "slam/detect/detector_factory.h"
#include "slam/detect/test_support.h"

namespace depot::slam {
namespace {

// --- a minimal protobuf writer, enough for an ONNX ModelProto ---
std::string varint(uint64_t v) {
  std::string s;
  do {
    uint8_t b = v & 0x7F;
    v >>= 7;
    if (v) b |= 0x80;
    s += static_cast<char>(b);
  } while (v);
  return s;
}
std::string field_varint(int field, uint64_t v) {
  return varint(uint64_t(field) << 3) + varint(v);
}
std::string field_bytes(int field, const std::string& bytes) {
  return varint((uint64_t(field) << 3) | 2) + varint(bytes.size()) + bytes;
}

// TensorProto (raw_data, little endian).
template <typename T>
std::string tensor(const std::string& name, const std::vector<int64_t>& dims, int data_type,
                   const std::vector<T>& values) {
  std::string s;
  for (int64_t d : dims) s += field_varint(1, static_cast<uint64_t>(d));
  s += field_varint(2, static_cast<uint64_t>(data_type));
  s += field_bytes(8, name);
  std::string raw(values.size() * sizeof(T), '\0');
  std::memcpy(raw.data(), values.data(), raw.size());
  return s + field_bytes(9, raw);
}

// ValueInfoProto of a float tensor.
std::string value_info(const std::string& name, const std::vector<int64_t>& dims) {
  std::string shape;
  for (int64_t d : dims) shape += field_bytes(1, field_varint(1, static_cast<uint64_t>(d)));
  const std::string tensor_type = field_varint(1, 1 /*FLOAT*/) + field_bytes(2, shape);
  return field_bytes(1, name) + field_bytes(2, field_bytes(1, tensor_type));
}

std::string node(const std::vector<std::string>& in, const std::string& out, const std::string& op,
                 const std::string& attributes = {}) {
  std::string s;
  for (const std::string& i : in) s += field_bytes(1, i);
  return s + field_bytes(2, out) + field_bytes(3, op + "_" + out) + field_bytes(4, op) + attributes;
}

// A model mapping any [1, 3, H, W] image to the constant [1, N, 85] `rows`.
std::string constant_yolov5_model(const std::vector<std::vector<float>>& rows) {
  const int64_t n = static_cast<int64_t>(rows.size());
  std::vector<float> bias;
  for (const auto& r : rows) bias.insert(bias.end(), r.begin(), r.end());
  const std::string kernel_shape = field_bytes(1, "kernel_shape") + field_varint(20, 7 /*INTS*/) +
                                   field_varint(8, 1) + field_varint(8, 1);
  std::string graph;
  graph += field_bytes(1, node({"images"}, "pooled", "GlobalAveragePool"));
  graph += field_bytes(1, node({"pooled", "w", "b"}, "conv", "Conv", field_bytes(5, kernel_shape)));
  graph += field_bytes(1, node({"conv", "shape"}, "output", "Reshape"));
  graph += field_bytes(2, "constant_yolov5");
  graph += field_bytes(5, tensor<float>("w", {85 * n, 3, 1, 1}, 1,
                                        std::vector<float>(static_cast<size_t>(85 * n * 3), 0.0f)));
  graph += field_bytes(5, tensor<float>("b", {85 * n}, 1, bias));
  graph += field_bytes(5, tensor<int64_t>("shape", {3}, 7 /*INT64*/, {1, n, 85}));
  graph += field_bytes(11, value_info("images", {1, 3, 64, 64}));
  graph += field_bytes(12, value_info("output", {1, n, 85}));
  const std::string opset = field_bytes(1, "") + field_varint(2, 11);
  return field_varint(1, 7) + field_bytes(2, "depot-test") + field_bytes(7, graph) +
         field_bytes(8, opset);
}

std::vector<float> row(float cx, float cy, float w, float h, float obj, int cls, float score) {
  std::vector<float> r(85, 0.0f);
  r[0] = cx, r[1] = cy, r[2] = w, r[3] = h, r[4] = obj;
  r[5 + static_cast<size_t>(cls)] = score;
  return r;
}

class Yolov5OnTinyModel : public ::testing::Test {
 protected:
  void SetUp() override {
    // Rows in 64x64 input pixels. A 640x480 frame letterboxes into 64x64 at
    // scale 0.1 with 8 px of padding on top.
    model_ = dir_.write("tiny.onnx", constant_yolov5_model({
                                         row(32, 32, 20, 30, 0.9f, 0, 0.9f),   // person 0.81
                                         row(33, 32, 20, 30, 0.8f, 0, 0.9f),   // its duplicate
                                         row(50, 40, 10, 10, 0.9f, 56, 0.8f),  // chair 0.72
                                         row(10, 10, 10, 10, 0.9f, 0, 0.2f),   // 0.18: dropped
                                     }));
    std::string names;
    for (int i = 0; i < 80; ++i)
      names += (i == 0    ? "person"
                : i == 56 ? "chair"
                          : "c" + std::to_string(i)) +
               std::string("\n");
    names_ = dir_.write("coco.names", names);
    config_.type = "yolov5";
    config_.model = model_;
    config_.names = names_;
    config_.input_width = config_.input_height = 64;
  }
  test::TempDir dir_;
  std::string model_, names_;
  DetectorConfig config_;
  const cv::Mat frame_ = cv::Mat(480, 640, CV_8UC3, cv::Scalar(30, 60, 90));
};

TEST_F(Yolov5OnTinyModel, DetectsDecodesSuppressesAndMapsBack) {
  const auto det = make_dnn_detector(config_);
  EXPECT_EQ(det->name(), "yolov5 (" + model_ + ")");
  ASSERT_EQ(det->class_names().size(), 80u);
  EXPECT_EQ(det->class_names()[56], "chair");
  const std::vector<Detection> d = det->detect(frame_, 0, 0);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].class_name, "person");
  EXPECT_EQ(d[0].class_id, 0);
  EXPECT_NEAR(d[0].confidence, 0.81f, 1e-5);
  // Input box (22, 17, 20, 30) -> ((22 - 0) / 0.1, (17 - 8) / 0.1, 200, 300).
  EXPECT_NEAR(d[0].box.x, 220.0f, 1e-3);
  EXPECT_NEAR(d[0].box.y, 90.0f, 1e-3);
  EXPECT_NEAR(d[0].box.width, 200.0f, 1e-3);
  EXPECT_NEAR(d[0].box.height, 300.0f, 1e-3);
  EXPECT_EQ(d[1].class_name, "chair");
  EXPECT_NEAR(d[1].confidence, 0.72f, 1e-5);
  // Input (45, 35, 10, 10) -> (450, 270, 100, 100).
  EXPECT_NEAR(d[1].box.x, 450.0f, 1e-3);
  EXPECT_NEAR(d[1].box.y, 270.0f, 1e-3);
  EXPECT_NEAR(d[1].box.width, 100.0f, 1e-3);
  EXPECT_NEAR(d[1].box.height, 100.0f, 1e-3);
}

TEST_F(Yolov5OnTinyModel, WantedClassesOnly) {
  config_.classes = {"chair"};
  const std::vector<Detection> d = make_dnn_detector(config_)->detect(frame_, 0, 0);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].class_name, "chair");
}

TEST_F(Yolov5OnTinyModel, NamesFileWithWrongClassCount) {
  config_.names = dir_.write("short.names", "person\ndog\ncat\n");
  try {
    make_dnn_detector(config_);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              model_ + ": model outputs 80 classes but " + config_.names + " lists 3");
  }
}

}  // namespace
}  // namespace depot::slam
