// angle_bins_model.hpp - a head-pose network whose outputs are angle bins
// (WHENet-like), run by OpenCV's DNN module: a face crop in, pitch/yaw/roll
// (deg, hkf convention) out, each the softmax expectation over its bins.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>

#include "head_pose_estimator.hpp"
#include "model_spec.hpp"

namespace hkf_estimator {

class AngleBinsModel : public HeadPoseEstimator {
public:
    // Loads spec.file; throws EstimatorError when it is missing, corrupt, or
    // lacks the outputs the description names.
    explicit AngleBinsModel(ModelSpec spec);

    const ModelSpec &spec() const override { return spec_; }
    bool needs_keypoints() const override { return false; }
    // The face box enlarged by the crop margin.
    std::optional<HeadPose> estimate(const cv::Mat &frame, const Face &face) override;

    // The network's input for a face crop (BGR, any size): resized, colour
    // order, scale, mean and std applied; NCHW float.
    cv::Mat make_input(const cv::Mat &bgr_crop) const;

    // A crop's reading; with flip_average, averaged with its mirror's (yaw and roll negated).
    HeadPose estimate_crop(const cv::Mat &bgr_crop);
    HeadPose estimate_input(const cv::Mat &input);

private:

    ModelSpec spec_;
    cv::dnn::Net net_;
    std::vector<std::string> outputs_;
};

}  // namespace hkf_estimator
