// face_detector.hpp - BlazeFace (MediaPipe, Apache-2.0) on OpenCV DNN: faces
// with six keypoints in a BGR frame.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>

namespace hkf_estimator {

struct Face {
    cv::Rect2f box;  // px in the frame
    // px: the subject's right eye, left eye, nose tip, mouth centre, right ear tragion, left ear tragion
    std::array<cv::Point2f, 6> keypoints;
    float score = 0.f;  // 0..1
};

enum class DetectorRange { Short, Full };  // short: faces within ~2 m (a driver); full: up to ~5 m

class FaceDetector {
public:
    // Loads face_detection_{short,full}_range.onnx from models_dir; throws EstimatorError.
    FaceDetector(const std::string &models_dir, DetectorRange range, float min_score = 0.5f);

    // Faces, best first, after weighted non-maximum suppression.
    std::vector<Face> detect(const cv::Mat &bgr);

private:

    cv::dnn::Net net_;
    int input_size_ = 0;
    float min_score_;
    std::vector<cv::Point2f> anchors_;  // centres, normalised to the letterboxed input
    std::vector<std::string> outputs_;  // scores, regressors
};

// Intersection over union of two boxes.
float iou(const cv::Rect2f &a, const cv::Rect2f &b);

}  // namespace hkf_estimator
