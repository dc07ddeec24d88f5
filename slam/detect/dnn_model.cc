#include "slam/detect/dnn_model.h"

#include <sys/stat.h>

#include <cmath>
#include <cstdint>
#include <fstream>

#include "common/error.h"

namespace depot::slam {
namespace {

void use_cpu(cv::dnn::Net& net) {
  net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
}

// OpenCV's message without the "OpenCV(4.x) file:line: error: (-n:...)" prefix.
std::string cv_message(const cv::Exception& e) {
  return e.err.empty() ? e.what() : e.err;
}

// Parameters (floats) Darknet reads from the weights file for `net`: the
// convolution / connected weights and biases and the batch-norm statistics.
size_t darknet_parameter_count(cv::dnn::Net& net) {
  size_t n = 0;
  for (const std::string& name : net.getLayerNames()) {
    const cv::Ptr<cv::dnn::Layer> layer = net.getLayer(name);
    if (layer->type != "Convolution" && layer->type != "BatchNorm" && layer->type != "InnerProduct")
      continue;
    for (const cv::Mat& b : layer->blobs) n += b.total();
  }
  return n;
}

// Floats after the header of a Darknet weights file (its layout: int32 major,
// minor, revision; "seen" as uint64 from version 0.2 on, else uint32).
size_t darknet_weights_floats(const std::string& weights) {
  std::ifstream in(weights, std::ios::binary | std::ios::ate);
  if (!in) fail(weights, "cannot open weights file");
  const auto size = static_cast<size_t>(in.tellg());
  in.seekg(0);
  int32_t header[3] = {0, 0, 0};
  if (size < sizeof header || !in.read(reinterpret_cast<char*>(header), sizeof header))
    fail(weights, "cannot load model: weights file too short for a Darknet header");
  const int32_t major = header[0], minor = header[1];
  const size_t seen = (major * 10 + minor >= 2 && major < 1000 && minor < 1000) ? 8 : 4;
  const size_t head = sizeof header + seen;
  return size > head ? (size - head) / sizeof(float) : 0;
}

}  // namespace

void require_file(const std::string& path, const std::string& what) {
  struct stat st {};
  if (path.empty()) fail(what, "no path given");
  if (::stat(path.c_str(), &st) != 0) fail(path, what + " not found");
  if (!S_ISREG(st.st_mode)) fail(path, what + " is not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot read " + what);
}

cv::dnn::Net load_onnx_net(const std::string& model) {
  require_file(model, "model file");
  cv::dnn::Net net;
  try {
    net = cv::dnn::readNetFromONNX(model);
  } catch (const cv::Exception& e) {
    fail(model, "cannot load model: " + cv_message(e));
  }
  if (net.empty()) fail(model, "cannot load model: OpenCV returned an empty network");
  use_cpu(net);
  return net;
}

cv::dnn::Net load_darknet_net(const std::string& cfg, const std::string& weights) {
  require_file(weights, "model file");
  require_file(cfg, "Darknet cfg file");
  cv::dnn::Net net;
  try {
    net = cv::dnn::readNetFromDarknet(cfg, weights);
  } catch (const cv::Exception& e) {
    fail(weights, "cannot load model with " + cfg + ": " + cv_message(e));
  }
  if (net.empty()) fail(weights, "cannot load model: OpenCV returned an empty network");
  const size_t needed = darknet_parameter_count(net);
  const size_t present = darknet_weights_floats(weights);
  if (present < needed)
    fail(weights, "cannot load model: weights file holds " + std::to_string(present) +
                      " parameters but " + cfg + " needs " + std::to_string(needed) +
                      " (truncated or not for this cfg)");
  use_cpu(net);
  return net;
}

std::vector<cv::Mat> run_net(cv::dnn::Net& net, const cv::Mat& blob, const std::string& model) {
  std::vector<cv::Mat> outs;
  try {
    net.setInput(blob);
    net.forward(outs, net.getUnconnectedOutLayersNames());
  } catch (const cv::Exception& e) {
    fail(model, "cannot run model on a " + shape_string(blob) + " input: " + cv_message(e));
  }
  if (outs.empty()) fail(model, "model has no output");
  return outs;
}

void require_finite(const cv::Mat& m, const std::string& model) {
  if (!cv::checkRange(m, true, nullptr, -1e30, 1e30))
    fail(model, "model produces non-finite outputs (corrupt weights?)");
}

std::string shape_string(const cv::Mat& m) {
  std::string s;
  for (int i = 0; i < m.dims; ++i) s += (i ? "x" : "") + std::to_string(m.size[i]);
  return s.empty() ? "0" : s;
}

}  // namespace depot::slam
