// face_detector.hpp - face detection on OpenCV DNN: BlazeFace (MediaPipe,
// Apache-2.0; short or full range) or RetinaFace MobileNet-0.25 (biubug6, MIT;
// finds profiles and far faces): faces with keypoints in a BGR frame.
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
    // (RetinaFace: no tragions; those two are the mouth's right and left corners)
    std::array<cv::Point2f, 6> keypoints;
    float score = 0.f;  // 0..1
    bool followed = false;  // found around the last frame's face by the tracker: the same face
};

// short: BlazeFace for faces within ~2 m (a driver); full: BlazeFace up to ~5 m;
// retina: RetinaFace, near and far faces and profiles (a 640 px search, slower)
enum class DetectorRange { Short, Full, Retina };

class FaceDetector {
public:
    // Loads face_detection_{short,full}_range.onnx or retinaface_640.onnx from models_dir;
    // throws EstimatorError.
    FaceDetector(const std::string &models_dir, DetectorRange range, float min_score = 0.5f);

    // Faces, best first, after weighted non-maximum suppression.
    std::vector<Face> detect(const cv::Mat &bgr);

private:
    std::vector<Face> detect_retina(const cv::Mat &bgr);

    bool retina_ = false;
    cv::dnn::Net net_;
    int input_size_ = 0;
    float min_score_;
    std::vector<cv::Point2f> anchors_;  // centres, normalised to the letterboxed input
    std::vector<cv::Vec3f> retina_anchors_;  // RetinaFace: centre x, y and side, px of the input
    std::vector<std::string> outputs_;  // scores, regressors
};

// Intersection over union of two boxes.
float iou(const cv::Rect2f &a, const cv::Rect2f &b);

}  // namespace hkf_estimator
