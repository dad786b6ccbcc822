// network_input.hpp - an image prepared the way a model description says:
// resized to the input size, colour order, pixel * scale, (x - mean) / std, NCHW.
#pragma once

#include <opencv2/core.hpp>

#include "model_spec.hpp"

namespace hkf_estimator {

cv::Mat network_input(const ModelSpec &spec, const cv::Mat &bgr);

}  // namespace hkf_estimator
