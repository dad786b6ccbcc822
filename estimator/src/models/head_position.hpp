// head_position.hpp - where the head is (cm, camera frame), from the same camera:
// the face mesh's fit (a translation from solvePnP on the rigid upper face,
// moved back to the point the head turns about), or, for a model that gives
// only angles, the face box and an average face size.
//
// Camera frame (docs/programs.md: "Angle convention"): x to the image's right, y up, z the
// distance along the optical axis (> 0). The focal length comes from the
// camera's diagonal field of view (--fov; opentrack's default 56 deg).
#pragma once

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

namespace hkf_estimator {

struct HeadPosition {
    float x = 0.f, y = 0.f, z = 0.f;  // cm, camera frame (above)
};

struct PositionSettings {
    double fov_deg = 56.0;      // the camera's diagonal field of view
    double pivot_cm = 10.0;     // the point the head turns about: this far behind the nose tip
    // the face box's width on a real face, for the box fallback: BlazeFace's box at the mesh's
    // distance (docs/estimator.md "Head position"; test_head_position)
    double box_face_width_cm = 13.3;
};

// Focal length in px of a camera with this diagonal field of view at this frame size.
double focal_from_fov(const cv::Size &frame, double fov_deg);

// The canonical face's points that do not move with the mouth and jaw: those
// above the nose tip's level less 1.5 cm (eyes, brows, forehead, nose, upper cheeks).
std::vector<int> rigid_points(const std::vector<cv::Point3f> &canonical);

// The pivot's position: the face model's pose in the camera (solvePnP's rvec,
// tvec: OpenCV axes, the model's units cm) applied to the pivot point, which
// is pivot_cm behind the model's front-most point along its forward (+z) axis.
HeadPosition position_from_fit(const cv::Vec3d &rvec, const cv::Vec3d &tvec, float front_z_cm, double pivot_cm);

// A fitted position, and the face's scale in the image at its front point (focal / that point's
// distance, px per cm), which no turn changes; 0 when that point is not in front of the camera.
struct PositionFit {
    HeadPosition position;
    double px_per_cm = 0.0;
};

// The mesh's position: the rigid canonical points (cm) fitted to their landmarks (px) by
// solvePnP (SQPNP) with the camera of settings.fov_deg, moved to the pivot. None when the
// fit fails or gives no finite position in front of the camera.
std::optional<PositionFit> fit_position(const std::vector<cv::Point3f> &rigid_canonical,
                                        const std::vector<cv::Point2f> &rigid_landmarks, const cv::Size &frame,
                                        const PositionSettings &settings, float front_z_cm);

// The position of a face box on a face face_width_cm wide: the distance from
// its width, x and y from its centre (the face's front), then moved pivot_cm
// behind it, against nose_cv: the direction the nose points in OpenCV's camera
// axes (from the model's angles: head_rotation.hpp).
HeadPosition position_from_box(const cv::Rect2f &box, const cv::Size &frame, double focal_px, double face_width_cm,
                               const cv::Vec3d &nose_cv, double pivot_cm);

}  // namespace hkf_estimator
