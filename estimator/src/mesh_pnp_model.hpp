// mesh_pnp_model.hpp - head pose from face-mesh landmarks and a 3D face.
//
// The detected face's box, squared on its long side and enlarged by
// roi_scale, is rotated so the eyes are level (from the detector's eye
// keypoints) and warped to the mesh network's input; its landmarks, mapped
// back to the frame, are matched to a canonical 3D face with cv::solvePnP
// (SQPNP: plain ITERATIVE can return the mirrored solution). The rotation
// relative to a face looking into the camera is the head pose. Independent of
// any angle-regression network.
#pragma once

#include <vector>

#include <opencv2/dnn.hpp>

#include "head_pose_estimator.hpp"

namespace hkf_estimator {

class MeshPnpModel : public HeadPoseEstimator {
public:
    // Loads the mesh network and the canonical face; throws EstimatorError.
    explicit MeshPnpModel(ModelSpec spec);

    const ModelSpec &spec() const override { return spec_; }
    bool needs_keypoints() const override { return true; }
    std::optional<HeadPose> estimate(const cv::Mat &frame, const Face &face) override;

    // The last estimate's landmarks, px in the frame.

private:
    ModelSpec spec_;
    cv::dnn::Net net_;
    std::vector<cv::Point3f> canonical_;
    std::vector<cv::Point2f> landmarks_;
};

}  // namespace hkf_estimator
