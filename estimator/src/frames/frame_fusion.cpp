// frame_fusion.cpp - see frame_fusion.hpp.
#include "frame_fusion.hpp"

#include <cmath>

#include "hkf/hkf_models.h"

namespace hkf_estimator {
namespace {

// The filter settings whose R is the model's: hkf-filter's defaults with the model's built-in curves.
void init_noise(hkf_filter_t &filter, const std::string &model)
{
    const hkf_model_info_t *info = hkf_find_model(model.c_str());  // libhkf's table of models, as hkf-filter's
    if (info == nullptr)
        throw EstimatorError("libhkf's table of models (hkf/hkf_models.h) has no noise curves for model '" + model +
                             "' to fuse it with: measure it alone (--second-model none)");
    hkf_settings_t settings = hkf_default_settings;
    settings.noise_mode = HKF_NOISE_ADAPTIVE;
    for (int a = 0; a < 3; ++a) settings.noise[a] = info->noise[a];
    if (hkf_init(&filter, &settings) != HKF_OK) throw EstimatorError("libhkf refused the settings of " + model);
}

}  // namespace

FrameFusion::FrameFusion(const std::string &first_model, const std::string &second_model, float second_from_yaw,
                         float second_alone_from_yaw)
    : second_from_yaw_(second_from_yaw), second_alone_from_yaw_(second_alone_from_yaw)
{
    init_noise(first_noise_, first_model);
    init_noise(second_noise_, second_model);
}

bool FrameFusion::wants_second(const std::optional<HeadPose> &first) const
{
    return !first || std::fabs(first->yaw) >= second_from_yaw_;
}

std::optional<HeadPose> FrameFusion::fuse(const std::optional<HeadPose> &first, const std::optional<HeadPose> &second) const
{
    if (!first) return second;
    if (!second || std::fabs(first->yaw) < second_from_yaw_) return first;
    if (std::fabs(first->yaw) >= second_alone_from_yaw_) return second;
    const float a[3] = {first->pitch, first->yaw, first->roll}, b[3] = {second->pitch, second->yaw, second->roll};
    float fused[3];
    for (int axis = 0; axis < 3; ++axis) {  // inverse-variance weights, each R by Eq. 8 at its own angle
        const double wa = 1.0 / static_cast<double>(hkf_observation_noise(&first_noise_, axis, a[axis]));
        const double wb = 1.0 / static_cast<double>(hkf_observation_noise(&second_noise_, axis, b[axis]));
        fused[axis] = static_cast<float>((wa * a[axis] + wb * b[axis]) / (wa + wb));
    }
    HeadPose pose(fused[0], fused[1], fused[2]);
    pose.has_position = first->has_position;  // the position is the first model's (the mesh's)
    pose.position = first->position;
    return pose;
}

}  // namespace hkf_estimator
