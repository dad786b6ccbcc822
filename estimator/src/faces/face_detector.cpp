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

// RetinaFace (biubug6/Pytorch_Retinaface's MobileNet-0.25 configuration): anchors of
// strides 8, 16, 32 with two square sizes each, centred on each cell; box offsets scaled
// by the variances 0.1 (centre) and 0.2 (log size); BGR input less the mean 104, 117, 123.
constexpr int kRetinaInput = 640;  // retinaface_640.onnx (dev/models/convert_retinaface.py)
constexpr float kRetinaCentreVariance = 0.1f, kRetinaSizeVariance = 0.2f, kRetinaNmsIou = 0.4f;

std::vector<cv::Vec3f> retina_anchors(int input)
{
    const int strides[3] = {8, 16, 32};
    const float sizes[3][2] = {{16.f, 32.f}, {64.f, 128.f}, {256.f, 512.f}};
    std::vector<cv::Vec3f> anchors;
    for (int level = 0; level < 3; ++level) {
        const int stride = strides[level], cells = (input + stride - 1) / stride;
        for (int y = 0; y < cells; ++y) {
            for (int x = 0; x < cells; ++x) {
                for (float size : sizes[level]) {
                    anchors.emplace_back((static_cast<float>(x) + 0.5f) * static_cast<float>(stride),
                                         (static_cast<float>(y) + 0.5f) * static_cast<float>(stride), size);
                }
            }
        }
    }
    return anchors;
}
}  // namespace

FaceDetector::FaceDetector(const std::string &models_dir, DetectorRange range, float min_score) : min_score_(min_score)
{
    if (range == DetectorRange::Retina) {
        retina_ = true;
        input_size_ = kRetinaInput;
        retina_anchors_ = retina_anchors(kRetinaInput);
        outputs_ = {"loc", "conf", "landmarks"};
        net_ = load_onnx_network(models_dir + "/retinaface_640.onnx", outputs_);
        return;
    }
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

std::vector<Face> FaceDetector::detect_retina(const cv::Mat &bgr)
{
    // letterbox into the square input, keeping the aspect ratio
    const float scale = static_cast<float>(input_size_) / static_cast<float>(std::max(bgr.cols, bgr.rows));
    const int w = std::max(1, static_cast<int>(std::lround(static_cast<float>(bgr.cols) * scale)));
    const int h = std::max(1, static_cast<int>(std::lround(static_cast<float>(bgr.rows) * scale)));
    cv::Mat small, input(input_size_, input_size_, CV_8UC3, cv::Scalar(104, 117, 123));
    cv::resize(bgr, small, cv::Size(w, h), 0, 0, cv::INTER_AREA);
    small.copyTo(input(cv::Rect(0, 0, w, h)));
    net_.setInput(cv::dnn::blobFromImage(input, 1.0, cv::Size(), cv::Scalar(104, 117, 123), false, false));
    std::vector<cv::Mat> out;
    net_.forward(out, outputs_);
    const int n = static_cast<int>(retina_anchors_.size());
    if (out.size() != 3 || out[0].total() != static_cast<size_t>(n) * 4 || out[1].total() != static_cast<size_t>(n) * 2 ||
        out[2].total() != static_cast<size_t>(n) * 10) {
        throw EstimatorError("RetinaFace gave outputs of unexpected sizes");
    }
    const float *loc = out[0].ptr<float>(), *conf = out[1].ptr<float>(), *marks = out[2].ptr<float>();
    std::vector<cv::Rect2d> boxes;
    std::vector<float> scores;
    std::vector<Face> candidates;
    for (int i = 0; i < n; ++i) {
        const float score = conf[2 * i + 1];
        if (!(score >= min_score_)) continue;
        const cv::Vec3f &a = retina_anchors_[static_cast<size_t>(i)];
        const float *l = loc + 4 * i, *m = marks + 10 * i;
        const float cx = a[0] + l[0] * kRetinaCentreVariance * a[2], cy = a[1] + l[1] * kRetinaCentreVariance * a[2];
        const float bw = a[2] * std::exp(l[2] * kRetinaSizeVariance), bh = a[2] * std::exp(l[3] * kRetinaSizeVariance);
        Face f;
        f.score = score;
        f.box = cv::Rect2f((cx - bw / 2.f) / scale, (cy - bh / 2.f) / scale, bw / scale, bh / scale);
        cv::Point2f p[5];
        for (int k = 0; k < 5; ++k) {  // the subject's right eye, left eye, nose, mouth's right, left corner
            p[k] = {(a[0] + m[2 * k] * kRetinaCentreVariance * a[2]) / scale,
                    (a[1] + m[2 * k + 1] * kRetinaCentreVariance * a[2]) / scale};
        }
        f.keypoints = {p[0], p[1], p[2], (p[3] + p[4]) * 0.5f, p[3], p[4]};
        if (!std::isfinite(f.box.x) || !std::isfinite(f.box.width)) continue;
        candidates.push_back(f);
        boxes.emplace_back(f.box.x, f.box.y, f.box.width, f.box.height);
        scores.push_back(score);
    }
    std::vector<int> keep;
    cv::dnn::NMSBoxes(boxes, scores, min_score_, kRetinaNmsIou, keep);
    std::vector<Face> faces;
    for (int k : keep) faces.push_back(candidates[static_cast<size_t>(k)]);
    std::sort(faces.begin(), faces.end(), [](const Face &a, const Face &b) { return a.score > b.score; });
    return faces;
}

std::vector<Face> FaceDetector::detect(const cv::Mat &bgr)
{
    if (bgr.empty() || bgr.type() != CV_8UC3) return {};
    if (retina_) return detect_retina(bgr);
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
