// angle_bins_model.cpp - see angle_bins_model.hpp.
#include "angle_bins_model.hpp"

#include <cmath>

#include "face_crop.hpp"
#include "head_rotation.hpp"
#include "network_outputs.hpp"
#include "onnx_network.hpp"

namespace hkf_estimator {

AngleBinsModel::AngleBinsModel(ModelSpec spec)
    : spec_(std::move(spec)),
      outputs_{spec_.pitch.output, spec_.yaw.output, spec_.roll.output}
{
    net_ = load_onnx_network(spec_.file, outputs_);
}

cv::Mat AngleBinsModel::make_input(const cv::Mat &bgr_crop) const { return network_input(spec_, bgr_crop); }

HeadPose AngleBinsModel::estimate_input(const cv::Mat &input)
{
    net_.setInput(input);
    std::vector<cv::Mat> out;
    net_.forward(out, outputs_);
    if (out.size() != 3) throw EstimatorError(spec_.name + " gave " + std::to_string(out.size()) + " outputs, not 3");
    if (!finite_outputs(out)) return HeadPose(std::nanf(""), std::nanf(""), std::nanf(""));
    HeadPose pose;
    pose.pitch = spec_.signs[0] * decode_angle_bins(out[0], spec_.pitch);
    pose.yaw = spec_.signs[1] * decode_angle_bins(out[1], spec_.yaw);
    pose.roll = spec_.signs[2] * decode_angle_bins(out[2], spec_.roll);
    return pose;
}

HeadPose AngleBinsModel::estimate_crop(const cv::Mat &bgr_crop)
{
    HeadPose pose = estimate_input(make_input(bgr_crop));
    if (!spec_.flip_average) return pose;
    cv::Mat mirrored;
    cv::flip(bgr_crop, mirrored, 1);
    const HeadPose m = estimate_input(make_input(mirrored));
    pose.pitch = 0.5f * (pose.pitch + m.pitch);
    pose.yaw = 0.5f * (pose.yaw - m.yaw);
    pose.roll = 0.5f * (pose.roll - m.roll);
    return pose;
}

std::optional<HeadPose> AngleBinsModel::estimate(const cv::Mat &frame, const Face &face)
{
    const cv::Rect crop = face_crop_rect(face.box, spec_.crop_margin, frame.size());
    if (crop.empty()) return std::nullopt;
    HeadPose pose = estimate_crop(frame(crop));
    if (spec_.profile_from_deg > 0.f && std::fabs(pose.yaw) >= spec_.profile_from_deg) {
        cv::Rect2f box = face.box;
        box.x += (pose.yaw < 0.f ? -spec_.profile_shift : spec_.profile_shift) * box.width;
        const cv::Rect profile = face_crop_rect(box, spec_.profile_margin, frame.size());
        if (!profile.empty()) pose = estimate_crop(frame(profile));
    }
    if (!std::isfinite(pose.pitch) || !std::isfinite(pose.yaw) || !std::isfinite(pose.roll)) return std::nullopt;
    // no landmarks: the position from the box and an average face (head_position.hpp)
    const cv::Vec3d nose = rotation_from_pose(pose) * cv::Vec3d(0.0, 0.0, -1.0);
    const HeadPosition p = position_from_box(face.box, frame.size(), focal_from_fov(frame.size(), position_settings_.fov_deg),
                                             position_settings_.box_face_width_cm, nose, position_settings_.pivot_cm);
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && p.z > 0.f) {
        pose.position = p;
        pose.has_position = true;
    }
    return pose;
}

}  // namespace hkf_estimator
