// head_pose_estimator.hpp - what every head-pose estimator offers: a frame and
// a detected face in, a head pose (hkf convention) out. The model
// description's decoder picks the kind (estimator/models/*.model).
#pragma once

#include <memory>
#include <optional>
#include <vector>
#include <string>

#include <opencv2/core.hpp>

#include "face_detector.hpp"
#include "head_pose.hpp"
#include "head_position.hpp"
#include "model_spec.hpp"

namespace hkf_estimator {

class HeadPoseEstimator {
public:
    virtual ~HeadPoseEstimator() = default;
    virtual const ModelSpec &spec() const = 0;
    // True when estimate() uses the face's keypoints, not only its box.
    virtual bool needs_keypoints() const = 0;
    // True when estimate() on a face the tracker followed (Face::followed) uses what it measured
    // on the frame before: a still image is then estimated twice, searched and followed, as video is.
    virtual bool follows_faces() const { return false; }
    // The pose of the face in frame (BGR); nullopt when the model finds no face there.
    virtual std::optional<HeadPose> estimate(const cv::Mat &frame, const Face &face) = 0;
    // The landmarks the last estimate was fitted to, px in the frame (none for a model without any).
    virtual std::vector<cv::Point2f> landmarks() const { return {}; }

    // The camera and head the position is measured with (--fov, --pivot).
    void set_position_settings(const PositionSettings &settings) { position_settings_ = settings; }
    // Faces on which the network gave NaN or infinite outputs (no pose): a healthy network never
    // does, so any is a sign of damaged weights.
    long non_finite_outputs() const { return non_finite_outputs_; }

protected:
    // false (and counted) when a network output holds a NaN or an infinity
    bool finite_outputs(const std::vector<cv::Mat> &outputs)
    {
        for (const cv::Mat &m : outputs)
            if (!cv::checkRange(m)) return ++non_finite_outputs_, false;
        return true;
    }
    PositionSettings position_settings_;

private:
    long non_finite_outputs_ = 0;
};

// The estimator a description names: angle_bins or landmarks_pnp. Throws EstimatorError.
std::unique_ptr<HeadPoseEstimator> make_estimator(const ModelSpec &spec);

}  // namespace hkf_estimator
