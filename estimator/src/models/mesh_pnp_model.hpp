// mesh_pnp_model.hpp - head pose from face-mesh landmarks and a 3D face.
//
// The detected face's box, squared on its long side and enlarged by
// roi_scale, is rotated so the eyes are level (from the detector's eye
// keypoints) and warped to the mesh network's input; a face the tracker
// followed from the last frame gets a region of roi_face_cm of face at the
// scale the last fit measured instead, which no turn changes (a rolled or
// turned face's box shrinks, and the mesh reads a face in a tighter region as
// farther: docs/estimator.md, "The mesh's region"); its landmarks, mapped
// back to the frame, are matched to a canonical 3D face with cv::solvePnP
// (SQPNP: plain ITERATIVE can return the mirrored solution). The rotation
// relative to a face looking into the camera is the head pose. Independent of
// any angle-regression network. The position: a second fit, of the rigid upper
// face alone, with the focal length of --fov (head_position.hpp).
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
    bool follows_faces() const override { return spec_.roi_face_cm > 0.f; }
    std::optional<HeadPose> estimate(const cv::Mat &frame, const Face &face) override;
    std::vector<cv::Point2f> landmarks() const override { return landmarks_; }

private:
    // The mesh in the square region of side px about centre, turned by angle deg, into landmarks_;
    // false when the network sees no face there.
    bool landmarks_in_region(const cv::Mat &frame, const cv::Point2f &centre, double angle, float side);

    ModelSpec spec_;
    cv::dnn::Net net_;
    std::vector<cv::Point3f> canonical_;
    std::vector<cv::Point2f> landmarks_;  // the last estimate's, px in the frame
    std::vector<cv::Point3f> rigid_canonical_;  // the rigid upper face, for the position
    std::vector<int> rigid_;
    float front_z_ = 0.f;  // cm: the canonical face's front-most point (the nose tip)
    double last_px_per_cm_ = 0.0;  // the last estimate's face scale, px per cm (0: none, or it failed)
};

}  // namespace hkf_estimator
