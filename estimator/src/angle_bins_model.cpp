// angle_bins_model.cpp - see angle_bins_model.hpp.
#include "angle_bins_model.hpp"

#include <cmath>

#include "onnx_network.hpp"

namespace hkf_estimator {

AngleBinsModel::AngleBinsModel(ModelSpec spec)
    : spec_(std::move(spec)),
      outputs_{spec_.pitch.output, spec_.yaw.output, spec_.roll.output}
{
    net_ = load_onnx_network(spec_.file, outputs_);
}

cv::Mat AngleBinsModel::make_input(const cv::Mat &bgr_crop) const { return network_input(spec_, bgr_crop); }

float AngleBinsModel::decode_bins(const cv::Mat &logits, const AngleBins &bins) const
{
    if (static_cast<int>(logits.total()) != bins.bins)
        throw EstimatorError("output '" + bins.output + "' has " + std::to_string(logits.total()) + " values, the description says " +
                             std::to_string(bins.bins));
    const float *v = logits.ptr<float>();
    float peak = v[0];
    for (int i = 1; i < bins.bins; ++i) peak = std::max(peak, v[i]);
    double sum = 0.0, expectation = 0.0;
    for (int i = 0; i < bins.bins; ++i) {
        const double e = std::exp(static_cast<double>(v[i] - peak));  // softmax, shifted for range
        sum += e;
        expectation += e * i;
    }
    return static_cast<float>(expectation / sum * bins.step + bins.offset);
}

HeadPose AngleBinsModel::estimate_input(const cv::Mat &input)
{
    net_.setInput(input);
    std::vector<cv::Mat> out;
    net_.forward(out, outputs_);
    HeadPose pose;
    pose.pitch = spec_.signs[0] * decode_bins(out[0], spec_.pitch);
    pose.yaw = spec_.signs[1] * decode_bins(out[1], spec_.yaw);
    pose.roll = spec_.signs[2] * decode_bins(out[2], spec_.roll);
    return pose;
}

std::optional<HeadPose> AngleBinsModel::estimate(const cv::Mat &frame, const Face &face)
{
    const cv::Rect crop = face_crop_rect(face.box, spec_.crop_margin, frame.size());
    if (crop.empty()) return std::nullopt;
    return estimate_crop(frame(crop));
}

cv::Rect face_crop_rect(const cv::Rect2f &box, float margin, const cv::Size &image)
{
    const float dx = box.width * margin, dy = box.height * margin;
    const int x0 = std::max(0, static_cast<int>(std::floor(box.x - dx)));
    const int y0 = std::max(0, static_cast<int>(std::floor(box.y - dy)));
    const int x1 = std::min(image.width, static_cast<int>(std::ceil(box.x + box.width + dx)));
    const int y1 = std::min(image.height, static_cast<int>(std::ceil(box.y + box.height + dy)));
    if (x1 <= x0 || y1 <= y0) return cv::Rect();
    return cv::Rect(x0, y0, x1 - x0, y1 - y0);
}

}  // namespace hkf_estimator
