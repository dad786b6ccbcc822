// network_input.cpp - see network_input.hpp.
#include "network_input.hpp"

#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

namespace hkf_estimator {

cv::Mat network_input(const ModelSpec &spec, const cv::Mat &bgr)
{
    if (bgr.empty() || bgr.type() != CV_8UC3) throw EstimatorError("a network input must be a non-empty 8-bit BGR image");
    cv::Mat resized, color, scaled;
    if (bgr.cols == spec.input_width && bgr.rows == spec.input_height) {
        resized = bgr;
    } else {
        cv::resize(bgr, resized, cv::Size(spec.input_width, spec.input_height), 0, 0, cv::INTER_LINEAR);
    }
    if (spec.rgb) {
        cv::cvtColor(resized, color, cv::COLOR_BGR2RGB);
    } else {
        color = resized;
    }
    color.convertTo(scaled, CV_32FC3, spec.scale);
    scaled -= cv::Scalar(spec.mean[0], spec.mean[1], spec.mean[2]);
    cv::divide(scaled, cv::Scalar(spec.std[0], spec.std[1], spec.std[2]), scaled);
    return cv::dnn::blobFromImage(scaled);  // HWC -> NCHW, no further change
}

}  // namespace hkf_estimator
