// onnx_network.hpp - loading an ONNX network into OpenCV DNN, and preparing
// its input the way a model description says.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>

#include "model_spec.hpp"

namespace hkf_estimator {

// Reads file; throws EstimatorError when it is missing, not readable ONNX, or
// lacks one of the named outputs.
cv::dnn::Net load_onnx_network(const std::string &file, const std::vector<std::string> &outputs);

// An image resized to the input size, colour order, pixel * scale,
// (x - mean) / std, as NCHW float.
cv::Mat network_input(const ModelSpec &spec, const cv::Mat &bgr);

}  // namespace hkf_estimator
