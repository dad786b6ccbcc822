// network_outputs.cpp - see network_outputs.hpp.
#include "network_outputs.hpp"

#include <algorithm>
#include <cmath>

namespace hkf_estimator {
namespace {

// The output's float values, after checking it holds `expected` of them.
const float *checked_floats(const cv::Mat &out, size_t expected, const std::string &what)
{
    if (out.empty() || out.depth() != CV_32F || out.channels() != 1 || !out.isContinuous() || out.total() != expected)
        throw EstimatorError("the network output '" + what + "' has " + std::to_string(out.total()) + " values of type " +
                             std::to_string(out.type()) + "; the model description implies " + std::to_string(expected) +
                             " floats (a model file that does not match its description?)");
    return out.ptr<float>();
}

}  // namespace

std::vector<cv::Point2f> ssd_anchors(int input_size, const std::vector<int> &strides, int anchors_per_layer)
{
    std::vector<cv::Point2f> anchors;
    for (size_t layer = 0; layer < strides.size();) {
        size_t last = layer;
        while (last < strides.size() && strides[last] == strides[layer]) ++last;
        const int per_location = anchors_per_layer * static_cast<int>(last - layer);
        const int cells = (input_size + strides[layer] - 1) / strides[layer];
        for (int y = 0; y < cells; ++y)
            for (int x = 0; x < cells; ++x)
                for (int k = 0; k < per_location; ++k)
                    anchors.push_back({(static_cast<float>(x) + 0.5f) / static_cast<float>(cells),
                                       (static_cast<float>(y) + 0.5f) / static_cast<float>(cells)});
        layer = last;
    }
    return anchors;
}

std::vector<Face> decode_face_detections(const cv::Mat &scores, const cv::Mat &regressors,
                                         const std::vector<cv::Point2f> &anchors, int input_size,
                                         const Letterbox &letterbox, float min_score)
{
    const float *score_logits = checked_floats(scores, anchors.size(), "detector scores");
    const float *regress = checked_floats(regressors, 16 * anchors.size(), "detector regressors");
    const float to_px = letterbox.side, size = static_cast<float>(input_size);
    std::vector<Face> candidates;
    for (size_t i = 0; i < anchors.size(); ++i) {
        if (!std::isfinite(score_logits[i])) continue;
        const float raw = std::min(100.f, std::max(-100.f, score_logits[i]));
        const float score = 1.f / (1.f + std::exp(-raw));
        if (score < min_score) continue;
        const float *r = regress + 16 * i;
        if (!std::all_of(r, r + 16, [](float v) { return std::isfinite(v) && std::fabs(v) < 1e6f; })) continue;
        const cv::Point2f &a = anchors[i];
        const float cx = a.x + r[0] / size, cy = a.y + r[1] / size, w = r[2] / size, h = r[3] / size;
        if (!(w > 0.f && h > 0.f)) continue;  // no box
        Face f;
        f.score = score;
        f.box = cv::Rect2f((cx - w / 2) * to_px - letterbox.pad_x, (cy - h / 2) * to_px - letterbox.pad_y, w * to_px,
                           h * to_px);
        for (int k = 0; k < 6; ++k)
            f.keypoints[static_cast<size_t>(k)] = {(a.x + r[4 + 2 * k] / size) * to_px - letterbox.pad_x,
                                                   (a.y + r[5 + 2 * k] / size) * to_px - letterbox.pad_y};
        candidates.push_back(f);
    }
    return candidates;
}

float decode_angle_bins(const cv::Mat &logits, const AngleBins &bins)
{
    const float *v = checked_floats(logits, static_cast<size_t>(std::max(bins.bins, 0)), bins.output);
    if (bins.bins < 1 || !std::all_of(v, v + bins.bins, [](float x) { return std::isfinite(x); }))
        return std::nanf("");
    const float peak = *std::max_element(v, v + bins.bins);
    double sum = 0.0, expectation = 0.0;
    for (int i = 0; i < bins.bins; ++i) {
        const double e = std::exp(static_cast<double>(v[i] - peak));  // softmax, shifted for range
        sum += e;
        expectation += e * i;
    }
    return static_cast<float>(expectation / sum * bins.step + bins.offset);
}

float decode_face_flag(const cv::Mat &flag, const std::string &output)
{
    const float logit = checked_floats(flag, 1, output)[0];
    return std::isfinite(logit) ? 1.f / (1.f + std::exp(-std::min(100.f, std::max(-100.f, logit)))) : 0.f;
}

const float *mesh_landmarks(const cv::Mat &landmarks, int count, const std::string &output)
{
    return checked_floats(landmarks, 3 * static_cast<size_t>(std::max(count, 0)), output);
}

}  // namespace hkf_estimator
