// network_outputs.hpp - reading the networks' outputs. Each output is checked
// against the size and type the model description (or the detector's anchors)
// implies before a value is read: a model file that does not match its
// description gives an EstimatorError naming the output, never a read past its
// end; non-finite values give no face rather than a NaN pose. Free of any
// network, so that tests/fuzz/fuzz_estimator_outputs.cpp feeds it any output.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "face_detector.hpp"
#include "model_spec.hpp"

namespace hkf_estimator {

// SSD anchor centres, normalised to the square input: layers of equal stride
// share one grid; per location each layer adds anchors_per_layer anchors.
std::vector<cv::Point2f> ssd_anchors(int input_size, const std::vector<int> &strides, int anchors_per_layer);

// Where the square network input sits in the frame: its side in frame px and
// the letterbox padding (frame px) on the left and top.
struct Letterbox {
    float side = 0.f, pad_x = 0.f, pad_y = 0.f;
};

// BlazeFace's two outputs -> the candidate faces scoring at least min_score
// (before non-maximum suppression). scores: one logit per anchor; regressors:
// 16 values per anchor (box centre and size, six keypoints, input px).
std::vector<Face> decode_face_detections(const cv::Mat &scores, const cv::Mat &regressors,
                                         const std::vector<cv::Point2f> &anchors, int input_size,
                                         const Letterbox &letterbox, float min_score);

// An angle-bins head's logits -> the softmax expectation over its bins (deg);
// NaN when a logit is not finite.
float decode_angle_bins(const cv::Mat &logits, const AngleBins &bins);

// The face mesh's face flag (a logit) -> its probability.
float decode_face_flag(const cv::Mat &flag, const std::string &output);

// The face mesh's landmarks output: x y z per landmark (input px).
const float *mesh_landmarks(const cv::Mat &landmarks, int count, const std::string &output);

}  // namespace hkf_estimator
