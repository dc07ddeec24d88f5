#pragma once
// Loading and running OpenCV dnn networks with one clear depot::Error per
// failure ("<file>: ..."), shared by the YOLOv5, Darknet and FastestDet
// detectors. Networks run on DNN_BACKEND_OPENCV / DNN_TARGET_CPU; the thread
// count is left to the application (cv::setNumThreads).
#include <string>
#include <vector>

#include <opencv2/dnn.hpp>

namespace depot::slam {

// Throws "<path>: <what> not found" unless `path` names a readable regular file.
void require_file(const std::string& path, const std::string& what);

// cv::dnn::readNetFromONNX; a cv::Exception becomes
// "<model>: cannot load model: <OpenCV's message>".
cv::dnn::Net load_onnx_net(const std::string& model);

// cv::dnn::readNetFromDarknet, with the same error wrapping. Also checks that
// the weights file holds exactly the parameters the cfg asks for (OpenCV reads
// a short file without complaint and runs on garbage).
cv::dnn::Net load_darknet_net(const std::string& cfg, const std::string& weights);

// Runs `net` on `blob` and returns its unconnected outputs (in
// getUnconnectedOutLayersNames order). A cv::Exception becomes
// "<model>: cannot run model: ...".
std::vector<cv::Mat> run_net(cv::dnn::Net& net, const cv::Mat& blob, const std::string& model);

// Throws "<model>: model produces non-finite outputs (corrupt weights?)" if
// any element of `m` (CV_32F) is NaN or infinite.
void require_finite(const cv::Mat& m, const std::string& model);

// "N" or "AxBxC" for error messages.
std::string shape_string(const cv::Mat& m);

}  // namespace depot::slam
