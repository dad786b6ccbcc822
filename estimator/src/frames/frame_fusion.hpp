// frame_fusion.hpp - what the default pipeline makes of one frame that two models measured:
// hkf-estimator runs the second model where the first's |yaw| is at least --second-from-yaw (or
// the first has no pose), and hkf-filter takes the second alone where the first's |yaw| is at least
// its pair_second_alone_from_yaw, and between the two fuses them with inverse-variance weights,
// each model's R from its Eq. 8 curve at its own angle (libhkf's hkf_observation_noise with the
// curves hkf-filter has built in). A single frame has no history: the node's offset between the
// two models is not applied. hkf-estimator --dataset measures the pipeline this way.
#pragma once

#include <optional>
#include <string>

#include "hkf/hkf.h"
#include "head_pose_estimator.hpp"
#include "model_pairing.h"

namespace hkf_estimator {

// the pairing rule's constant, which hkf-filter's pair_second_alone_from_yaw defaults to (model_pairing.h), deg
constexpr float kSecondAloneFromYaw = static_cast<float>(HKF_SECOND_ALONE_FROM_YAW);

class FrameFusion {
public:
    // Throws EstimatorError for a model whose Eq. 8 curves hkf-filter does not have built in.
    FrameFusion(const std::string &first_model, const std::string &second_model, float second_from_yaw,
                float second_alone_from_yaw = kSecondAloneFromYaw);
    // The live pipeline runs the second model on this frame.
    bool wants_second(const std::optional<HeadPose> &first) const;
    // The frame's pose: the first's, the second's, or both fused (no pose when neither has one).
    std::optional<HeadPose> fuse(const std::optional<HeadPose> &first, const std::optional<HeadPose> &second) const;

private:
    hkf_filter_t first_noise_, second_noise_;  // initialised only to evaluate each model's R (Eq. 8)
    float second_from_yaw_, second_alone_from_yaw_;
};

}  // namespace hkf_estimator
