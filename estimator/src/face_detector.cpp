// face_detector.cpp - see face_detector.hpp. Anchors, decoding and weighted
// non-maximum suppression follow MediaPipe's face detection graph settings.
#include "face_detector.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "model_spec.hpp"
#include "network_outputs.hpp"
#include "onnx_network.hpp"

namespace hkf_estimator {

namespace {
constexpr float kNmsIou = 0.3f;  // MediaPipe's min_suppression_threshold
}

FaceDetector::FaceDetector(const std::string &models_dir, DetectorRange range, float min_score) : min_score_(min_score)
{
    const bool short_range = range == DetectorRange::Short;
    const std::string file = models_dir + (short_range ? "/face_detection_short_range.onnx" : "/face_detection_full_range.onnx");
    if (short_range) {
        input_size_ = 128;  // strides 8, 16, 16, 16; two anchors per layer and location
        anchors_ = ssd_anchors(input_size_, {8, 16, 16, 16}, 2);
        outputs_ = {"classificators", "regressors"};
    } else {
        input_size_ = 192;  // one layer of stride 4, one anchor per location
        anchors_ = ssd_anchors(input_size_, {4}, 1);
        outputs_ = {"reshaped_classifier_face_4", "reshaped_regressor_face_4"};
    }
    net_ = load_onnx_network(file, outputs_);
}

std::vector<Face> FaceDetector::detect(const cv::Mat &bgr)
{
    if (bgr.empty() || bgr.type() != CV_8UC3) return {};
    // letterbox to a square, keeping the aspect ratio, then RGB in [-1, 1]
    const int side = std::max(bgr.cols, bgr.rows);
    const int pad_x = (side - bgr.cols) / 2, pad_y = (side - bgr.rows) / 2;
    cv::Mat square, small, rgb;
    cv::copyMakeBorder(bgr, square, pad_y, side - bgr.rows - pad_y, pad_x, side - bgr.cols - pad_x, cv::BORDER_CONSTANT);
    cv::resize(square, small, cv::Size(input_size_, input_size_), 0, 0, cv::INTER_AREA);
    cv::cvtColor(small, rgb, cv::COLOR_BGR2RGB);
    net_.setInput(cv::dnn::blobFromImage(rgb, 1.0 / 127.5, cv::Size(), cv::Scalar(127.5, 127.5, 127.5)));
    std::vector<cv::Mat> out;
    net_.forward(out, outputs_);
    if (out.size() != 2) throw EstimatorError("the face detector gave " + std::to_string(out.size()) + " outputs, not 2");
    std::vector<Face> candidates = decode_face_detections(
        out[0], out[1], anchors_, input_size_,
        Letterbox{static_cast<float>(side), static_cast<float>(pad_x), static_cast<float>(pad_y)}, min_score_);
    std::sort(candidates.begin(), candidates.end(), [](const Face &a, const Face &b) { return a.score > b.score; });

    // weighted non-maximum suppression: each kept face is the score-weighted
    // mean of the candidates overlapping the best remaining one
    std::vector<Face> faces;
    std::vector<bool> used(candidates.size(), false);
    for (size_t i = 0; i < candidates.size(); ++i) {
        if (used[i]) continue;
        Face merged = candidates[i];
        float total = 0.f, x = 0.f, y = 0.f, w = 0.f, h = 0.f;
        std::array<cv::Point2f, 6> keypoints{};
        for (size_t j = i; j < candidates.size(); ++j) {
            if (used[j] || iou(candidates[i].box, candidates[j].box) <= kNmsIou) continue;
            used[j] = true;
            const Face &c = candidates[j];
            total += c.score;
            x += c.score * c.box.x;
            y += c.score * c.box.y;
            w += c.score * c.box.width;
            h += c.score * c.box.height;
            for (size_t k = 0; k < 6; ++k) keypoints[k] += c.score * c.keypoints[k];
        }
        merged.box = cv::Rect2f(x / total, y / total, w / total, h / total);
        for (size_t k = 0; k < 6; ++k) merged.keypoints[k] = keypoints[k] / total;
        faces.push_back(merged);
    }
    return faces;
}

float iou(const cv::Rect2f &a, const cv::Rect2f &b)
{
    const float overlap = (a & b).area();
    const float total = a.area() + b.area() - overlap;
    return total > 0.f ? overlap / total : 0.f;
}

}  // namespace hkf_estimator
